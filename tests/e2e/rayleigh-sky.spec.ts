// <sb-rayleigh-sky> in Chromium with WebGPU (SwiftShader): it draws a non-blank sky,
// its readouts show the physics of chapter 3 (a blue zenith at noon, a red sun at
// sunset, a black sky without air), the step count trades accuracy against cost,
// the sweep over N plots the error against the GPU time with fitted slopes and can
// be cancelled while the page stays live, its state round-trips through the URL,
// presentation mode and the presets work from the keyboard, and without WebGPU it
// falls back to the float64 twin and says so.
import { expect, test, type Locator, type Page } from '@playwright/test';
import {
  canvasStats,
  parseDisplayed,
  readout,
  recordStagesFromNextInput,
  toggleTheme,
  trackErrors,
  waitForRender,
  waitForSettled,
  widgetAxeViolations,
  widgetPictureOpener,
} from './support.ts';

const CHAPTER = '/chapters/03-phase-functions-and-in-scattering.html';
const ID = 'rayleigh-sky-1';

/** Opens the chapter with `state` (parameter → value) in the hash for the first sky widget. */
async function openSky(
  page: Page,
  state: Record<string, string> = {},
  query = '',
): Promise<Locator> {
  const hash = Object.entries(state)
    .map(([k, v]) => `${ID}.${k}=${v}`)
    .join('&');
  await page.goto(`${CHAPTER}${query}${hash ? `#${hash}` : ''}`);
  const widget = page.locator('sb-rayleigh-sky').first();
  await waitForRender(widget);
  return widget;
}

/** Opens the chapter like openSky, waiting for the first picture only (widgetPictureOpener). */
const openSkyPicture = widgetPictureOpener(CHAPTER, 'sb-rayleigh-sky', ID);

function controlValue(widget: Locator, name: string): Locator {
  return widget.locator(`input[type="number"][name="${name}"], select[name="${name}"]`);
}

/** The largest relative error over the probes, the first number of the error readout (%). */
async function largestError(widget: Locator): Promise<number> {
  return parseDisplayed(await readout(widget, 'error'));
}

// One page load for every check of the chapter's figure as it opens (sun at 60°, noon):
// loading the chapter and refining the 640×480 panorama on SwiftShader is most of each
// test's time, so the picture, the physics of the presets, the accessibility check and
// presentation mode share it, each in its own step.
test('draws a non-blank noon sky on the GPU with its readouts; the presets give a red sun and no air; axe-core in both themes; presentation mode', async ({
  page,
}) => {
  test.setTimeout(180_000);
  const errors = trackErrors(page);
  await page.emulateMedia({ colorScheme: 'light' });
  const widget = await openSky(page);
  await test.step('a non-blank sky, with the cost, the error and the scope line', async () => {
    const stats = await canvasStats(widget.locator('canvas.sb-canvas'));
    expect(stats.luminanceDeviation).toBeGreaterThan(10);
    expect(stats.distinctColours).toBeGreaterThan(20);
    await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
    await expect(widget.locator('.sb-cost')).toContainText('per frame');
    await expect(widget.locator('.sb-notice--warning')).toHaveCount(0);
    await expect(widget.locator('.sb-sky-labels')).toContainText('enlarged ×4');
    await expect(widget).toContainText(
      'Single Rayleigh scattering only: no ozone, no aerosols, no multiple scattering.',
    );
  });
  await test.step('noon has a blue zenith', async () => {
    await expect(controlValue(widget, 'sun-elevation')).toHaveValue('60');
    expect(parseDisplayed(await readout(widget, 'zenith-ratio'))).toBeGreaterThan(1);
    // The float64 twin gives L_B/L_R = 4.51 at the zenith for a sun at 60°.
    expect(parseDisplayed(await readout(widget, 'zenith-ratio'))).toBeCloseTo(4.5, 1);
  });
  await test.step('axe-core: every rule in the light theme, the colour rules in the dark', async () => {
    expect(await widgetAxeViolations(page, 'sb-rayleigh-sky'), 'light theme').toEqual([]);
    await toggleTheme(page, 'dark');
    expect(
      await widgetAxeViolations(page, 'sb-rayleigh-sky', { colourOnly: true }),
      'dark theme',
    ).toEqual([]);
  });
  await test.step('sunset has a red sun, and no air a black sky with a white sun', async () => {
    await widget.locator('input[type="range"]').first().focus();
    await page.keyboard.press('3');
    await expect(controlValue(widget, 'sun-elevation')).toHaveValue('2');
    // The probes are evaluated at the reader's N in every frame, a preview's too, so the
    // readout changes with the first picture at 2° (at 60° the ratio is well under 10): no
    // need to wait for the full-resolution panorama. Twin: T_sun = (0.421, 0.133,
    // 0.0072) at 2°, red/blue ≈ 58.
    await expect
      .poll(async () => parseDisplayed(await readout(widget, 'sun-ratio')))
      .toBeGreaterThan(10);
    await page.keyboard.press('4');
    await expect(controlValue(widget, 'scattering')).toHaveValue('off');
    await expect.poll(() => readout(widget, 'sun')).toBe('1, 1, 1');
    await expect.poll(() => readout(widget, 'zenith')).toBe('0, 0, 0');
  });
  await test.step('presentation mode: F enters and fills the screen, number keys recall the presets, Esc leaves', async () => {
    await widget.locator('input[type="range"]').first().focus();
    await page.keyboard.press('f');
    const shell = widget.locator('.sb-widget');
    await expect(shell).toHaveClass(/is-presenting/);
    const box = await shell.boundingBox();
    expect(box?.width).toBeGreaterThan(1200);
    expect(box?.height).toBeGreaterThan(850);
    await expect.poll(() => page.url()).toContain('present=1');
    await expect(widget.locator('canvas.sb-canvas')).toBeInViewport();
    await page.keyboard.press('2');
    await expect(widget.locator('.sb-preset-toast')).toHaveText('2 · afternoon');
    await expect(controlValue(widget, 'sun-elevation')).toHaveValue('20');
    await expect(controlValue(widget, 'scattering')).toHaveValue('on');
    await page.keyboard.press('1');
    await expect(controlValue(widget, 'sun-elevation')).toHaveValue('60');
    await page.keyboard.press('Escape');
    await expect(shell).not.toHaveClass(/is-presenting/);
    await widget.getByRole('button', { name: 'Present' }).click();
    await expect(shell).toHaveClass(/is-presenting/);
    await widget.getByRole('button', { name: 'Exit presentation' }).click();
    await expect(shell).not.toHaveClass(/is-presenting/);
  });
  expect(errors).toEqual([]);
});

test('the picture follows the sun, and more view-ray samples lower the error against the converged reference', async ({
  page,
}) => {
  const widget = await openSky(page, { 'sun-elevation': '20', steps: '8' });
  await expect(widget.locator('.sb-cost')).toContainText('N = 8 view samples');
  const before = await canvasStats(widget.locator('canvas.sb-canvas'));
  // The sun moves at N = 8, whose full-resolution panorama is cheap to settle, so the
  // two pictures compared are both complete.
  const rendered = Number(await widget.getAttribute('data-rendered'));
  const slider = widget.locator('input[type="range"][name="sun-elevation"]');
  await slider.focus();
  for (let i = 0; i < 4; i++) await page.keyboard.press('ArrowRight');
  await waitForRender(widget, rendered + 1);
  await expect(controlValue(widget, 'sun-elevation')).toHaveValue('22');
  const after = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(after.png.equals(before.png)).toBe(false);
  // The error is the probes', evaluated at the reader's N in every frame (a preview
  // only lowers the panorama's resolution), against the reference for this sun.
  const coarse = await largestError(widget);
  const steps = controlValue(widget, 'steps');
  await steps.fill('64');
  await steps.press('Enter');
  await expect(widget.locator('.sb-cost')).toContainText('N = 64 view samples × M = 16');
  // Midpoint rule, O(h²): 8× more samples cut the error by ~64; at least 10× here.
  await expect.poll(() => largestError(widget)).toBeLessThan(coarse / 10);
  await expect.poll(() => page.url()).toContain('steps=64');
});

test('after an input the panorama is a lower-resolution preview first, then settles to the numbers of a fresh load', async ({
  page,
}) => {
  test.setTimeout(180_000);
  const errors = trackErrors(page);
  const widget = await openSky(page, { 'sun-elevation': '30' });
  // Every stage the widget shows, in order, from the next input on.
  const slider = widget.locator('input[type="range"][name="sun-elevation"]');
  const stagesShown = await recordStagesFromNextInput(widget, slider);
  await slider.focus();
  for (let i = 0; i < 10; i++) await page.keyboard.press('ArrowRight');
  await expect(controlValue(widget, 'sun-elevation')).toHaveValue('35');
  await waitForSettled(widget, 120_000);
  const stages = await stagesShown();
  expect(stages[0]).toMatch(/^Preview: \d+×\d+ pixels$/);
  expect(stages.at(-1)).toBe('640×480 pixels');
  expect(await widget.locator('canvas.sb-canvas').getAttribute('width')).toBe('640');
  await expect(widget.locator('.sb-cost')).toContainText('panorama 640×480, N = 32');
  const settled = Object.fromEntries(
    await Promise.all(
      ['zenith', 'toward', 'away', 'error', 'sun'].map(
        async (key) => [key, await readout(widget, key)] as const,
      ),
    ),
  );
  const fresh = await openSky(page, { 'sun-elevation': '35' });
  for (const [key, text] of Object.entries(settled)) expect(await readout(fresh, key)).toBe(text);
  expect(errors).toEqual([]);
});

// One page for the cancel and the whole sweep: the cancel first (as a reader who stops
// a sweep and runs it again), then the eleven points the fit needs.
test('a running sweep can be cancelled while the page stays live; run again, it plots the relative RMS error against the panorama time, with the fitted slopes', async ({
  page,
}) => {
  test.setTimeout(420_000);
  const errors = trackErrors(page);
  const widget = await openSky(page);
  await expect(widget.locator('.sb-sweep-hint')).toContainText('relative RMS error');
  expect(await readout(widget, 'slope')).toBe('run the sweep');
  const run = widget.getByRole('button', { name: 'Run sweep N = 4 … 128' });
  await test.step('a running sweep can be cancelled, and the page stays live while it runs', async () => {
    await run.click();
    await expect(widget).toHaveAttribute('data-sweeping', '');
    await expect
      .poll(async () =>
        Number(await widget.locator('progress').evaluate((e) => (e as HTMLProgressElement).value)),
      )
      .toBeGreaterThanOrEqual(2);
    // The page answers input mid-sweep: a control changes, the URL follows, and the
    // widget redraws, all while the sweep is still running.
    const rendered = Number(await widget.getAttribute('data-rendered'));
    const exposure = controlValue(widget, 'exposure');
    await exposure.fill('1');
    await exposure.press('Enter');
    await expect.poll(() => page.url()).toContain('exposure=1');
    await waitForRender(widget, rendered + 1);
    await expect(widget).toHaveAttribute('data-sweeping', '');
    await widget.getByRole('button', { name: 'Cancel' }).click();
    await expect(widget.locator('.sb-sky-sweep-status')).toHaveText('Sweep cancelled.');
    await expect(widget).not.toHaveAttribute('data-sweeping');
    await expect(run).toBeEnabled();
    const stoppedAt = await widget
      .locator('progress')
      .evaluate((e) => (e as HTMLProgressElement).value);
    expect(stoppedAt).toBeLessThan(11);
    // The plot kept the points measured before the cancel.
    await expect(widget.locator('.sb-plot .u-over')).toBeVisible();
    // Once the frame in flight is done, the slopes say the sweep was cancelled.
    await expect
      .poll(() => readout(widget, 'slope'), { timeout: 60_000 })
      .toBe('cancelled; run the sweep again');
  });
  await test.step('the whole sweep plots the error against the time, with the fitted slopes', async () => {
    // The sweep's error and time do not depend on the exposure (a display setting).
    await run.click();
    await expect(widget.locator('.sb-sky-sweep-status')).toContainText('Sweep done', {
      timeout: 300_000,
    });
    await expect(widget.locator('progress')).toHaveJSProperty('value', 11);
    await expect(widget.locator('progress')).toHaveJSProperty('max', 11);
    await expect(widget.locator('.sb-sky-sweep-status')).toContainText(
      /time of one 640×480 panorama \((GPU timestamp query|wall time; this GPU has no timestamp queries)\), median of/,
    );
    // Twin at 60°: p = −1.94 over N = 16 … 128; the f32 kernel agrees to 3 digits there.
    const p = parseDisplayed(await readout(widget, 'slope'));
    expect(p).toBeGreaterThan(-2.3);
    expect(p).toBeLessThan(-1.7);
    expect(await readout(widget, 'slope')).toContain('midpoint rule: −2');
    // The time slope depends on the machine: only its form is checked, never its value.
    expect(await readout(widget, 'time-slope')).toMatch(/^q = -?[\d.]+(×10[⁻⁰-⁹]+)?, a = -?[\d.]+/);
    await expect(widget.locator('.sb-plot .u-over')).toBeVisible();
    await expect(widget.locator('.sb-plot .u-legend')).toContainText(
      'relative RMS error, sun at 60°',
    );
    await expect(widget.locator('.sb-plot')).toHaveAttribute(
      'aria-label',
      'Log–log plot of relative RMS error against time per render',
    );
    const plot = await canvasStats(widget.locator('.sb-plot canvas'));
    expect(plot.distinctColours).toBeGreaterThan(3);
    // Afterwards the picture and the cost line are back at the chosen N = 32.
    await expect(widget.locator('.sb-cost')).toContainText('N = 32 view samples × M = 8');
    await expect(widget.locator('.sb-cost')).toContainText('median of');
  });
  expect(errors).toEqual([]);
});

test('a deep link restores the state exactly', async ({ page }) => {
  // Controls, the cost line and the probes' readouts are the same in every refinement
  // stage: the first picture is enough (full refinement at N = 100 is slow on SwiftShader).
  const widget = await openSkyPicture(page, {
    'sun-elevation': '2',
    scattering: 'on',
    steps: '100',
    exposure: '1.5',
  });
  await expect(controlValue(widget, 'sun-elevation')).toHaveValue('2');
  await expect(controlValue(widget, 'scattering')).toHaveValue('on');
  await expect(controlValue(widget, 'steps')).toHaveValue('100');
  await expect(controlValue(widget, 'exposure')).toHaveValue('1.5');
  await expect(widget.locator('.sb-cost')).toContainText('N = 100 view samples × M = 25');
  expect(parseDisplayed(await readout(widget, 'sun-ratio'))).toBeGreaterThan(1);
});

test('?backend=cpu: the float64 twin draws the sky and computes the same numbers, and its sweep times the float64 probes instead of a panorama; it says so', async ({
  page,
}) => {
  test.setTimeout(180_000);
  const errors = trackErrors(page);
  const state = { 'sun-elevation': '60', steps: '16' };
  const gpuWidget = await openSky(page, state);
  await expect(gpuWidget.locator('.sb-cost')).toContainText('WebGPU');
  const gpuZenith = parseDisplayed(await readout(gpuWidget, 'zenith-ratio'));
  const widget = await openSky(page, state, '?backend=cpu');
  await expect(widget.locator('.sb-notice--warning')).toContainText('WebGPU is not available');
  await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
  const stats = await canvasStats(widget.locator('canvas.sb-canvas'));
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  // Same N and M: f32 vs float64 differ by < 1e-3 relative (tests/shaders), so the
  // four displayed digits of the ratio agree to within one unit in the last place.
  expect(Math.abs(parseDisplayed(await readout(widget, 'zenith-ratio')) - gpuZenith)).toBeLessThan(
    2e-3,
  );
  // The sweep runs over its own N = 4 … 128 at the sun of the inputs (60°), whatever N is chosen.
  await widget.getByRole('button', { name: /Run sweep/ }).click();
  await expect(widget.locator('.sb-sky-sweep-status')).toContainText('Sweep done', {
    timeout: 90_000,
  });
  await expect(widget.locator('.sb-sky-sweep-status')).toContainText(
    'CPU fallback: time of the three float64 probes (CPU wall time), no panorama',
  );
  // Twin at 60°: p = −1.944 exactly (float64 against the same cached reference).
  expect(parseDisplayed(await readout(widget, 'slope'))).toBeCloseTo(-1.94, 2);
  expect(errors).toEqual([]);
});
