// <sb-beer-law> in Chromium with WebGPU (SwiftShader): it draws, its controls
// change the picture and the numbers, its numbers match Beer's law, its state
// round-trips through the URL, and presentation mode works from the keyboard.
import { expect, test, type Page } from '@playwright/test';
import {
  canvasStats,
  displayedDigits,
  parseDisplayed,
  trackErrors,
  waitForRender,
} from './support.ts';

const CHAPTER = '/chapters/02-extinction-and-transmittance.html';

async function firstWidget(page: Page, hash = '') {
  await page.goto(`${CHAPTER}${hash}`);
  const widget = page.locator('sb-beer-law').first();
  await waitForRender(widget);
  return widget;
}

async function readout(widget: ReturnType<Page['locator']>, key: string): Promise<string> {
  return (await widget.locator(`[data-readout="${key}"]`).textContent()) ?? '';
}

function controlValue(widget: ReturnType<Page['locator']>, name: string) {
  return widget.locator(`input[type="number"][name="${name}"], select[name="${name}"]`);
}

test('draws a non-blank beam on the GPU and reports GPU cost', async ({ page }) => {
  const errors = trackErrors(page);
  const widget = await firstWidget(page);
  const stats = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  expect(stats.distinctColours).toBeGreaterThan(20);
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  await expect(widget.locator('.sb-notice--warning')).toHaveCount(0);
  await expect(widget.locator('.sb-plot canvas').first()).toBeVisible();
  expect(errors).toEqual([]);
});

test('T at the exit equals exp(−σt·d) to the displayed digits', async ({ page }) => {
  const widget = await firstWidget(page);
  const sigmaA = Number(await controlValue(widget, 'sigma-a').inputValue());
  const sigmaS = Number(await controlValue(widget, 'sigma-s').inputValue());
  const thickness = Number(await controlValue(widget, 'thickness').inputValue());
  await controlValue(widget, 'profile').selectOption('homogeneous');
  await waitForRender(widget, 2);
  const text = await readout(widget, 'exit');
  const shown = parseDisplayed(text);
  const exact = Math.exp(-(sigmaA + sigmaS) * thickness);
  const digits = displayedDigits(text);
  expect(Number(exact.toPrecision(digits))).toBe(shown);
});

test('moving a control changes the picture and the numbers, and the URL', async ({ page }) => {
  const widget = await firstWidget(page);
  const before = await canvasStats(widget.locator('canvas.sb-canvas'));
  const exitBefore = await readout(widget, 'exit');
  const rendered = Number(await widget.getAttribute('data-rendered'));
  const slider = widget.locator('input[type="range"][name="sigma-a"]');
  await slider.focus();
  for (let i = 0; i < 60; i++) await page.keyboard.press('ArrowRight');
  await waitForRender(widget, rendered + 1);
  await expect.poll(() => readout(widget, 'exit')).not.toBe(exitBefore);
  const after = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(after.png.equals(before.png)).toBe(false);
  await expect.poll(() => page.url()).toContain('sigma-a=');
});

test('a deep link restores the state exactly', async ({ page }) => {
  const widget = await firstWidget(
    page,
    '#beer-law-1.sigma-a=1.5&beer-law-1.thickness=3&beer-law-1.profile=layered',
  );
  await expect(controlValue(widget, 'sigma-a')).toHaveValue('1.5');
  await expect(controlValue(widget, 'thickness')).toHaveValue('3');
  await expect(controlValue(widget, 'profile')).toHaveValue('layered');
  const reference = parseDisplayed(await readout(widget, 'reference'));
  const gpu = parseDisplayed(await readout(widget, 'exit'));
  expect(Math.abs(gpu - reference)).toBeLessThan(1e-5 * Math.max(reference, 1e-30) + 1e-12);
  await expect(widget.locator('[data-readout="split-check"]')).toContainText('holds');
});

test('invalid values are clamped and the widget says so', async ({ page }) => {
  const errors = trackErrors(page);
  const widget = await firstWidget(
    page,
    '#beer-law-1.sigma-a=-5&beer-law-1.profile=spiral&beer-law-1.thickness=abc',
  );
  await expect(controlValue(widget, 'sigma-a')).toHaveValue('0');
  await expect(controlValue(widget, 'profile')).toHaveValue('homogeneous');
  const warnings = widget.locator('.sb-notice--warning');
  await expect(warnings).toHaveCount(3);
  await expect(warnings.first()).toContainText('clamped');
  const stats = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  expect(errors).toEqual([]);
});

