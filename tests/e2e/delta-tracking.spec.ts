// <sb-delta-tracking> in Chromium with WebGPU (SwiftShader): it draws a non-blank
// transmittance image and variance image, changing the estimator changes the
// picture and the numbers (the biased exp(−τ̂) is flagged), a too-low majorant
// biases delta tracking high, the state round-trips through the URL,
// presentation mode and presets work, the sweep completes and can be cancelled,
// and without WebGPU the float64 twin draws at reduced resolution and says so.
// The comparison view (view=compare): ten labelled images (equal samples, equal
// time), the variance toggle, the sweep of all five estimators (five series,
// cancellable), deep links, presentation mode and the CPU fallback.
import { expect, test, type Locator, type Page } from '@playwright/test';
import {
  canvasStats,
  parseDisplayed,
  readout,
  toggleTheme,
  trackErrors,
  waitForRender,
  widgetAxeViolations,
  widgetOpener,
} from './support.ts';

const CHAPTER = '/chapters/06-unbiased-transmittance.html';
const ID = 'delta-tracking-1';

const openWidget = widgetOpener(CHAPTER, 'sb-delta-tracking', ID);

function control(widget: Locator, name: string): Locator {
  return widget.locator(`input[type="number"][name="${name}"], select[name="${name}"]`);
}

// One page load for the single view as the chapter opens it: its pictures and readouts,
// the sweep and its cancel, then presentation mode and the presets.
test('draws a non-blank image and variance image on the GPU, with RMSE, bias, lookups and time; the sweep gives RMSE ∝ spp^−½ for delta tracking and can be cancelled; presentation mode and its presets', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page);
  await test.step('a non-blank image and variance image, with RMSE, bias, lookups and time', async () => {
    const canvases = widget.locator('canvas.sb-canvas');
    await expect(canvases).toHaveCount(2);
    const image = await canvasStats(canvases.first());
    expect(image.luminanceDeviation).toBeGreaterThan(10);
    expect(image.distinctColours).toBeGreaterThan(5);
    const variance = await canvasStats(canvases.nth(1));
    expect(variance.distinctColours).toBeGreaterThan(5);
    await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
    // Twin at 128×80, spp = 4: RMSE 0.15 and 1.4 lookups per estimate.
    const rmse = parseDisplayed(await readout(widget, 'rmse'));
    expect(rmse).toBeGreaterThan(0.05);
    expect(rmse).toBeLessThan(0.3);
    const lookups = parseDisplayed(await readout(widget, 'lookups'));
    expect(lookups).toBeGreaterThan(1);
    expect(lookups).toBeLessThan(2);
    expect(parseDisplayed(await readout(widget, 'variance-scale'))).toBeGreaterThan(0);
    expect(await readout(widget, 'bias')).not.toContain('biased');
    expect(await readout(widget, 'time')).toMatch(/GPU timestamp query|wall time/);
    await expect(widget.locator('.sb-notice--warning')).toHaveCount(0);
  });
  await test.step('the sweep completes with RMSE ∝ spp^−½ for delta tracking, and can be cancelled', async () => {
    const run = widget.getByRole('button', { name: /Run sweep/ });
    await run.click();
    await expect(widget.locator('.sb-dt-sweep-status')).toContainText('Sweep done', {
      timeout: 60_000,
    });
    await expect(widget.locator('progress')).toHaveJSProperty('value', 9);
    const p = parseDisplayed(await readout(widget, 'slope'));
    expect(p).toBeLessThan(-0.4);
    expect(p).toBeGreaterThan(-0.6);
    await expect(widget.locator('.sb-plot .u-over')).toBeVisible();
    await run.click();
    await widget.getByRole('button', { name: 'Cancel' }).click();
    await expect(widget.locator('.sb-dt-sweep-status')).toContainText('cancelled');
    await expect(run).toBeEnabled();
  });
  await test.step('presentation mode: F enters, number keys recall the presets, Esc leaves', async () => {
    await widget.locator('input[type="range"]').first().focus();
    await page.keyboard.press('f');
    const shell = widget.locator('.sb-widget');
    await expect(shell).toHaveClass(/is-presenting/);
    await expect(widget.locator('canvas.sb-canvas').first()).toBeInViewport();
    await page.keyboard.press('2');
    await expect(widget.locator('.sb-preset-toast')).toHaveText('2 · ratio tracking');
    await expect(control(widget, 'estimator')).toHaveValue('ratio');
    await page.keyboard.press('4');
    await expect(control(widget, 'estimator')).toHaveValue('delta');
    await expect(control(widget, 'majorant')).toHaveValue('low');
    await page.keyboard.press('Escape');
    await expect(shell).not.toHaveClass(/is-presenting/);
  });
  expect(errors).toEqual([]);
});

