// <sb-vre-ray> in Chromium with WebGPU (SwiftShader): it draws the ray, its
// readouts agree with the exact integral form of the VRE (chapter 4,
// L = (1 − α)Le(1 − T) + αL_in(1 − T) + T·L_bg), its controls change the picture
// and the numbers, its state round-trips through the URL, presentation mode and
// the presets work from the keyboard, and with ?backend=cpu it falls back to the
// float64 march and says so.
import { expect, test, type Locator, type Page } from '@playwright/test';
import {
  canvasStats,
  displayedDigits,
  parseDisplayed,
  readout,
  trackErrors,
  waitForRender,
} from './support.ts';

const CHAPTER = '/chapters/04-the-volume-rendering-equation.html';

async function openChapter(page: Page, query = '', hash = ''): Promise<Locator> {
  await page.goto(`${CHAPTER}${query}${hash ? `#${hash}` : ''}`);
  const widget = page.locator('sb-vre-ray').first();
  await waitForRender(widget);
  return widget;
}

function controlValue(widget: Locator, name: string): Locator {
  return widget.locator(`input[type="number"][name="${name}"], select[name="${name}"]`);
}

/** Chapter 4's exact form for σt = σ0(1 + 0.8 sin 3s): τ = σ0 d + 0.8 σ0 (1 − cos 3d)/3. */
function exactL(
  sigma: number,
  albedo: number,
  le: number,
  lin: number,
  bg: number,
  d: number,
): number {
  const f = Math.fround;
  const [s, a, e, q, b, l] = [f(sigma), f(albedo), f(le), f(lin), f(bg), f(d)];
  const T = Math.exp(-(s * l + (0.8 * s * (1 - Math.cos(3 * l))) / 3));
  return ((1 - a) * e + a * q) * (1 - T) + T * b;
}

/** The readouts a student checks: the exact value to its displayed digits, and the GPU (or CPU) march close to it. */
async function expectSoundNumbers(widget: Locator, exact: number, budget: number): Promise<void> {
  const reference = await readout(widget, 'reference');
  expect(parseDisplayed(reference)).toBe(Number(exact.toPrecision(displayedDigits(reference))));
  // 1024 midpoint steps: |τ̂ − τ| ≤ d·h²·σ0·0.8·9/24 (≤ 2e-5 here), plus WGSL sin and f32 rounding
  // (see tests/shaders/vre-ray-kernel.test.ts); `budget` is that bound relative to L.
  const total = parseDisplayed(await readout(widget, 'total'));
  expect(Math.abs(total - exact) / exact).toBeLessThan(budget);
  expect(parseDisplayed(await readout(widget, 'error'))).toBeLessThan(budget);
}

test('draws a non-blank ray on the GPU and reports L next to the exact integral form and the GPU cost', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openChapter(page);
  const stats = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  expect(stats.distinctColours).toBeGreaterThan(20);
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  await expect(widget.locator('.sb-cost')).toContainText('1024 midpoint steps');
  await expect(widget.locator('.sb-notice--warning')).toHaveCount(0);
  await expect(widget.locator('.sb-plot canvas').first()).toBeVisible();
  // Chapter 4's worked example: L = 0.480343 radiance units.
  await expectSoundNumbers(widget, exactL(1, 0.5, 0.5, 0.3, 1, 2), 1e-3);
  expect(errors).toEqual([]);
});

test('moving σ0 changes the picture, the numbers and the URL', async ({ page }) => {
  const widget = await openChapter(page);
  const before = await canvasStats(widget.locator('canvas.sb-canvas'));
  const totalBefore = await readout(widget, 'total');
  const rendered = Number(await widget.getAttribute('data-rendered'));
  const slider = widget.locator('input[type="range"][name="sigma"]');
  await slider.focus();
  for (let i = 0; i < 50; i++) await page.keyboard.press('ArrowRight');
  await waitForRender(widget, rendered + 1);
  await expect(controlValue(widget, 'sigma')).toHaveValue('1.5');
  await expect.poll(() => readout(widget, 'total')).not.toBe(totalBefore);
  await expect
    .poll(async () => parseDisplayed(await readout(widget, 'reference')))
    .toBeCloseTo(exactL(1.5, 0.5, 0.5, 0.3, 1, 2), 5);
  const after = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(after.png.equals(before.png)).toBe(false);
  await expect.poll(() => page.url()).toContain('sigma=1.5');
});