test('presentation mode: F enters, the widget fills the screen, number keys recall presets, Esc leaves', async ({
  page,
}) => {
  const widget = await firstWidget(page);
  await widget.locator('input[type="range"]').first().focus();
  await page.keyboard.press('f');
  const shell = widget.locator('.sb-widget');
  await expect(shell).toHaveClass(/is-presenting/);
  const box = await shell.boundingBox();
  expect(box?.width).toBeGreaterThan(1200);
  expect(box?.height).toBeGreaterThan(850);
  await expect.poll(() => page.url()).toContain('present=1');
  await page.keyboard.press('2');
  await expect(controlValue(widget, 'sigma-a')).toHaveValue('1.2');
  await page.keyboard.press('Escape');
  await expect(shell).not.toHaveClass(/is-presenting/);
  await widget.getByRole('button', { name: 'Present' }).click();
  await expect(shell).toHaveClass(/is-presenting/);
  await widget.getByRole('button', { name: 'Exit presentation' }).click();
  await expect(shell).not.toHaveClass(/is-presenting/);
  // Esc in full screen is the browser's: it leaves full screen without passing the key on
  // (Chrome), and presentation mode ends with it. F was a user gesture, so full screen
  // was granted; leaving it from the page stands in for the browser's own Esc. First the
  // full screen the button left has to be gone (a request while it goes is not granted).
  await expect.poll(() => page.evaluate(() => document.fullscreenElement === null)).toBe(true);
  await page.keyboard.press('f');
  await expect(shell).toHaveClass(/is-presenting/);
  await expect
    .poll(() =>
      page.evaluate(() => document.fullscreenElement?.classList.contains('sb-widget') ?? false),
    )
    .toBe(true);
  await page.evaluate(() => document.exitFullscreen());
  await expect(shell).not.toHaveClass(/is-presenting/);
  await expect.poll(() => page.url()).not.toContain('present=1');
  // Esc ends it wherever the focus is (here on the page's body, outside the widget).
  await page.keyboard.press('f');
  await expect(shell).toHaveClass(/is-presenting/);
  await page.evaluate(() => {
    (document.activeElement as HTMLElement | null)?.blur();
  });
  await page.keyboard.press('Escape');
  await expect(shell).not.toHaveClass(/is-presenting/);
});

test('the heterogeneous profile shows the multiplicative property', async ({ page }) => {
  const widget = await firstWidget(
    page,
    '#beer-law-1.profile=smooth&beer-law-1.split=1&beer-law-1.thickness=2&beer-law-1.sigma-a=0.2&beer-law-1.sigma-s=0.8',
  );
  const product = await readout(widget, 'split');
  // T(0→1) = exp(−(1 + 0.8/3·(1 − cos 3))) for σ̄t = 1 (chapter 2's worked example).
  const before = Math.exp(-(1 + (0.8 / 3) * (1 - Math.cos(3))));
  // WGSL lets sin err by 2^-11 absolute and SwiftShader uses that freedom: the
  // f32 optical depth is good to ~5e-4 relative (tests/shaders/transmittance.test.ts).
  expect(Math.abs(parseDisplayed(product) - before) / before).toBeLessThan(5e-4);
  await expect(widget.locator('[data-readout="split-check"]')).toContainText('holds');
});

test('when the GPU device is lost, the widget falls back to the CPU and says so', async ({
  page,
}) => {
  const errors = trackErrors(page);
  // Keep a handle on the page's device so the test can destroy it, as a driver reset would.
  await page.addInitScript(() => {
    const original = GPUAdapter.prototype.requestDevice;
    GPUAdapter.prototype.requestDevice = async function (
      this: GPUAdapter,
      descriptor?: GPUDeviceDescriptor,
    ) {
      const device = await original.call(this, descriptor);
      (window as unknown as { testDevice: GPUDevice }).testDevice = device;
      return device;
    };
  });
  const widget = await firstWidget(page);
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  await page.evaluate(() => (window as unknown as { testDevice: GPUDevice }).testDevice.destroy());
  await expect(widget.locator('.sb-notice--warning')).toContainText('device was lost');
  await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
  const stats = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  expect(errors).toEqual([]);
});
