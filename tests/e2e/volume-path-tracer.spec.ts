// <sb-volume-path-tracer> in Chromium with WebGPU (SwiftShader): both progressive images
// are drawn and not blank, the plan of each render is shown, raising the albedo changes
// the multiple-scattering image more than the single-scattering one, accumulation adds
// samples and lowers the standard error, the reference can be cancelled and the images
// paused, a deep link restores the state, and presentation mode recalls the presets.
// SwiftShader runs WebGPU on the CPU, so frames take seconds: the tests wait on the
// widget's own counters (spp readout, data-rendered), never on wall time.
import { expect, test, type Locator, type Page } from '@playwright/test';
import { PNG } from 'pngjs';
import {
  canvasStats,
  parseDisplayed,
  readout,
  recordStagesFromNextInput,
  trackErrors,
  waitForRender,
  waitForSettled,
} from './support.ts';

const CHAPTER = '/chapters/10-multiple-scattering.html';
const ID = 'volume-path-tracer-1';

test.setTimeout(180_000);

async function openWidget(page: Page, state: Record<string, string> = {}): Promise<Locator> {
  const hash = Object.entries(state)
    .map(([k, v]) => `${ID}.${k}=${v}`)
    .join('&');
  await page.goto(`${CHAPTER}${hash ? `#${hash}` : ''}`);
  const widget = page.locator('sb-volume-path-tracer').first();
  await waitForRender(widget);
  return widget;
}

function control(widget: Locator, name: string): Locator {
  return widget.locator(`input[type="number"][name="${name}"], select[name="${name}"]`);
}

/** Samples per pixel so far (both images get the same number each frame). */
async function spp(widget: Locator): Promise<number> {
  return parseDisplayed(await readout(widget, 'spp'));
}

async function waitForSpp(widget: Locator, atLeast: number): Promise<void> {
  await expect.poll(() => spp(widget), { timeout: 120_000 }).toBeGreaterThanOrEqual(atLeast);
}

/** Mean luminance (0–255) of the middle third of a canvas: the lit medium, not the sky. */
async function centreLuminance(canvas: Locator): Promise<number> {
  const image = PNG.sync.read(await canvas.screenshot());
  let sum = 0;
  let count = 0;
  for (let y = Math.floor(image.height / 3); y < (2 * image.height) / 3; y++)
    for (let x = Math.floor(image.width / 3); x < (2 * image.width) / 3; x++) {
      const i = 4 * (y * image.width + x);
      sum += 0.2126 * image.data[i]! + 0.7152 * image.data[i + 1]! + 0.0722 * image.data[i + 2]!;
      count++;
    }
  return sum / count;
}

test('draws both images on the GPU, non-blank, with the plan, the readouts and the frame cost', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page);
  const canvases = widget.locator('canvas.sb-canvas');
  await expect(canvases).toHaveCount(2);
  await waitForSpp(widget, 8);
  for (const k of [0, 1]) {
    const stats = await canvasStats(canvases.nth(k));
    expect(stats.luminanceDeviation).toBeGreaterThan(10);
    expect(stats.distinctColours).toBeGreaterThan(20);
  }
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  await expect(widget.locator('[data-readout="plan-single"]')).toContainText(
    'single-scattering estimator',
  );
  await expect(widget.locator('[data-readout="plan-multiple"]')).toContainText(
    'volumetric path tracing',
  );
  expect(await readout(widget, 'frame')).toMatch(/GPU timestamp query|wall time/);
  expect(Number(await widget.getAttribute('data-frame-ms'))).toBeGreaterThan(0);
  // Multiple scattering adds light: at α = 0.9, τ = 8 the ratio is about 4.5.
  expect(parseDisplayed(await readout(widget, 'ratio'))).toBeGreaterThan(2);
  expect(await readout(widget, 'capped')).toBe('0');
  await expect(widget.locator('.sb-notice--warning')).toHaveCount(0);
  expect(errors).toEqual([]);
});

test('accumulation adds samples and lowers the standard error', async ({ page }) => {
  const widget = await openWidget(page, { spp: '2' });
  await waitForSpp(widget, 4);
  const early = await spp(widget);
  const earlyError = parseDisplayed(await readout(widget, 'stderr-multiple'));
  await waitForSpp(widget, early + 8);
  const laterError = parseDisplayed(await readout(widget, 'stderr-multiple'));
  // The standard error falls as 1/√n; from n to n + 8 ≥ 3n it falls by ≥ 1.7 in
  // expectation. Require a clear drop with room for the noise of the estimate itself.
  expect(laterError).toBeLessThan(earlyError * 0.8);
  await expect(widget.locator('figcaption').nth(1)).toContainText('spp');
});

