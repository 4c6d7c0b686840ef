// <sb-delta-tracking> in Chromium with WebGPU (SwiftShader): it draws a non-blank
// transmittance image and variance image, changing the estimator changes the
// picture and the numbers (the biased exp(−τ̂) is flagged), a too-low majorant
// biases delta tracking high, the state round-trips through the URL,
// presentation mode and presets work, the sweep completes and can be cancelled,
// and without WebGPU the float64 twin draws at reduced resolution and says so.
import { expect, test, type Locator, type Page } from '@playwright/test';
import { canvasStats, parseDisplayed, trackErrors, waitForRender } from './support.ts';

const CHAPTER = '/chapters/06-unbiased-transmittance.html';
const ID = 'delta-tracking-1';

async function openWidget(
  page: Page,
  state: Record<string, string> = {},
  query = '',
): Promise<Locator> {
  const hash = Object.entries(state)
    .map(([k, v]) => `${ID}.${k}=${v}`)
    .join('&');
  await page.goto(`${CHAPTER}${query}${hash ? `#${hash}` : ''}`);
  const widget = page.locator('sb-delta-tracking').first();
  await waitForRender(widget);
  return widget;
}

async function readout(widget: Locator, key: string): Promise<string> {
  return (await widget.locator(`[data-readout="${key}"]`).textContent()) ?? '';
}

function control(widget: Locator, name: string): Locator {
  return widget.locator(`input[type="number"][name="${name}"], select[name="${name}"]`);
}

test('draws a non-blank image and variance image on the GPU, with RMSE, bias, lookups and time', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page);
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
  expect(errors).toEqual([]);
});

test('switching to the biased exp(−τ̂) changes the picture and the numbers, and the bias is flagged', async ({
  page,
}) => {
  const widget = await openWidget(page, { spp: '16' });
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
  expect(page.url()).toContain('estimator=biased');
});

test('a majorant that is too low biases delta tracking high (physics.md §4.5)', async ({
  page,
}) => {
  const widget = await openWidget(page, { spp: '16', majorant: 'low' });
  await expect.poll(() => readout(widget, 'bias')).toContain('biased');
  // Twin: +0.09 at spp = 4.
  expect(parseDisplayed(await readout(widget, 'bias'))).toBeGreaterThan(0.05);
  const rendered = Number(await widget.getAttribute('data-rendered'));
  await control(widget, 'estimator').selectOption('ratio');
  await waitForRender(widget, rendered + 1);
  await expect.poll(() => readout(widget, 'bias')).not.toContain('biased');
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

test('presentation mode: F enters, number keys recall the presets, Esc leaves', async ({
  page,
}) => {
  const widget = await openWidget(page);
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

test('the sweep completes with RMSE ∝ spp^−½ for delta tracking, and can be cancelled', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page);
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
  expect(errors).toEqual([]);
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