test('switching to the biased exp(−τ̂) changes the picture and the numbers, and the bias is flagged; a majorant that is too low biases delta tracking high (physics.md §4.5)', async ({
  page,
}) => {
  const widget = await openWidget(page, { spp: '16' });
  await test.step('the biased exp(−τ̂) changes the picture and the numbers, and is flagged', async () => {
    const before = await canvasStats(widget.locator('canvas.sb-canvas').first());
    const deltaRmse = parseDisplayed(await readout(widget, 'rmse'));
    const rendered = Number(await widget.getAttribute('data-rendered'));
    await control(widget, 'estimator').selectOption('biased');
    await waitForRender(widget, rendered + 1);
    await expect.poll(() => readout(widget, 'bias')).toContain('biased');
    // Twin: mean bias +0.03 (one jittered step, Jensen).
    expect(parseDisplayed(await readout(widget, 'bias'))).toBeGreaterThan(0.01);
    expect(parseDisplayed(await readout(widget, 'rmse'))).not.toBe(deltaRmse);
    expect(parseDisplayed(await readout(widget, 'lookups'))).toBe(1);
    const after = await canvasStats(widget.locator('canvas.sb-canvas').first());
    expect(after.png.equals(before.png)).toBe(false);
    await expect.poll(() => page.url()).toContain('estimator=biased');
  });
  await test.step('a majorant that is too low biases delta tracking high; ratio tracking is not biased by it', async () => {
    // The state of a link with spp = 16 and majorant = low, reached with the controls.
    const rendered = Number(await widget.getAttribute('data-rendered'));
    await control(widget, 'estimator').selectOption('delta');
    await control(widget, 'majorant').selectOption('low');
    await waitForRender(widget, rendered + 1);
    await expect(control(widget, 'spp')).toHaveValue('16');
    await expect.poll(() => readout(widget, 'bias')).toContain('biased');
    // Twin: +0.09 at spp = 4.
    expect(parseDisplayed(await readout(widget, 'bias'))).toBeGreaterThan(0.05);
    const ratioFrom = Number(await widget.getAttribute('data-rendered'));
    await control(widget, 'estimator').selectOption('ratio');
    await waitForRender(widget, ratioFrom + 1);
    await expect.poll(() => readout(widget, 'bias')).not.toContain('biased');
  });
});

test('a deep link restores the state exactly', async ({ page }) => {
  const widget = await openWidget(page, {
    estimator: 'residual',
    spp: '37',
    majorant: 'loose',
    seed: '12345',
  });
  await expect(control(widget, 'estimator')).toHaveValue('residual');
  await expect(control(widget, 'spp')).toHaveValue('37');
  await expect(control(widget, 'majorant')).toHaveValue('loose');
  await expect(control(widget, 'seed')).toHaveValue('12345');
  await expect(widget.locator('.sb-cost')).toContainText('spp = 37 estimates');
});

test('?backend=cpu: the float64 twin draws at reduced resolution and says so', async ({ page }) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page, { estimator: 'biased' }, '?backend=cpu');
  await expect(widget.locator('.sb-notice--warning')).toContainText('WebGPU is not available');
  await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
  const stats = await canvasStats(widget.locator('canvas.sb-canvas').first());
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  expect(parseDisplayed(await readout(widget, 'rmse'))).toBeGreaterThan(0);
  await widget.getByRole('button', { name: /Run sweep/ }).click();
  await expect(widget.locator('.sb-dt-sweep-status')).toContainText('Sweep done', {
    timeout: 60_000,
  });
  // The biased estimator levels off at its bias: far flatter than −½.
  expect(parseDisplayed(await readout(widget, 'slope'))).toBeGreaterThan(-0.35);
  expect(errors).toEqual([]);
});

