// <sb-exercise> in Chromium with WebGPU (SwiftShader), on chapter 2's Beer's-law
// exercise: the statement is typeset at build time, the editor starts from the
// starter code, a correct solution passes the public checks (graded on the GPU by
// the same core as the command line), a syntax error is shown at its line and
// column and moves the cursor there, and the code survives a reload. Above the editor,
// a note says how grading works and which browsers run the checks; Download submission
// saves the editor's code as beer-law.wgsl, the file the grading kits take.
import { readFileSync } from 'node:fs';
import AxeBuilder from '@axe-core/playwright';
import { expect, test, type Locator, type Page } from '@playwright/test';
import { trackErrors, waitForRender } from './support.ts';

const CHAPTER = '/chapters/02-extinction-and-transmittance.html';

const SOLUTION = `fn transmittance(sigmaT: f32, d: f32) -> f32 {
  // Clamp the optical thickness so T stays in [0, 1].
  return exp(-max(sigmaT * d, 0.0));
}
`;

// Line 3 lacks its semicolon: the compiler reports it at line 3 or 4.
const SYNTAX_ERROR = `fn transmittance(sigmaT: f32, d: f32) -> f32 {
  // Beer's law.
  let tau = max(sigmaT * d, 0.0)
  return exp(-tau);
}
`;

/** axe-core's WCAG 2.1 AA rules on the exercise, as book.spec.ts runs them on pages. */
async function axeViolations(page: Page): Promise<string[]> {
  const results = await new AxeBuilder({ page })
    .include('sb-exercise')
    .withTags(['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa'])
    .analyze();
  return results.violations.map(
    (violation) =>
      `${violation.id}: ${violation.nodes.map((node) => node.target.join(' ')).join(', ')}`,
  );
}

async function openExercise(page: Page): Promise<Locator> {
  await page.goto(CHAPTER);
  const widget = page.locator('sb-exercise[exercise="beer-law"]');
  await waitForRender(widget);
  await expect(widget.locator('.cm-content')).toBeVisible();
  return widget;
}

/** Replaces the editor's text the way a paste would. */
async function setCode(page: Page, widget: Locator, code: string): Promise<void> {
  await widget.locator('.cm-content').click();
  await page.keyboard.press('ControlOrMeta+A');
  await page.keyboard.insertText(code);
}

test('a correct solution passes the public checks, and the code survives a reload', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openExercise(page);
  await expect(widget.locator('.sb-exercise-statement .katex').first()).toBeVisible();
  await expect(widget.locator('.cm-content')).toContainText(
    'fn transmittance(sigmaT: f32, d: f32) -> f32',
  );
  await expect(widget.locator('.cm-content')).toHaveAttribute('aria-label', /WGSL code/);
  await expect(widget.locator('.sb-exercise-keyhint')).toContainText('Escape, then Tab');

  await setCode(page, widget, SOLUTION);
  await widget.locator('[data-action="run"]').click();
  await expect(widget).toHaveAttribute('data-state', 'graded', { timeout: 40_000 });
  await expect(widget.locator('.sb-exercise-summary')).toContainText(
    'Public checks passed (2 of 2, 6 of 6 points) — hidden tests run when graded.',
  );
  await expect(widget.locator('.sb-exercise-check[data-verdict="pass"]')).toHaveCount(2);
  // The student's values stand next to the reference's: exp(−1) at d = 1 m.
  const row = widget.locator('.sb-exercise-samples tr', { hasText: 'd = 1 m' }).first();
  await expect(row).toContainText('0.3678');
  await expect(widget.locator('.sb-exercise-figure .sb-plot canvas').first()).toBeVisible();
  await expect(widget.locator('[data-readout="points"]')).toHaveText('6 of 6');
  expect(await axeViolations(page)).toEqual([]);

  await page.reload();
  const again = page.locator('sb-exercise[exercise="beer-law"]');
  await waitForRender(again);
  await expect(again.locator('.cm-content')).toContainText('exp(-max(sigmaT * d, 0.0))');
  await expect(again.locator('.sb-exercise-summary')).toContainText('public checks passed');
  expect(errors).toEqual([]);
});

test('the note says how grading works and which browsers run the checks; Download submission saves beer-law.wgsl', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openExercise(page);
  const note = widget.locator('.sb-exercise-grading');
  await expect(note).toContainText('Run checks runs the public checks here');
  await expect(note).toContainText('same public checks and hidden ones');
  await expect(note).toContainText('Download submission and hand in the file beer-law.wgsl');
  for (const browser of ['Chrome or Edge', 'Safari 26', 'Firefox 141'])
    await expect(note).toContainText(browser);
  await expect(note).toContainText('Without WebGPU you can write, save and download your code');
  await expect(widget.locator('.sb-exercise-gpu-status')).toHaveText(
    'This browser has WebGPU: the checks run here.',
  );
  // Said before the student writes code: the note sits above the editor.
  const noteBox = await note.boundingBox();
  const editorBox = await widget.locator('.cm-editor').boundingBox();
  expect(noteBox && editorBox && noteBox.y + noteBox.height <= editorBox.y).toBe(true);

  await setCode(page, widget, SOLUTION);
  const download = page.waitForEvent('download');
  await widget.locator('[data-action="download"]').click();
  const file = await download;
  expect(file.suggestedFilename()).toBe('beer-law.wgsl');
  expect(readFileSync(await file.path(), 'utf8')).toBe(SOLUTION);
  await expect(widget.locator('.sb-notice--info')).toContainText(
    'Saved your code as beer-law.wgsl',
  );
  expect(await axeViolations(page)).toEqual([]);
  expect(errors).toEqual([]);
});

