// <sb-hg-lobe> in Chromium with WebGPU (SwiftShader): it draws the lobe, its
// controls change the picture and the numbers, its readouts agree with the closed
// forms of physics.md §2.2 (normalisation, peak values, mean cosine = g) and its
// histogram passes the chi-square test, its state round-trips through the URL,
// presentation mode and the presets work from the keyboard, and without WebGPU
// (or after a device loss) it falls back to the CPU twin and says so.
import AxeBuilder from '@axe-core/playwright';
import { expect, test, type Locator, type Page } from '@playwright/test';
import {
  canvasStats,
  displayedDigits,
  parseDisplayed,
  trackErrors,
  waitForRender,
} from './support.ts';

const CHAPTER = '/chapters/03-phase-functions-and-in-scattering.html';

/** The number of the first deck slide that shows <sb-hg-lobe> (the deck is data, slides may be added). */
async function lobeSlide(page: Page): Promise<number> {
  await page.goto('/deck.html');
  const id = await page.locator('.deck-slide:has(sb-hg-lobe)').first().getAttribute('id');
  const number = Number(/^slide-(\d+)$/.exec(id ?? '')?.[1]);
  expect(number).toBeGreaterThan(0);
  return number;
}

/** Opens the first hg-lobe slide with `state` (parameter → value) in its hash. */
async function openSlide(page: Page, state: Record<string, string> = {}): Promise<Locator> {
  const slide = await lobeSlide(page);
  const id = `slide-${slide}-widget`;
  const hash = [`slide=${slide}`, ...Object.entries(state).map(([k, v]) => `${id}.${k}=${v}`)];
  await page.goto(`/deck.html#${hash.join('&')}`);
  await page.reload();
  const widget = page.locator(`#${id}`);
  await waitForRender(widget);
  return widget;
}

async function readout(widget: Locator, key: string): Promise<string> {
  return (await widget.locator(`[data-readout="${key}"]`).textContent()) ?? '';
}

function controlValue(widget: Locator, name: string): Locator {
  return widget.locator(`input[type="number"][name="${name}"], select[name="${name}"]`);
}

/** HG at μ = ±1 (physics.md §2.2): p(1) = (1+g)/(4π(1−g)²), p(−1) = (1−g)/(4π(1+g)²). */
function hgPeak(g: number, forward: boolean): number {
  return forward ? (1 + g) / (4 * Math.PI * (1 - g) ** 2) : (1 - g) / (4 * Math.PI * (1 + g) ** 2);
}

/** The readouts a student checks: ∫p dω = 1, mean cosine within 5 SE of g, χ² passes. */
async function expectSoundNumbers(widget: Locator, g: number): Promise<void> {
  // The quadrature of the float64 twin is good to 1e-12; ten decimals are shown.
  expect(Math.abs(parseDisplayed(await readout(widget, 'normalisation')) - 1)).toBeLessThan(1e-9);
  const mean = await readout(widget, 'mean-cosine');
  const match = /(-?[\d.]+) ± ([\d.]+(?:×10[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)?)/.exec(mean);
  expect(match, mean).not.toBeNull();
  const sampleMean = Number(match?.[1]);
  const standardError = parseDisplayed(match?.[2] ?? '');
  // 5 SE: two-sided p ≈ 6e-7 for a correct sampler (a fixed seed makes it deterministic).
  expect(Math.abs(sampleMean - g)).toBeLessThan(5 * standardError);
  await expect(widget.locator('[data-readout="mean-cosine"]')).toHaveClass(/sb-ok/);
  await expect(widget.locator('[data-readout="chi-square"]')).toContainText('passes at α = 0.01');
  await expect(widget.locator('[data-readout="chi-square"]')).toContainText('critical');
}

test('draws a non-blank lobe on the GPU and reports the GPU cost next to the CPU twin', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openSlide(page);
  const stats = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  expect(stats.distinctColours).toBeGreaterThan(20);
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  await expect(widget.locator('.sb-cost')).toContainText('float64 twin on the CPU');
  await expect(widget.locator('.sb-notice--warning')).toHaveCount(0);
  await expect(widget.locator('.sb-plot canvas').first()).toBeVisible();
  await expect(widget.locator('.sb-hg-labels')).toContainText('incident beam');
  expect(errors).toEqual([]);
});

