// <sb-dipole-profile> in Chromium with WebGPU (SwiftShader): it draws the lit disc and
// the profile plot with the published dipole totals (physics.md §6.1), a preset changes
// the picture, the coefficients and the numbers, editing a coefficient by hand leaves
// the preset, "More photons" grows the Monte Carlo and shrinks its error bars and can be
// cancelled, a deep link restores the state, presentation mode and the number keys work,
// and without WebGPU the float64 twins draw the same numbers and say so.
import { expect, test, type Locator } from '@playwright/test';
import {
  canvasStats,
  parseDisplayed,
  readout,
  trackErrors,
  waitForRender,
  widgetOpener,
} from './support.ts';
import { dipoleParameters, dipoleTotalReflectance } from '../../src/reference/dipole.ts';

const CHAPTER = '/chapters/11-subsurface-scattering.html';
const ID = 'dipole-profile-1';

const openWidget = widgetOpener(CHAPTER, 'sb-dipole-profile', ID);

function control(widget: Locator, name: string): Locator {
  return widget.locator(`input[type="number"][name="${name}"], select[name="${name}"]`);
}

/** The three standard errors of the Monte Carlo total, as shown (R · G · B). */
async function standardErrors(widget: Locator): Promise<number[]> {
  return (await readout(widget, 'mc-se')).split('·').map((part) => parseDisplayed(part.trim()));
}

test('draws the lit disc and the profile plot on the GPU, with the published dipole totals; a hand edit, a preset and presentation mode change them', async ({
  page,
}) => {
  // Four refinements to full quality one after the other (load, edit, preset, preset key).
  test.setTimeout(150_000);
  const errors = trackErrors(page);
  const widget = await openWidget(page);
  const disc = await canvasStats(widget.locator('canvas.sb-canvas').first());
  expect(disc.luminanceDeviation).toBeGreaterThan(10);
  expect(disc.distinctColours).toBeGreaterThan(20);
  await expect(widget.locator('.sb-dp-profile .u-over')).toBeVisible();
  // physics.md §6.1, Skin1: R_d = 0.435956, 0.227331, 0.130999.
  expect(parseDisplayed(await readout(widget, 'total-dipole-r'))).toBeCloseTo(0.436, 3);
  expect(parseDisplayed(await readout(widget, 'total-dipole-g'))).toBeCloseTo(0.2273, 4);
  expect(parseDisplayed(await readout(widget, 'total-dipole-b'))).toBeCloseTo(0.131, 3);
  // Monte Carlo: a first run, with a standard error and a cost.
  expect(await readout(widget, 'total-mc-r')).toMatch(/^0\.4\d* ± /);
  expect(await readout(widget, 'mc-photons')).toMatch(/per channel/);
  expect(await readout(widget, 'mc-time')).toMatch(/GPU timestamp query|wall time/);
  expect(await readout(widget, 'capped')).toContain('0');
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  await expect(widget.locator('.sb-notice--warning')).toHaveCount(0);
  expect(Number(await widget.getAttribute('data-frame-ms'))).toBeGreaterThan(0);

  // Editing a coefficient by hand leaves the preset and recomputes the totals.
  let rendered = Number(await widget.getAttribute('data-rendered'));
  const sigmaA = control(widget, 'sigma-a-r');
  await sigmaA.fill('0.5');
  await sigmaA.dispatchEvent('change');
  await waitForRender(widget, rendered + 1);
  await expect(control(widget, 'material')).toHaveValue('manual');
  const expected = dipoleTotalReflectance(dipoleParameters(0.74, 0.5, 1.3));
  await expect
    .poll(async () => parseDisplayed(await readout(widget, 'total-dipole-r')), {
      message: 'the hand-edited total follows the dipole of σs′ = 0.74, σa = 0.5, η = 1.3',
    })
    .toBeCloseTo(expected, 3);

  // A material preset changes the picture, the coefficients and the numbers.
  const before = await canvasStats(widget.locator('canvas.sb-canvas').first());
  rendered = Number(await widget.getAttribute('data-rendered'));
  await control(widget, 'material').selectOption('ketchup');
  await waitForRender(widget, rendered + 1);
  // physics.md §6.1, Ketchup: R_d = 0.163836, 0.006337, 0.001830.
  await expect
    .poll(async () => parseDisplayed(await readout(widget, 'total-dipole-g')))
    .toBeCloseTo(0.006337, 5);
  expect(parseDisplayed(await readout(widget, 'total-dipole-r'))).toBeCloseTo(0.1638, 4);
  await expect(control(widget, 'sigma-s-r')).toHaveValue('0.18');
  await expect(control(widget, 'sigma-a-b')).toHaveValue('1.45');
  const after = await canvasStats(widget.locator('canvas.sb-canvas').first());
  expect(after.png.equals(before.png), 'ketchup changes the picture').toBe(false);
  await expect.poll(() => page.url()).toContain('material=ketchup');

  // Presentation mode: F enters, number keys recall materials, Esc leaves.
  await control(widget, 'eta').focus();
  await widget.locator('input[type="range"]').first().focus();
  await page.keyboard.press('f');
  const shell = widget.locator('.sb-widget');
  await expect(shell).toHaveClass(/is-presenting/);
  await expect(widget.locator('.sb-dp-profile')).toBeInViewport();
  await page.keyboard.press('2');
  await expect(widget.locator('.sb-preset-toast')).toHaveText('2 · Marble');
  await expect(control(widget, 'material')).toHaveValue('marble');
  await expect(control(widget, 'eta')).toHaveValue('1.5');
  // physics.md §6.1, Marble R: 0.830191.
  await expect
    .poll(async () => parseDisplayed(await readout(widget, 'total-dipole-r')), { timeout: 30_000 })
    .toBeCloseTo(0.8302, 4);
  await page.keyboard.press('Escape');
  await expect(shell).not.toHaveClass(/is-presenting/);
  expect(errors).toEqual([]);
});