test('raising the albedo changes the multiple-scattering image more than the single', async ({
  page,
}) => {
  const widget = await openWidget(page, { albedo: '0.5', spp: '8' });
  await waitForSpp(widget, 16);
  const canvases = widget.locator('canvas.sb-canvas');
  const singleBefore = await centreLuminance(canvases.nth(0));
  const multipleBefore = await centreLuminance(canvases.nth(1));
  const ratioBefore = parseDisplayed(await readout(widget, 'ratio'));
  const albedo = control(widget, 'albedo');
  const stagesShown = await recordStagesFromNextInput(widget, albedo);
  await albedo.fill('0.99');
  await albedo.press('Enter');
  // The input restarts both images: its first frame starts the new albedo's run, a preview
  // of at most a frame's 8 spp where the old run had 16 or more (the readout after it
  // counts the new run, whose frames need not pass through exactly 8 or 16).
  await expect
    .poll(async () => (await stagesShown())[0] ?? '', { timeout: 60_000 })
    .toMatch(/^(Preview: )?\d+ of \d+ spp/);
  const first = (await stagesShown())[0] ?? '';
  expect(Number(/(\d+) of/.exec(first)?.[1]), first).toBeLessThanOrEqual(8);
  await waitForSpp(widget, 16);
  const singleAfter = await centreLuminance(canvases.nth(0));
  const multipleAfter = await centreLuminance(canvases.nth(1));
  expect(multipleAfter - multipleBefore).toBeGreaterThan(2 * (singleAfter - singleBefore));
  expect(multipleAfter).toBeGreaterThan(multipleBefore + 20);
  expect(parseDisplayed(await readout(widget, 'ratio'))).toBeGreaterThan(ratioBefore);
  await expect.poll(() => page.url()).toContain('albedo=0.99');
});

test('switching to the puffy cloud shows a preview first, then settles; the old scene stops', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page);
  // Every stage label the widget shows from the input on, in order (data-stage, set per frame).
  const scene = control(widget, 'scene');
  const stagesShown = await recordStagesFromNextInput(widget, scene);
  await scene.selectOption('cloud');
  await waitForSettled(widget, 120_000);
  const stages = await stagesShown();
  // The first frame after the input is the new scene's preview (fewer samples than a
  // frame's 4: the sphere's count did not carry on), then a whole frame settles it.
  expect(stages[0]).toMatch(/^Preview: [1-3] of 4 spp$/);
  // Settled, and still accumulating at low priority: the stage line says so.
  expect(await widget.getAttribute('data-stage')).toMatch(/^\d+ of 1024 spp$/);
  await expect(widget.locator('[data-readout="stage"]')).toHaveText(
    /^\d+ of 1024 spp · accumulating$/,
  );
  expect(parseDisplayed(await readout(widget, 'spp'))).toBeGreaterThanOrEqual(4);
  await expect(widget.locator('[data-readout="plan-multiple"]')).toContainText('majorant grid');
  expect(parseDisplayed(await readout(widget, 'lookups'))).toBeGreaterThan(0);
  expect(errors).toEqual([]);
});

test('pause stops the accumulation and the reference can be cancelled', async ({ page }) => {
  const widget = await openWidget(page);
  await expect(widget.locator('.sb-vpt-reference-status')).toContainText('Computing the reference');
  await widget.getByRole('button', { name: 'Cancel reference' }).click();
  await expect(widget.locator('.sb-vpt-reference-status')).toContainText('Reference cancelled');
  await expect(widget.getByRole('button', { name: 'Compute reference' })).toBeVisible();
  await widget.getByRole('button', { name: 'Pause' }).click();
  await expect(widget.getByRole('button', { name: 'Resume' })).toBeVisible();
  const paused = await spp(widget);
  // A frame already in flight may still land (it takes seconds on SwiftShader); wait
  // until the count holds still, then check that it stays put.
  let settled = paused;
  await expect
    .poll(
      async () => {
        const before = await spp(widget);
        await page.waitForTimeout(2000);
        settled = await spp(widget);
        return settled === before;
      },
      { timeout: 60_000 },
    )
    .toBe(true);
  await page.waitForTimeout(3000);
  expect(await spp(widget)).toBe(settled);
  expect(settled - paused).toBeLessThanOrEqual(4);
  await widget.getByRole('button', { name: 'Resume' }).click();
  await waitForSpp(widget, settled + 1);
});

test('a deep link restores the state exactly', async ({ page }) => {
  // Written as an old link: `density` is the former name of optical-thickness.
  const widget = await openWidget(page, {
    scene: 'cloud',
    albedo: '0.75',
    g: '0.3',
    density: '12',
    spp: '3',
  });
  await expect(control(widget, 'scene')).toHaveValue('cloud');
  await expect(control(widget, 'albedo')).toHaveValue('0.75');
  await expect(control(widget, 'g')).toHaveValue('0.3');
  await expect(control(widget, 'optical-thickness')).toHaveValue('12');
  await expect(control(widget, 'spp')).toHaveValue('3');
  await expect(widget.locator('[data-readout="plan-multiple"]')).toContainText('majorant grid');
  await waitForSpp(widget, 3);
  expect(parseDisplayed(await readout(widget, 'lookups'))).toBeGreaterThan(0);
});

test('presentation mode: F enters, number keys recall the presets, Esc leaves', async ({
  page,
}) => {
  const widget = await openWidget(page);
  await widget.locator('input[type="range"]').first().focus();
  await page.keyboard.press('f');
  const shell = widget.locator('.sb-widget');
  await expect(shell).toHaveClass(/is-presenting/);
  await expect(widget.locator('canvas.sb-canvas').first()).toBeInViewport();
  await page.keyboard.press('1');
  await expect(widget.locator('.sb-preset-toast')).toHaveText('1 · white cloud (α = 0.99)');
  await expect(control(widget, 'albedo')).toHaveValue('0.99');
  await page.keyboard.press('4');
  await expect(control(widget, 'scene')).toHaveValue('cloud');
  await page.keyboard.press('Escape');
  await expect(shell).not.toHaveClass(/is-presenting/);
});
