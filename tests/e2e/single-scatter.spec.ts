// <sb-single-scatter> in Chromium with WebGPU (SwiftShader): it draws a non-blank
// single-scattering image and lists the plan, switching in-scattering off changes the
// picture and marks the skipped effects as skipped, the progressive accumulation raises
// the samples per pixel and (against the cached reference) lowers the error readout,
// the kernels are timed against each other, a deep link restores the state, and
// presentation mode works with the presets. The targets are small (16–32 spp) because
// SwiftShader runs the kernel on the CPU.
import { expect, test, type Locator, type Page } from '@playwright/test';
import {
  canvasStats,
  parseDisplayed,
  recordStagesFromNextInput,
  trackErrors,
  waitForRender,
  waitForSettled,
} from './support.ts';

const CHAPTER = '/chapters/09-single-scattering.html';
const ID = 'single-scatter-1';

async function openWidget(page: Page, state: Record<string, string> = {}): Promise<Locator> {
  const hash = Object.entries(state)
    .map(([k, v]) => `${ID}.${k}=${v}`)
    .join('&');
  await page.goto(`${CHAPTER}${hash ? `#${hash}` : ''}`);
  const widget = page.locator('sb-single-scatter').first();
  await waitForRender(widget);
  return widget;
}

function control(widget: Locator, name: string): Locator {
  return widget.locator(`input[type="number"][name="${name}"], select[name="${name}"]`);
}

function planRow(widget: Locator, effect: string): Locator {
  return widget.locator(`.sb-ss-plan tr[data-effect="${effect}"]`);
}

async function spp(widget: Locator): Promise<number> {
  return Number((await widget.getAttribute('data-spp')) ?? '0');
}

/** Waits until the image has `target` spp and the reference for it is complete. */
async function waitConverged(widget: Locator, target: number): Promise<number> {
  await expect
    .poll(
      async () =>
        (await spp(widget)) >= target &&
        (await widget.getAttribute('data-reference-done')) === 'true',
      { timeout: 150_000, intervals: [1000] },
    )
    .toBe(true);
  await expect.poll(() => widget.getAttribute('data-error')).not.toBeNull();
  return Number(await widget.getAttribute('data-error'));
}

test('draws a non-blank image, its standard error and the plan on the GPU', async ({ page }) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page, { spp: '16' });
  await expect.poll(() => spp(widget), { timeout: 60_000 }).toBeGreaterThanOrEqual(4);
  const canvases = widget.locator('canvas.sb-canvas');
  await expect(canvases).toHaveCount(2);
  const image = await canvasStats(canvases.first());
  expect(image.luminanceDeviation).toBeGreaterThan(10);
  expect(image.distinctColours).toBeGreaterThan(10);
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  await expect(widget.locator('.sb-ss-plan caption')).toContainText('single-scattering');
  await expect(planRow(widget, 'shadow rays')).toHaveAttribute('data-enabled', 'true');
  await expect(planRow(widget, 'equiangular sampling')).toHaveAttribute('data-enabled', 'true');
  await expect(planRow(widget, 'emission')).toHaveAttribute('data-enabled', 'false');
  await expect(planRow(widget, 'emission').locator('td').first()).toHaveText('skipped');
  expect(Number(await widget.getAttribute('data-frame-ms'))).toBeGreaterThan(0);
  await expect(widget).toHaveAttribute('data-frame-timer', /GPU|wall time/);
  expect(errors).toEqual([]);
});

test('switching in-scattering off changes the picture and marks effects as skipped', async ({
  page,
}) => {
  const widget = await openWidget(page, { spp: '16' });
  await expect.poll(() => spp(widget), { timeout: 60_000 }).toBeGreaterThanOrEqual(4);
  const before = await canvasStats(widget.locator('canvas.sb-canvas').first());
  await control(widget, 'scattering').selectOption('off');
  await expect(planRow(widget, 'in-scattering')).toHaveAttribute('data-enabled', 'false');
  await expect(planRow(widget, 'in-scattering').locator('td').first()).toHaveText('skipped');
  await expect(planRow(widget, 'phase functions')).toHaveAttribute('data-enabled', 'false');
  // The floor still reflects the spot light: its shadow rays stay compiled.
  await expect(planRow(widget, 'shadow rays')).toHaveAttribute('data-enabled', 'true');
  await expect.poll(() => spp(widget), { timeout: 60_000 }).toBeGreaterThanOrEqual(4);
  const after = await canvasStats(widget.locator('canvas.sb-canvas').first());
  expect(after.png.equals(before.png)).toBe(false);
  // Without the lit fog the picture is mostly black: far less variation.
  expect(after.luminanceDeviation).toBeLessThan(before.luminanceDeviation);

  // Floor and occluder off as well: nothing scatters, shadow rays and lights are skipped.
  await control(widget, 'floor').selectOption('off');
  await control(widget, 'occluder').selectOption('none');
  await expect(widget.locator('.sb-ss-plan caption')).toContainText('emission-absorption');
  await expect(planRow(widget, 'shadow rays')).toHaveAttribute('data-enabled', 'false');
  await expect(planRow(widget, 'spot lights')).toHaveAttribute('data-enabled', 'false');
});

