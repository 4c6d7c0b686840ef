// <sb-raymarch-steps> in Chromium with WebGPU (SwiftShader): it draws a non-blank
// image and error image, changing the placement changes the picture and the RMSE
// (midpoint beats left at the same N), the linear update at N = 4 is flagged, the
// state round-trips through the URL, presentation mode and presets work, the
// sweep completes with a fitted order and can be cancelled, and without WebGPU the
// float64 twin draws at reduced resolution and says so.
import { expect, test, type Locator } from '@playwright/test';
import {
  canvasStats,
  parseDisplayed,
  readout,
  trackErrors,
  waitForRender,
  widgetOpener,
  widgetPictureOpener,
} from './support.ts';

const CHAPTER = '/chapters/05-emission-absorption-and-ray-marching.html';
const ID = 'raymarch-steps-1';

const openWidget = widgetOpener(CHAPTER, 'sb-raymarch-steps', ID);
/** Opens the chapter waiting for the first picture only (for controls and the cost line). */
const openPicture = widgetPictureOpener(CHAPTER, 'sb-raymarch-steps', ID);

function control(widget: Locator, name: string): Locator {
  return widget.locator(`input[type="number"][name="${name}"], select[name="${name}"]`);
}

// One page load for the chapter's figure and what a reader does with it next: loading
// the chapter and refining its pictures on SwiftShader is most of each test's time, so
// the placements, the presets in presentation mode and the linear update share it, each
// in its own step, reaching their states with the controls and the preset keys.
test('draws a non-blank image and error image on the GPU; midpoint beats left at the same N; presentation mode and its presets; the linear update at N = 4 clamps and says so, exact never does', async ({
  page,
}) => {
  test.setTimeout(180_000);
  const errors = trackErrors(page);
  const widget = await openWidget(page);
  await test.step('a non-blank image and error image, with RMSE, time and the error scale', async () => {
    const canvases = widget.locator('canvas.sb-canvas');
    await expect(canvases).toHaveCount(2);
    const image = await canvasStats(canvases.nth(0));
    expect(image.luminanceDeviation).toBeGreaterThan(10);
    expect(image.distinctColours).toBeGreaterThan(20);
    const error = await canvasStats(canvases.nth(1));
    expect(error.distinctColours).toBeGreaterThan(5);
    await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
    await expect(widget.locator('.sb-cost')).toContainText('N = 1024');
    expect(parseDisplayed(await readout(widget, 'rmse'))).toBeGreaterThan(0);
    expect(parseDisplayed(await readout(widget, 'error-scale'))).toBeGreaterThan(0);
    expect(await readout(widget, 'time')).toMatch(/GPU timestamp query|wall time/);
    await expect(widget.locator('.sb-notice--warning')).toHaveCount(0);
  });
  await test.step('midpoint samples beat left samples at the same N, and the picture changes', async () => {
    let rendered = Number(await widget.getAttribute('data-rendered'));
    await control(widget, 'steps').fill('8');
    await control(widget, 'steps').press('Enter');
    await control(widget, 'placement').selectOption('left');
    await waitForRender(widget, rendered + 1);
    await expect(widget.locator('.sb-cost')).toContainText('N = 8 steps');
    await expect(control(widget, 'placement')).toHaveValue('left');
    const left = parseDisplayed(await readout(widget, 'rmse'));
    const before = await canvasStats(widget.locator('canvas.sb-canvas').nth(1));
    rendered = Number(await widget.getAttribute('data-rendered'));
    await control(widget, 'placement').selectOption('midpoint');
    await waitForRender(widget, rendered + 1);
    // Twin at 32×20: 7.6e-2 (left) vs 4.6e-3 (midpoint); at least 5× here.
    await expect
      .poll(async () => parseDisplayed(await readout(widget, 'rmse')))
      .toBeLessThan(left / 5);
    const after = await canvasStats(widget.locator('canvas.sb-canvas').nth(1));
    expect(after.png.equals(before.png)).toBe(false);
    await expect.poll(() => page.url()).toContain('placement=midpoint');
  });
  await test.step('presentation mode: F enters, number keys recall the presets, Esc leaves', async () => {
    await widget.locator('input[type="range"]').first().focus();
    await page.keyboard.press('f');
    const shell = widget.locator('.sb-widget');
    await expect(shell).toHaveClass(/is-presenting/);
    await expect(widget.locator('canvas.sb-canvas').first()).toBeInViewport();
    await page.keyboard.press('1');
    await expect(control(widget, 'placement')).toHaveValue('left');
    await page.keyboard.press('2');
    await expect(widget.locator('.sb-preset-toast')).toHaveText('2 · midpoint, N = 8');
    await expect(control(widget, 'placement')).toHaveValue('midpoint');
    await page.keyboard.press('4');
    await expect(control(widget, 'update')).toHaveValue('linear');
    await expect(control(widget, 'steps')).toHaveValue('4');
    await page.keyboard.press('Escape');
    await expect(shell).not.toHaveClass(/is-presenting/);
  });
  await test.step('the linear update at N = 4 clamps negative factors and says so; exact never does', async () => {
    await waitForRender(widget);
    await expect(widget.locator('.sb-notice--warning')).toContainText('linear update failed');
    expect(parseDisplayed(await readout(widget, 'clamped'))).toBeGreaterThan(0);
    const rendered = Number(await widget.getAttribute('data-rendered'));
    await control(widget, 'update').selectOption('exact');
    await waitForRender(widget, rendered + 1);
    await expect(widget.locator('.sb-notice--warning')).toHaveCount(0);
    await expect.poll(() => readout(widget, 'clamped')).toContain('exact update');
  });
  expect(errors).toEqual([]);
});