/**
 * Opens the page with the widget in the comparison view and waits until all ten
 * images are rendered: on SwiftShader the calibration and the ten images (each
 * timed three times) take a few seconds, more on a busy machine.
 */
async function openComparison(
  page: Page,
  state: Record<string, string> = {},
  query = '',
): Promise<Locator> {
  const hash = Object.entries({ view: 'compare', ...state })
    .map(([k, v]) => `${ID}.${k}=${v}`)
    .join('&');
  await page.goto(`${CHAPTER}${query}#${hash}`);
  const widget = page.locator('sb-delta-tracking').first();
  await widget.scrollIntoViewIfNeeded();
  await waitForComparison(widget);
  return widget;
}

/** Waits until the comparison has rendered all ten images for the current settings. */
async function waitForComparison(widget: Locator): Promise<void> {
  await expect(widget.locator('.sb-dt-compare-status')).toContainText('Equal time: budget', {
    timeout: 90_000,
  });
  await expect(widget.locator('.sb-dt-compare')).not.toHaveAttribute('aria-busy', 'true');
}

async function cellSpp(widget: Locator, row: 'samples' | 'time'): Promise<number[]> {
  return widget
    .locator(`.sb-dt-row[data-row="${row}"] canvas.sb-canvas`)
    .evaluateAll((canvases) => canvases.map((c) => Number((c as HTMLElement).dataset['spp'])));
}

test('compare view: ten non-blank labelled images, equal samples and equal time; the grid switches to per-pixel variance without re-rendering, delta tracking near T(1 − T)', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openComparison(page, { spp: '8' });
  await test.step('ten non-blank labelled images, equal samples and equal time', async () => {
    const canvases = widget.locator('.sb-dt-cell canvas.sb-canvas');
    await expect(canvases).toHaveCount(10);
    for (let i = 0; i < 10; i++) {
      const stats = await canvasStats(canvases.nth(i));
      expect(stats.luminanceDeviation).toBeGreaterThan(5);
      expect(stats.distinctColours).toBeGreaterThan(5);
    }
    // Every image says what it is, as text under it and to screen readers.
    const captions = widget.locator('.sb-dt-cell figcaption');
    await expect(captions).toHaveCount(10);
    for (const text of await captions.allTextContents()) {
      expect(text).toMatch(/spp \d+ · [\d.]+ (ms|µs)/);
      expect(text).toContain('RMSE');
      expect(text).toContain('bias');
    }
    await expect(canvases.first()).toHaveAttribute('aria-label', /biased exp\(−τ̂\), equal samples/);
    // Equal samples: all at the chosen spp. Equal time: the reference (delta
    // tracking) keeps it, the others get the spp their measured cost allows.
    expect(await cellSpp(widget, 'samples')).toEqual([8, 8, 8, 8, 8]);
    const timeSpp = await cellSpp(widget, 'time');
    expect(timeSpp[1]).toBe(8);
    expect(new Set(timeSpp).size).toBeGreaterThan(1);
    await expect(widget.locator('.sb-dt-row[data-row="time"] .sb-dt-row-title')).toContainText(
      'the time of delta tracking at spp = 8',
    );
    // The biased estimator is flagged in both rows; the unbiased ones are not.
    const biasedCells = widget.locator('.sb-dt-cell[data-estimator="biased"] .sb-dt-biased');
    await expect(biasedCells).toHaveCount(2);
    await expect(
      widget.locator('.sb-dt-cell:not([data-estimator="biased"]) .sb-dt-biased'),
    ).toHaveCount(0);
    // Readouts: the budget, the cost per sample and lookups of each estimator.
    await expect(widget.locator('[data-readout="budget"]')).toContainText('delta tracking × spp 8');
    expect(parseDisplayed(await readout(widget, 'lookups-urm'))).toBeGreaterThan(5);
    expect(parseDisplayed(await readout(widget, 'lookups-biased'))).toBe(1);
    await expect(widget.locator('[data-readout="cost-ratio"]')).toContainText(/ms|µs/);
    await expect(widget.locator('[data-readout="timing"]')).toHaveText(
      /GPU timestamp query|wall time/,
    );
    // The single view's pictures and readouts are not in the document meanwhile.
    await expect(widget.locator('[data-readout="rmse"]')).toHaveCount(0);
  });
  await test.step('the grid switches to per-pixel variance without re-rendering', async () => {
    const status = await widget.locator('.sb-dt-compare-status').textContent();
    const before = await canvasStats(widget.locator('.sb-dt-cell canvas.sb-canvas').nth(1));
    const rendered = Number(await widget.getAttribute('data-rendered'));
    await control(widget, 'grid').selectOption('variance');
    await waitForRender(widget, rendered + 1);
    await expect(widget.locator('.sb-dt-legend')).toContainText('Variance of one estimate');
    const after = await canvasStats(widget.locator('.sb-dt-cell canvas.sb-canvas').nth(1));
    expect(after.png.equals(before.png)).toBe(false);
    expect(after.distinctColours).toBeGreaterThan(5);
    // The same images, repainted: the measured times did not change.
    await expect(widget.locator('.sb-dt-compare-status')).toHaveText(status ?? '');
    // Delta tracking's variance per sample is T(1 − T), 0.0950 averaged over the image.
    const caption = await widget
      .locator('.sb-dt-row[data-row="samples"] .sb-dt-cell[data-estimator="delta"] figcaption')
      .textContent();
    const meanVariance = parseDisplayed(/mean Var (\S+)/.exec(caption ?? '')?.[1] ?? '');
    expect(meanVariance).toBeGreaterThan(0.085);
    expect(meanVariance).toBeLessThan(0.105);
    await expect.poll(() => page.url()).toContain('grid=variance');
  });
  expect(errors).toEqual([]);
});