test('the readouts agree with physics.md §2.2: ∫p dω = 1, the peak values, ⟨μ⟩ = g, χ² passes', async ({
  page,
}) => {
  const widget = await openSlide(page, { g: '0.6', samples: '16', seed: '1' });
  const g = Math.fround(0.6);
  for (const [key, forward] of [
    ['forward', true],
    ['backward', false],
  ] as const) {
    const text = await readout(widget, key);
    const exact = hgPeak(g, forward);
    expect(parseDisplayed(text)).toBe(Number(exact.toPrecision(displayedDigits(text))));
  }
  await expectSoundNumbers(widget, g);
  // N = 2^16 on the GPU and the CPU twin replaying the same streams.
  await expect(widget.locator('.sb-cost')).toContainText('65536 samples');
  await expect(widget.locator('[data-readout="replay"]')).toHaveClass(/sb-ok/);
});

test('moving g changes the picture, the numbers and the URL', async ({ page }) => {
  const widget = await openSlide(page, { g: '0.6' });
  const before = await canvasStats(widget.locator('canvas.sb-canvas'));
  const forwardBefore = await readout(widget, 'forward');
  const rendered = Number(await widget.getAttribute('data-rendered'));
  const slider = widget.locator('input[type="range"][name="g"]');
  await slider.focus();
  for (let i = 0; i < 20; i++) await page.keyboard.press('ArrowRight');
  await waitForRender(widget, rendered + 1);
  await expect(controlValue(widget, 'g')).toHaveValue('0.8');
  await expect.poll(() => readout(widget, 'forward')).not.toBe(forwardBefore);
  await expect
    .poll(async () => parseDisplayed(await readout(widget, 'forward')))
    .toBeCloseTo(hgPeak(Math.fround(0.8), true), 3);
  const after = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(after.png.equals(before.png)).toBe(false);
  expect(page.url()).toContain('g=0.8');
  await expectSoundNumbers(widget, Math.fround(0.8));
});

test('a deep link restores the state exactly', async ({ page }) => {
  const widget = await openSlide(page, {
    g: '-0.5',
    compare: 'rayleigh',
    scale: 'log',
    samples: '12',
    seed: '42',
  });
  await expect(controlValue(widget, 'g')).toHaveValue('-0.5');
  await expect(controlValue(widget, 'compare')).toHaveValue('rayleigh');
  await expect(controlValue(widget, 'scale')).toHaveValue('log');
  await expect(controlValue(widget, 'samples')).toHaveValue('12');
  await expect(controlValue(widget, 'seed')).toHaveValue('42');
  // physics.md §2.2 table: g = −0.5 gives p(μ = 1) = 0.0176838825657661 sr⁻¹.
  const forward = await readout(widget, 'forward');
  expect(parseDisplayed(forward)).toBe(
    Number((0.0176838825657661).toPrecision(displayedDigits(forward))),
  );
  await expect(widget.locator('.sb-cost')).toContainText('4096 samples');
  await expect(widget.locator('.sb-hg-labels')).toContainText('outline: Rayleigh');
  await expectSoundNumbers(widget, -0.5);
});

test('invalid values are clamped and the widget says so', async ({ page }) => {
  const errors = trackErrors(page);
  const widget = await openSlide(page, { g: '5', scale: 'spiral' });
  await expect(controlValue(widget, 'g')).toHaveValue('0.99');
  // An unknown choice falls back to the schema default.
  await expect(controlValue(widget, 'scale')).toHaveValue('linear');
  const warnings = widget.locator('.sb-notice--warning');
  await expect(warnings).toHaveCount(2);
  await expect(warnings.first()).toContainText('clamped');
  const stats = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  expect(errors).toEqual([]);
});

