// <sb-translucent-room> in Chromium with WebGPU (SwiftShader), at 16² pixels and 4 samples per
// pixel so that it stays cheap: both pictures draw and accumulate, the dipole's error and the
// indirect share are shown, an input shows a preview first, black walls take the indirect share to zero and restore from the
// URL, presentation mode and a preset key work; and without WebGPU the float64 twins draw both
// pictures in the worker and say so.
import { expect, test } from '@playwright/test';
import {
  canvasStats,
  parseDisplayed,
  readout,
  recordStagesFromNextInput,
  trackErrors,
  widgetOpener,
} from './support.ts';

const CHAPTER = '/chapters/12-beyond-the-lecture.html';
const ID = 'translucent-room-1';
const openWidget = widgetOpener(CHAPTER, 'sb-translucent-room', ID);
const CHEAP = { size: '16', spp: '2' };

/** The last number of the indirect-share row: the share over all three channels. */
const indirectAll = async (widget: import('@playwright/test').Locator): Promise<number> =>
  parseDisplayed((await readout(widget, 'indirect')).split('·').at(-1)!.trim());

test('both pictures accumulate with times and the dipole error; black walls leave no indirect light', async ({
  page,
}) => {
  test.setTimeout(120_000);
  const errors = trackErrors(page);
  const widget = await openWidget(page, CHEAP);
  const canvases = widget.locator('canvas.sb-canvas');
  await expect(canvases).toHaveCount(2);
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  await expect.poll(() => readout(widget, 'path-spp'), { timeout: 60_000 }).toMatch(/^4 of 4/);
  await expect.poll(() => readout(widget, 'dipole-spp'), { timeout: 60_000 }).toMatch(/^4 of 4/);
  for (const k of [0, 1])
    expect((await canvasStats(canvases.nth(k))).luminanceDeviation).toBeGreaterThan(5);
  expect(await readout(widget, 'path-time')).toMatch(/GPU timestamp query|wall time/);
  expect(await readout(widget, 'dipole-error')).toMatch(/%.*%/);
  const coloured = await indirectAll(widget);
  expect(coloured).toBeGreaterThan(10);
  expect(coloured).toBeLessThan(90);
  const before = await canvasStats(canvases.nth(1));

  const rendered = Number(await widget.getAttribute('data-rendered'));
  const walls = widget.locator('select[name="walls"]');
  const stagesShown = await recordStagesFromNextInput(widget, walls);
  await walls.selectOption('black');
  await expect
    .poll(async () => Number(await widget.getAttribute('data-rendered')))
    .toBeGreaterThan(rendered);
  await expect.poll(() => indirectAll(widget)).toBe(0);
  // The input's first picture is the preview (a smaller pass 1), then pass 1 at full size.
  await expect.poll(() => widget.getAttribute('data-stage')).toBe('full');
  const stages = await stagesShown();
  // At half the side (a 16² picture previews at 8²).
  expect(stages[0]).toMatch(/^Preview: pass 1 with 256 × 8, 1 sample per pixel at 8² pixels$/);
  expect(stages.at(-1)).toBe('full');
  await expect(widget.locator('.sb-cost')).toContainText('1024 irradiance samples × 64 rays');
  await expect.poll(() => page.url()).toContain('walls=black');
  await expect
    .poll(async () => (await canvasStats(canvases.nth(1))).png.equals(before.png))
    .toBe(false);

  // Presentation mode, and the number keys recall presets (3 is marble).
  await widget.locator('select[name="walls"]').focus();
  await page.keyboard.press('f');
  await expect(widget.locator('.sb-widget')).toHaveClass(/is-presenting/);
  await page.keyboard.press('3');
  await expect(widget.locator('select[name="material"]')).toHaveValue('marble');
  expect(errors).toEqual([]);
});

test('?backend=cpu: the float64 twins draw both pictures in the worker and say so', async ({
  page,
}) => {
  test.setTimeout(120_000);
  const errors = trackErrors(page);
  const widget = await openWidget(page, { spp: '2' }, '?backend=cpu');
  await expect(widget.locator('.sb-cost')).toContainText('CPU');
  await expect(widget.locator('.sb-notice', { hasText: 'float64 twins' })).toHaveCount(1);
  expect(await readout(widget, 'path-spp')).toMatch(/^4 of 4/);
  const canvases = widget.locator('canvas.sb-canvas');
  for (const k of [0, 1])
    expect((await canvasStats(canvases.nth(k))).luminanceDeviation).toBeGreaterThan(5);
  expect(await indirectAll(widget)).toBeGreaterThan(10);
  expect(errors).toEqual([]);
});