test('a syntax error is shown at its line and column, and a click moves the cursor there', async ({
  page,
}) => {
  const widget = await openExercise(page);
  await setCode(page, widget, SYNTAX_ERROR);
  await widget.locator('[data-action="run"]').click();
  await expect(widget).toHaveAttribute('data-state', 'compile-error', { timeout: 40_000 });
  await expect(widget.locator('.sb-exercise-summary')).toContainText('does not compile');
  const diagnostic = widget.locator('.sb-exercise-diagnostic').first();
  await expect(diagnostic).toHaveText(/^line [34], column \d+: /);
  await expect(widget.locator('.cm-lintRange-error')).not.toHaveCount(0);
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  await diagnostic.click();
  await expect(widget.locator('.cm-activeLine')).toHaveText(/let tau|return exp/);
  await expect(widget.locator('.cm-content')).toBeFocused();
  await page.emulateMedia({ colorScheme: 'dark' });
  expect(await axeViolations(page)).toEqual([]);
});

test('without WebGPU: a notice, and the editor, hints, saving, export, import and reset still work', async ({
  page,
}) => {
  // This project has WebGPU; hide it from the page as a browser without it would.
  await page.addInitScript(() => {
    Object.defineProperty(Navigator.prototype, 'gpu', { get: () => undefined });
  });
  const errors = trackErrors(page);
  const widget = await openExercise(page);
  await expect(widget.locator('.sb-notice--warning')).toContainText('WebGPU is not available');
  await expect(widget.locator('.sb-notice--warning')).toContainText(
    'running the checks needs WebGPU',
  );
  await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
  await expect(widget.locator('[data-action="run"]')).toBeDisabled();
  await expect(widget.locator('.sb-exercise-gpu-status')).toHaveText(
    /^This browser cannot run them: this browser has no WebGPU/,
  );
  await setCode(page, widget, SOLUTION);
  // Downloading the submission needs no GPU.
  const saved = page.waitForEvent('download');
  await widget.locator('[data-action="download"]').click();
  expect((await saved).suggestedFilename()).toBe('beer-law.wgsl');
  expect(readFileSync(await (await saved).path(), 'utf8')).toBe(SOLUTION);
  await widget.locator('[data-action="hint"]').click();
  await expect(widget.locator('.sb-exercise-hints li')).toHaveCount(1);
  await page.reload();
  const again = page.locator('sb-exercise[exercise="beer-law"]');
  await waitForRender(again);
  await expect(again.locator('.cm-content')).toContainText('exp(-max(sigmaT * d, 0.0))');
  await expect(again.locator('[data-action="hint"]')).toHaveText('Show a hint (1 of 3 shown)');

  // Export writes every exercise's code to a file; importing a broken file says why.
  const download = page.waitForEvent('download');
  await again.locator('[data-action="export"]').click();
  const file = await (await download).path();
  const exported = JSON.parse(readFileSync(file, 'utf8')) as {
    format: string;
    exercises: Record<string, { code: string }>;
  };
  expect(exported.format).toBe('scatterbook-exercise-progress');
  expect(exported.exercises['beer-law']?.code).toContain('exp(-max(sigmaT * d, 0.0))');
  await again.locator('input[type="file"]').setInputFiles({
    name: 'progress.json',
    mimeType: 'application/json',
    buffer: Buffer.from(
      '{"format":"scatterbook-exercise-progress","version":1,"exercises":{"beer-law":{"code":5}}}',
    ),
  });
  await expect(again.locator('.sb-notice--error')).toContainText(
    'Nothing was imported. exercise “beer-law”: “code” must be text',
  );
  exported.exercises['beer-law'] = { ...exported.exercises['beer-law'], code: '// imported\n' };
  await again.locator('input[type="file"]').setInputFiles({
    name: 'progress.json',
    mimeType: 'application/json',
    buffer: Buffer.from(JSON.stringify(exported)),
  });
  await expect(again.locator('.cm-content')).toHaveText('// imported');

  // Reset asks first, then restores the starter.
  page.once('dialog', (dialog) => void dialog.accept());
  await again.locator('[data-action="reset"]').click();
  await expect(again.locator('.cm-content')).toContainText('return 1.0;');
  expect(errors).toEqual([]);
});