test('accumulation raises spp and lowers the error; the kernels are timed', async ({ page }) => {
  test.setTimeout(400_000);
  const errors = trackErrors(page);
  // 16 then 32 spp (references of 128 and 256 spp): the smallest targets the control
  // allows, and four snapshots (4…32 spp) for the fitted slope.
  const widget = await openWidget(page, { spp: '16' });
  const first = await waitConverged(widget, 16);
  expect(first).toBeGreaterThan(0);
  await expect(widget.locator('[data-readout="error"]')).not.toContainText('waiting');
  // Specialized against general kernel: both times and variances, and a saving.
  await expect
    .poll(() => widget.getAttribute('data-general-ms'), { timeout: 60_000 })
    .not.toBeNull();
  expect(Number(await widget.getAttribute('data-plan-ms'))).toBeGreaterThan(0);
  expect(Number(await widget.getAttribute('data-plan-variance'))).toBeGreaterThan(0);
  await expect(widget.locator('[data-readout="saved"]')).toContainText('%');

  // A higher target: the same accumulation and reference go on.
  const input = control(widget, 'spp');
  await input.fill('32');
  await input.press('Enter');
  const second = await waitConverged(widget, 32);
  expect(await spp(widget)).toBe(32);
  // 2× the samples (and 2× the reference's): the RMSE should fall by √2, to 0.71; the
  // RMSE over 64² pixels varies by a few per cent, so 0.85 leaves room for chance.
  expect(second).toBeLessThan(0.85 * first);
  // The fitted slope of log RMSE against log spp (4 … 32 spp) is near −½; loose bounds,
  // since the reference's own noise flattens it a little.
  const slope = parseDisplayed(
    (await widget.locator('[data-readout="slope"]').textContent()) ?? '',
  );
  expect(slope).toBeLessThan(-0.25);
  expect(slope).toBeGreaterThan(-0.8);
  expect(errors).toEqual([]);
});

test('a deep link restores the state', async ({ page }) => {
  const widget = await openWidget(page, {
    light: 'directional',
    occluder: 'box',
    'sigma-s': '1.25',
    g: '-0.2',
    emission: 'on',
    spp: '32',
  });
  await expect(control(widget, 'light')).toHaveValue('directional');
  await expect(control(widget, 'occluder')).toHaveValue('box');
  await expect(control(widget, 'sigma-s')).toHaveValue('1.25');
  await expect(control(widget, 'g')).toHaveValue('-0.2');
  await expect(control(widget, 'emission')).toHaveValue('on');
  await expect(control(widget, 'spp')).toHaveValue('32');
  await expect(planRow(widget, 'directional lights')).toHaveAttribute('data-enabled', 'true');
  await expect(planRow(widget, 'emission')).toHaveAttribute('data-enabled', 'true');
  await expect(planRow(widget, 'equiangular sampling')).toHaveAttribute('data-enabled', 'false');
});

test('presentation mode: F enters, number keys recall the presets, Esc leaves', async ({
  page,
}) => {
  const widget = await openWidget(page, { spp: '16' });
  await widget.locator('input[type="range"]').first().focus();
  await page.keyboard.press('f');
  const shell = widget.locator('.sb-widget');
  await expect(shell).toHaveClass(/is-presenting/);
  await expect(widget.locator('canvas.sb-canvas').first()).toBeInViewport();
  await page.keyboard.press('2');
  await expect(control(widget, 'light')).toHaveValue('directional');
  await expect(control(widget, 'occluder')).toHaveValue('box');
  await expect(planRow(widget, 'directional lights')).toHaveAttribute('data-enabled', 'true');
  await page.keyboard.press('4');
  await expect(control(widget, 'scattering')).toHaveValue('off');
  await expect(widget.locator('.sb-ss-plan caption')).toContainText('emission-absorption');
  await page.keyboard.press('Escape');
  await expect(shell).not.toHaveClass(/is-presenting/);
});

test('an input shows a one-pass preview of the new scene first, then refines', async ({ page }) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page, { spp: '16' });
  const occluder = control(widget, 'occluder');
  const stagesShown = await recordStagesFromNextInput(widget, occluder);
  await occluder.selectOption('box');
  await waitForSettled(widget, 120_000);
  const stages = await stagesShown();
  // The preview is the new run's first pass (the old scene's samples did not carry on);
  // the next frame adds passes and the reference for the new scene starts.
  expect(stages[0]).toBe('Preview: 1 of 16 spp');
  expect(stages.at(-1)).toMatch(/^\d+ of 16 spp/);
  expect(Number(await widget.getAttribute('data-spp'))).toBeGreaterThan(1);
  expect(errors).toEqual([]);
});