test('a deep link restores the state exactly', async ({ page }) => {
  const widget = await openChapter(
    page,
    '',
    'vre-ray-1.sigma=3&vre-ray-1.albedo=0.2&vre-ray-1.emission=1.5&vre-ray-1.inscatter=0&vre-ray-1.background=2&vre-ray-1.length=0.5',
  );
  await expect(controlValue(widget, 'sigma')).toHaveValue('3');
  await expect(controlValue(widget, 'albedo')).toHaveValue('0.2');
  await expect(controlValue(widget, 'emission')).toHaveValue('1.5');
  await expect(controlValue(widget, 'inscatter')).toHaveValue('0');
  await expect(controlValue(widget, 'background')).toHaveValue('2');
  await expect(controlValue(widget, 'length')).toHaveValue('0.5');
  await expectSoundNumbers(widget, exactL(3, 0.2, 1.5, 0, 2, 0.5), 1e-3);
});

test('presentation mode: F enters, number keys recall the presets (3 hides the background, 4 is vacuum), Esc leaves', async ({
  page,
}) => {
  const widget = await openChapter(page);
  await widget.locator('input[type="range"]').first().focus();
  await page.keyboard.press('f');
  const shell = widget.locator('.sb-widget');
  await expect(shell).toHaveClass(/is-presenting/);
  await expect.poll(() => page.url()).toContain('present=1');
  await expect(widget.locator('canvas.sb-canvas')).toBeInViewport();
  await page.keyboard.press('3');
  await expect(widget.locator('.sb-preset-toast')).toContainText(
    'thick medium hides the background',
  );
  await expect(controlValue(widget, 'sigma')).toHaveValue('3');
  await expect(controlValue(widget, 'length')).toHaveValue('4');
  // τ ≈ 12.1: T ≈ 5e-6, so L is the source function J = 0.5·0.5 + 0.5·0.3 = 0.4 to 5 digits.
  await expect.poll(async () => parseDisplayed(await readout(widget, 'total'))).toBeCloseTo(0.4, 4);
  await page.keyboard.press('4');
  await expect(controlValue(widget, 'sigma')).toHaveValue('0');
  // Vacuum: T = 1 and L = L_bg = 1 exactly (the march adds 0 per step, multiplies T by e^0 = 1).
  await expect.poll(() => readout(widget, 'total')).toMatch(/^1 /);
  await expect.poll(() => readout(widget, 'reference')).toMatch(/^1 =/);
  await page.keyboard.press('Escape');
  await expect(shell).not.toHaveClass(/is-presenting/);
});

test('?backend=cpu: the float64 march draws the ray and computes the numbers, and says so', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openChapter(page, '?backend=cpu', 'vre-ray-1.sigma=2&vre-ray-1.length=3');
  await expect(widget.locator('.sb-notice--warning')).toContainText('WebGPU is not available');
  await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
  const stats = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  // float64 march vs the exact form: only the midpoint error of τ̂, ≤ 1e-5 relative here.
  await expectSoundNumbers(widget, exactL(2, 0.5, 0.5, 0.3, 1, 3), 1e-5);
  expect(errors).toEqual([]);
});

test('the deck has a slide for the VRE that draws the ray', async ({ page }) => {
  await page.goto('/deck.html');
  const id = await page.locator('.deck-slide:has(sb-vre-ray)').first().getAttribute('id');
  const slide = Number(/^slide-(\d+)$/.exec(id ?? '')?.[1]);
  expect(slide).toBeGreaterThan(0);
  await page.goto(`/deck.html#slide=${slide}`);
  await page.reload();
  const widget = page.locator(`#slide-${slide}-widget`);
  await waitForRender(widget);
  const stats = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
});