test('a deep link #…view=compare restores the comparison and its settings', async ({ page }) => {
  const widget = await openComparison(page, {
    grid: 'variance',
    estimator: 'ratio',
    spp: '8',
    majorant: 'loose',
  });
  await expect(control(widget, 'view')).toHaveValue('compare');
  await expect(control(widget, 'grid')).toHaveValue('variance');
  await expect(control(widget, 'grid')).toBeVisible();
  await expect(control(widget, 'estimator')).toHaveValue('ratio');
  await expect(control(widget, 'majorant')).toHaveValue('loose');
  await expect(widget.locator('.sb-dt-legend')).toContainText('Variance of one estimate');
  expect(await cellSpp(widget, 'samples')).toEqual([8, 8, 8, 8, 8]);
  expect((await cellSpp(widget, 'time'))[2]).toBe(8);
  await expect(widget.locator('.sb-dt-row[data-row="time"] .sb-dt-row-title')).toContainText(
    'the time of ratio tracking at spp = 8',
  );
  await expect(widget.locator('.sb-cost')).toContainText('loose majorant');
  // Back to one estimator: its two pictures return and the grid setting hides.
  const rendered = Number(await widget.getAttribute('data-rendered'));
  await control(widget, 'view').selectOption('single');
  await waitForRender(widget, rendered + 1);
  await expect(widget.locator('canvas.sb-canvas')).toHaveCount(2);
  await expect(control(widget, 'grid')).toBeHidden();
  await expect.poll(() => page.url()).not.toContain('view=compare');
});

test('?backend=cpu, compare view: the float64 twin draws all ten images and says so', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openComparison(page, {}, '?backend=cpu');
  await expect(widget.locator('.sb-notice--warning')).toContainText('CPU wall time');
  await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
  await expect(widget.locator('[data-readout="timing"]')).toHaveText('CPU wall time');
  const canvases = widget.locator('.sb-dt-cell canvas.sb-canvas');
  await expect(canvases).toHaveCount(10);
  for (let i = 0; i < 10; i++)
    expect((await canvasStats(canvases.nth(i))).luminanceDeviation).toBeGreaterThan(5);
  expect(errors).toEqual([]);
});