test('presentation mode: F enters and fills the screen, number keys recall the presets, Esc leaves', async ({
  page,
}) => {
  const widget = await openSlide(page);
  await widget.locator('input[type="range"]').first().focus();
  await page.keyboard.press('f');
  const shell = widget.locator('.sb-widget');
  await expect(shell).toHaveClass(/is-presenting/);
  const box = await shell.boundingBox();
  expect(box?.width).toBeGreaterThan(1200);
  expect(box?.height).toBeGreaterThan(850);
  expect(page.url()).toContain('present=1');
  await expect(widget.locator('canvas.sb-canvas')).toBeInViewport();
  await page.keyboard.press('4');
  await expect(widget.locator('.sb-preset-toast')).toHaveText('4 · g = 0.9 (clouds)');
  await expect(controlValue(widget, 'g')).toHaveValue('0.9');
  await page.keyboard.press('5');
  await expect(controlValue(widget, 'g')).toHaveValue('0');
  await expect(controlValue(widget, 'compare')).toHaveValue('rayleigh');
  await expect.poll(() => readout(widget, 'forward')).toContain('0.0795775');
  await page.keyboard.press('Escape');
  await expect(shell).not.toHaveClass(/is-presenting/);
  await widget.getByRole('button', { name: 'Present' }).click();
  await expect(shell).toHaveClass(/is-presenting/);
  await widget.getByRole('button', { name: 'Exit presentation' }).click();
  await expect(shell).not.toHaveClass(/is-presenting/);
});

test('?backend=cpu: the CPU twin draws the same lobe and computes the same numbers, and says so', async ({
  page,
}) => {
  const errors = trackErrors(page);
  await page.goto(`${CHAPTER}?backend=cpu#hg-lobe-1.g=0.3&hg-lobe-1.samples=14&hg-lobe-1.seed=3`);
  const widget = page.locator('sb-hg-lobe').first();
  await waitForRender(widget);
  await expect(widget.locator('.sb-notice--warning')).toContainText('WebGPU is not available');
  await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
  await expect(widget.locator('.sb-cost')).toContainText('16384 samples');
  const stats = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  // physics.md §2.2 table: g = 0.3 gives p(μ = 1) = 0.211123904101494 sr⁻¹.
  const forward = await readout(widget, 'forward');
  expect(parseDisplayed(forward)).toBe(
    Number((0.211123904101494).toPrecision(displayedDigits(forward))),
  );
  await expectSoundNumbers(widget, Math.fround(0.3));
  expect(errors).toEqual([]);
});

test('the CPU fallback’s histogram is the GPU’s: the same mean cosine to the displayed digits', async ({
  page,
}) => {
  const state = '#hg-lobe-1.g=0.6&hg-lobe-1.samples=15&hg-lobe-1.seed=9';
  await page.goto(`${CHAPTER}${state}`);
  const gpuWidget = page.locator('sb-hg-lobe').first();
  await waitForRender(gpuWidget);
  await expect(gpuWidget.locator('.sb-cost')).toContainText('WebGPU');
  const gpuMean = parseDisplayed(await readout(gpuWidget, 'mean-cosine'));
  await page.goto(`${CHAPTER}?backend=cpu${state}`);
  const cpuWidget = page.locator('sb-hg-lobe').first();
  await waitForRender(cpuWidget);
  await expect(cpuWidget.locator('.sb-cost')).toContainText('CPU fallback');
  const cpuMean = parseDisplayed(await readout(cpuWidget, 'mean-cosine'));
  // The same PCG streams: the means differ only by f32 rounding of μ (≲ 3e-7 per
  // sample) and of the partial sums, far below the 5 displayed digits' 1e-5.
  expect(Math.abs(gpuMean - cpuMean)).toBeLessThanOrEqual(1e-5);
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
  const widget = await openSlide(page);
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  await page.evaluate(() => (window as unknown as { testDevice: GPUDevice }).testDevice.destroy());
  await expect(widget.locator('.sb-notice--warning')).toContainText('device was lost');
  await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
  const stats = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  expect(errors).toEqual([]);
});

test('passes an axe accessibility check in both themes (labelled controls, contrast of the labels)', async ({
  page,
}) => {
  for (const colorScheme of ['light', 'dark'] as const) {
    await page.emulateMedia({ colorScheme });
    const widget = await openSlide(page, { scale: 'log' });
    await expect(widget.locator('.sb-hg-labels')).toContainText('10');
    const results = await new AxeBuilder({ page })
      .include(`#${await widget.getAttribute('id')}`)
      .analyze();
    expect(results.violations.map((v) => `${v.id}: ${v.help}`)).toEqual([]);
  }
});