test('a deep link restores the state exactly; More photons grows the Monte Carlo and shrinks its error bars; Cancel stops it', async ({
  page,
}) => {
  test.setTimeout(150_000);
  const errors = trackErrors(page);
  // Every setting away from its default. The coefficients keep the walks about as long
  // as skin1's (model.ts's expectedCollisions: 114 collisions per photon against 98), so
  // the first run is 1024 photons per channel as for skin1 (firstRunPhotons) and the run
  // below to 2^13 is 8× that, a few steps on SwiftShader; conservative coefficients
  // (σa → 0) would make it many times longer.
  const state = {
    material: 'manual',
    'sigma-s-r': '1.5',
    'sigma-s-g': '1.2',
    'sigma-s-b': '0.8',
    'sigma-a-r': '0.1',
    'sigma-a-g': '0.2',
    'sigma-a-b': '0.5',
    eta: '1.45',
    g: '0.3',
    exposure: '2',
    view: '6',
    seed: '42',
    photons: '13',
  };
  const widget = await openWidget(page, state);
  for (const [name, value] of Object.entries(state))
    await expect(control(widget, name), `${name} from the link`).toHaveValue(value);
  await expect(widget.locator('.sb-cost')).toContainText('HG g = 0.3');
  await expect(widget.locator('.sb-cost')).toContainText('η = 1.45');
  const expected = [
    [1.5, 0.1],
    [1.2, 0.2],
    [0.8, 0.5],
  ].map(([sp, sa]) => dipoleTotalReflectance(dipoleParameters(sp!, sa!, 1.45)));
  for (const [c, key] of ['r', 'g', 'b'].entries())
    expect(
      parseDisplayed(await readout(widget, `total-dipole-${key}`)),
      `dipole total ${key}`,
    ).toBeCloseTo(expected[c]!, 3);

  const firstSe = await standardErrors(widget);
  const plot = widget.locator('.sb-dp-profile canvas').first();
  const plotBefore = await plot.screenshot();
  await widget.getByRole('button', { name: 'More photons' }).click();
  await expect(widget.locator('.sb-dp-status')).toContainText('Done', { timeout: 60_000 });
  // Counts are exact, grouped with thin spaces ("8 192").
  const photons = Number(
    (await readout(widget, 'mc-photons')).replace(/\u2009/g, '').split(' ')[0],
  );
  expect(photons).toBeGreaterThanOrEqual(8192);
  const laterSe = await standardErrors(widget);
  // 8× the photons: each standard error about √8 ≈ 2.8× smaller; at least 1.8× here.
  laterSe.forEach((se, c) => expect(se).toBeLessThan(firstSe[c]! / 1.8));
  expect((await plot.screenshot()).equals(plotBefore)).toBe(false);
  await expect(widget.locator('.sb-dp-errors .u-over')).toBeVisible();

  // A target of 2^22 is far away: start, cancel, and the button is free again.
  const target = control(widget, 'photons');
  await target.fill('22');
  await target.dispatchEvent('change');
  const more = widget.getByRole('button', { name: 'More photons' });
  await more.click();
  await expect(widget.getByRole('button', { name: 'Cancel' })).toBeEnabled();
  await widget.getByRole('button', { name: 'Cancel' }).click();
  await expect(widget.locator('.sb-dp-status')).toContainText('cancelled');
  await expect(more).toBeEnabled();
  expect(errors).toEqual([]);
});

test('?backend=cpu: the float64 twins draw the same numbers and say so', async ({ page }) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page, {}, '?backend=cpu');
  await expect(widget.locator('.sb-notice--warning')).toContainText('WebGPU is not available');
  await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
  const stats = await canvasStats(widget.locator('canvas.sb-canvas').first());
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  expect(parseDisplayed(await readout(widget, 'total-dipole-r'))).toBeCloseTo(0.436, 3);
  expect(await readout(widget, 'total-mc-r')).toMatch(/^0\.4\d* ± /);
  expect(await readout(widget, 'mc-time')).toContain('CPU wall time');
  expect(errors).toEqual([]);
});
