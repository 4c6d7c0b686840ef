// <sb-photon-map> in Chromium with WebGPU (SwiftShader), at cheap settings (8192
// photons): the photon view and both images are drawn, both errors and times are
// shown, changing the gather radius from the keyboard changes the photon-mapped
// image and the URL, presentation mode with a preset works from the keyboard, and
// the sweep draws its three series (fixed radius, progressive radius, path tracing)
// and stops on Cancel after its first points (never waiting for the whole sweep).
import { expect, test, type Locator } from '@playwright/test';
import {
  canvasStats,
  parseDisplayed,
  readout,
  trackErrors,
  waitForRender,
  widgetOpener,
} from './support.ts';

const CHAPTER = '/chapters/10-multiple-scattering.html';
const ID = 'photon-map-1';
const openWidget = widgetOpener(CHAPTER, 'sb-photon-map', ID);

function control(widget: Locator, name: string): Locator {
  return widget.locator(`input[type="number"][name="${name}"]`);
}

test('draws photons, photon map and path tracing with errors and times; the radius changes the image', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page, { photons: '8192', radius: '0.08' });
  const canvases = widget.locator('canvas.sb-canvas');
  await expect(canvases).toHaveCount(3);
  for (let k = 0; k < 3; k++)
    expect((await canvasStats(canvases.nth(k))).distinctColours).toBeGreaterThan(5);
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  expect(parseDisplayed(await readout(widget, 'pm-error'))).toBeGreaterThan(0);
  expect(parseDisplayed(await readout(widget, 'pt-error'))).toBeGreaterThan(0);
  expect(parseDisplayed(await readout(widget, 'pt-spp'))).toBeGreaterThanOrEqual(4);
  expect(await readout(widget, 'pm-time')).toMatch(/GPU timestamp query|wall time/);
  // "3,594 from 8,192 emitted": about 0.44 stored per emitted photon.
  const stored = Number((await readout(widget, 'stored')).split(' ')[0]!.replace(/,/g, ''));
  expect(stored).toBeGreaterThan(1000);
  // The sweep's readouts wait for it: a plateau for the fixed radius, fitted rates
  // for progressive photon mapping and path tracing.
  for (const key of ['plateau', 'progressive', 'pt-rate'])
    expect(await readout(widget, key)).toBe('run the sweep');

  const before = await canvasStats(canvases.nth(1));
  const rendered = Number(await widget.getAttribute('data-rendered'));
  const radius = control(widget, 'radius');
  await radius.fill('0.03');
  await radius.press('Enter');
  await waitForRender(widget, rendered + 1);
  await expect.poll(() => page.url()).toContain('radius=0.03');
  const after = await canvasStats(canvases.nth(1));
  expect(after.png.equals(before.png)).toBe(false);
  expect(errors).toEqual([]);
});

test('presentation mode: F enters, a number key recalls a preset, Esc leaves', async ({ page }) => {
  const widget = await openWidget(page, { photons: '8192', radius: '0.08' });
  await widget.locator('input[type="range"]').first().focus();
  await page.keyboard.press('f');
  const shell = widget.locator('.sb-widget');
  await expect(shell).toHaveClass(/is-presenting/);
  await page.keyboard.press('1');
  await expect(control(widget, 'radius')).toHaveValue('0.1');
  await expect(control(widget, 'photons')).toHaveValue('8192');
  await page.keyboard.press('Escape');
  await expect(shell).not.toHaveClass(/is-presenting/);
});

test('the sweep plots fixed-radius, progressive and path-traced series; Cancel stops it', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page, { photons: '8192', radius: '0.08' });
  await widget.getByRole('button', { name: /Run error-vs-time sweep/ }).click();
  await expect(widget).toHaveAttribute('data-sweeping', '');
  // n = 1 measured for all three series (3 of 21 steps): every curve has a point.
  await expect
    .poll(async () => Number(await widget.locator('.sb-sweep progress').getAttribute('value')), {
      timeout: 20_000,
    })
    .toBeGreaterThanOrEqual(3);
  const legend = widget.locator('.sb-plot .u-legend .u-series');
  // uPlot's legend lists x first, then one entry per series.
  await expect(legend).toHaveCount(4);
  const labels = (await legend.allTextContents()).slice(1).join(' | ');
  expect(labels).toContain('photon mapping, r = 0.08 m');
  expect(labels).toContain('progressive, r = 0.08 m·(N/8192)^(−1/7)');
  expect(labels).toContain('path tracing');
  for (const key of ['plateau', 'progressive', 'pt-rate'])
    expect(await readout(widget, key)).toBe('sweeping…');
  await widget.getByRole('button', { name: 'Cancel' }).click();
  await expect(widget.locator('.sb-sweep-status')).toHaveText('Sweep cancelled.');
  await expect(widget).not.toHaveAttribute('data-sweeping');
  expect(errors).toEqual([]);
});
