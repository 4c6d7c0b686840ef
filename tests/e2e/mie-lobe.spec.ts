// <sb-mie-lobe> in Chromium with WebGPU (SwiftShader): the lobe the GPU draws from the
// tabulated phase function follows the float64 series, a control changes it, a deep
// link restores its state, and without WebGPU the float64 twin draws and says so.
// Few and fast: each test opens the chapter once and reads the first settled frame.
import { expect, test } from '@playwright/test';
import { parseDisplayed, readout, trackErrors, waitForRender, widgetOpener } from './support.ts';

const CHAPTER = '/chapters/03-phase-functions-and-in-scattering.html';
const open = widgetOpener(CHAPTER, 'sb-mie-lobe', 'mie-lobe-1');

test('draws the lobe on the GPU; the radius changes it (x, g and the colour readout)', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await open(page);
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  await expect(widget.locator('.sb-cost')).toContainText('angles from the table');
  expect(await readout(widget, 'drawn-error')).toContain('GPU, f32 table');
  const gBefore = parseDisplayed(await readout(widget, 'g'));
  expect(gBefore).toBeGreaterThan(0.5);
  const rendered = Number(await widget.getAttribute('data-rendered'));
  const radius = widget.locator('input[type="number"][name="log-radius"]');
  await radius.fill('-2');
  await radius.press('Enter');
  await waitForRender(widget, rendered + 1);
  const gAfter = parseDisplayed(await readout(widget, 'g'));
  expect(Math.abs(gAfter)).toBeLessThan(0.05);
  await expect(widget.locator('[data-readout="colour"]')).toContainText('bluish');
  expect(errors).toEqual([]);
});

test('a deep link restores the state: soot at 0.1 µm absorbs', async ({ page }) => {
  const widget = await open(page, { 'log-radius': '-1', n: '1.75', kappa: '0.44' });
  await expect(widget.locator('input[type="number"][name="kappa"]')).toHaveValue('0.44');
  const efficiencies = await readout(widget, 'efficiencies');
  const [qExt, qSca] = efficiencies.split(',').map((part) => parseDisplayed(part));
  expect(qExt!).toBeGreaterThan(qSca!);
  expect(parseDisplayed(await readout(widget, 'albedo'))).toBeLessThan(0.5);
});

test('?backend=cpu: the float64 twin of the table draws and says so', async ({ page }) => {
  const widget = await open(page, {}, '?backend=cpu');
  await expect(widget.locator('.sb-cost')).toContainText('CPU');
  expect(await readout(widget, 'drawn-error')).toContain('CPU, float64 twin of the table');
  await expect(widget.locator('canvas').first()).toBeVisible();
});