// One comparison page for the sweep of all five estimators, then (with a majorant that
// is too low, so the biased flags and warnings are on screen) a cancelled sweep, the
// accessibility check in both themes, and presentation mode.
test('compare view: the sweep of all five estimators draws five series with fitted slopes, and can be cancelled; axe-core in both themes after a sweep; presentation mode fills the screen with readable captions', async ({
  page,
}) => {
  test.setTimeout(300_000);
  const errors = trackErrors(page);
  await page.emulateMedia({ colorScheme: 'light' });
  const widget = await openComparison(page);
  const run = widget.getByRole('button', { name: /Sweep all five/ });
  await test.step('the sweep of all five estimators draws five series with fitted slopes, and can be cancelled', async () => {
    await run.click();
    await expect(widget.locator('.sb-dt-sweepall-status')).toContainText('Sweep done', {
      timeout: 150_000,
    });
    await expect(widget.locator('progress')).toHaveJSProperty('value', 45);
    const legend = widget.locator('.sb-plot .u-legend .u-series');
    // uPlot's legend lists x first, then one entry per series.
    await expect(legend).toHaveCount(6);
    const labels = (await legend.allTextContents()).slice(1);
    for (const name of [
      'biased exp(−τ̂)',
      'delta tracking',
      'ratio tracking',
      'residual ratio tracking',
      'unbiased ray marching',
    ])
      expect(labels.some((label) => label.includes(name) && /p = -?[\d.]+/.test(label))).toBe(true);
    for (const key of ['biased', 'delta', 'ratio', 'residual', 'urm'])
      expect(Number.isFinite(parseDisplayed(await readout(widget, `slope-${key}`)))).toBe(true);
    // Against spp (no timing in it): −½ for the unbiased four, a plateau for exp(−τ̂).
    for (const key of ['delta', 'ratio', 'residual', 'urm']) {
      const p = parseDisplayed(await readout(widget, `spp-slope-${key}`));
      expect(p).toBeGreaterThan(-0.6);
      expect(p).toBeLessThan(-0.4);
    }
    expect(parseDisplayed(await readout(widget, 'spp-slope-biased'))).toBeGreaterThan(-0.2);
    await run.click();
    await expect(widget.locator('.sb-dt-sweepall-status')).toContainText('of 45');
    await widget.getByRole('button', { name: 'Cancel' }).click();
    await expect(widget.locator('.sb-dt-sweepall-status')).toContainText('cancelled');
    await expect(run).toBeEnabled();
    expect(
      await widget.locator('progress').evaluate((p: HTMLProgressElement) => p.value),
    ).toBeLessThan(45);
  });
  await test.step('axe-core after a cancelled sweep with a majorant that is too low: every WCAG 2.1 AA rule in the light theme, the colour rules in the dark', async () => {
    const rendered = Number(await widget.getAttribute('data-rendered'));
    await control(widget, 'majorant').selectOption('low');
    await waitForRender(widget, rendered + 1);
    await waitForComparison(widget);
    await run.click();
    await expect(widget.locator('.sb-dt-sweepall-status')).toContainText('of 45');
    await widget.getByRole('button', { name: 'Cancel' }).click();
    await expect(widget.locator('.sb-dt-sweepall-status')).toContainText('cancelled');
    expect(
      await widgetAxeViolations(page, 'sb-delta-tracking', {
        tags: ['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa'],
      }),
      'light theme',
    ).toEqual([]);
    await toggleTheme(page, 'dark');
    expect(
      await widgetAxeViolations(page, 'sb-delta-tracking', { colourOnly: true }),
      'dark theme',
    ).toEqual([]);
  });
  await test.step('presentation mode: the grid fills the screen with readable captions', async () => {
    await widget.locator('select[name="view"]').focus();
    await page.keyboard.press('f');
    await expect(widget.locator('.sb-widget')).toHaveClass(/is-presenting/);
    await expect(widget.locator('.sb-dt-cell canvas.sb-canvas').first()).toBeInViewport();
    const size = await widget
      .locator('.sb-dt-cell figcaption')
      .first()
      .evaluate((el) => parseFloat(getComputedStyle(el).fontSize));
    expect(size).toBeGreaterThanOrEqual(16);
    // Five images side by side in a row at 1280 px.
    const boxes = await widget
      .locator('.sb-dt-row[data-row="samples"] canvas.sb-canvas')
      .evaluateAll((canvases) => canvases.map((c) => c.getBoundingClientRect().top));
    expect(new Set(boxes.map(Math.round)).size).toBe(1);
    await page.keyboard.press('Escape');
    await expect(widget.locator('.sb-widget')).not.toHaveClass(/is-presenting/);
  });
  expect(errors).toEqual([]);
});