test('a deep link restores the state exactly', async ({ page }) => {
  // Controls and the cost line are the same in every refinement stage: the first picture is enough.
  const widget = await openPicture(page, {
    steps: '37',
    placement: 'jittered-strata',
    update: 'exact',
    density: '2.5',
    seed: '12345',
  });
  await expect(control(widget, 'steps')).toHaveValue('37');
  await expect(control(widget, 'placement')).toHaveValue('jittered-strata');
  await expect(control(widget, 'density')).toHaveValue('2.5');
  await expect(control(widget, 'seed')).toHaveValue('12345');
  await expect(widget.locator('.sb-cost')).toContainText('N = 37 steps');
});

test('the sweep completes with a fitted order near 2 for midpoint samples, and can be cancelled', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page, { placement: 'midpoint' });
  const run = widget.getByRole('button', { name: /Run sweep/ });
  await run.click();
  await expect(widget.locator('.sb-rm-sweep-status')).toContainText('Sweep done', {
    timeout: 60_000,
  });
  await expect(widget.locator('progress')).toHaveJSProperty('value', 9);
  const slope = await readout(widget, 'slope');
  // Twin: p = −1.98 over N = 1 … 256; f32 noise only matters near N = 256.
  const p = parseDisplayed(slope);
  expect(p).toBeLessThan(-1.6);
  expect(p).toBeGreaterThan(-2.4);
  await expect(widget.locator('.sb-plot .u-over')).toBeVisible();
  await run.click();
  await widget.getByRole('button', { name: 'Cancel' }).click();
  await expect(widget.locator('.sb-rm-sweep-status')).toContainText('cancelled');
  await expect(run).toBeEnabled();
  expect(errors).toEqual([]);
});

test('?backend=cpu: the float64 twin draws at reduced resolution and says so', async ({ page }) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page, { steps: '8' }, '?backend=cpu');
  await expect(widget.locator('.sb-notice--warning')).toContainText('WebGPU is not available');
  await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
  const stats = await canvasStats(widget.locator('canvas.sb-canvas').first());
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  expect(parseDisplayed(await readout(widget, 'rmse'))).toBeGreaterThan(0);
  await widget.getByRole('button', { name: /Run sweep/ }).click();
  await expect(widget.locator('.sb-rm-sweep-status')).toContainText('Sweep done', {
    timeout: 60_000,
  });
  expect(parseDisplayed(await readout(widget, 'slope'))).toBeLessThan(-0.7);
  expect(errors).toEqual([]);
});
