// <sb-chromatic-media> in Chromium with WebGPU (SwiftShader): the three estimators draw a
// sphere, and in a grey medium (a deep link: spread 1) hero wavelength and spectral tracking
// have exactly zero colour noise while one channel at a time does not (one shared walk per
// sample against three independent ones); moving the spread slider to 16 gives hero
// wavelength colour noise too. Without WebGPU the float64 twin draws in the compute worker and
// says so. The error-against-time plot gets a point per estimator and pass, and starts
// again on an input, whose first picture is a one-sample preview. Two cheap tests: 2 samples
// per pass and a target of 2 (4 where the plot's second point is checked).
import { expect, test } from '@playwright/test';
import {
  canvasStats,
  readout,
  recordStagesFromNextInput,
  trackErrors,
  waitForRender,
  widgetOpener,
} from './support.ts';

const CHAPTER = '/chapters/12-beyond-the-lecture.html';
const open = widgetOpener(CHAPTER, 'sb-chromatic-media', 'chromatic-media-1');
const CHEAP = { spp: '2', target: '2' };

/** The colour noise of one channel at a time, hero wavelength and spectral tracking. */
async function colourNoise(widget: Parameters<typeof readout>[0]): Promise<number[]> {
  const text = await readout(widget, 'colour-noise');
  return text.split('·').map((part) => Number(part.trim()));
}

test('grey medium from a deep link: zero colour noise for the shared walks; the spread slider changes it', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await open(page, { ...CHEAP, target: '4', spread: '1' });
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  await expect(widget.locator('input[type="number"][name="spread"]')).toHaveValue('1');
  const stats = await canvasStats(widget.locator('canvas').first());
  expect(stats.luminanceDeviation).toBeGreaterThan(2);
  const [one, hero, spectral] = await colourNoise(widget);
  expect(one).toBeGreaterThan(0);
  expect(hero).toBe(0);
  expect(spectral).toBe(0);
  await expect(widget.locator('[data-readout="capped"]')).toHaveText('0');

  // The plot of error against time: labelled for screen readers, drawn by uPlot with a
  // legend of the three estimators, one point each per pass from two samples per pixel on
  // (passes of 1, the preview, then 2 and 1 to the target 4).
  const plot = widget.locator('.sb-chromatic-plot');
  await expect(plot).toHaveAttribute('role', 'img');
  await expect(plot).toHaveAttribute('aria-label', /RMS error against the reference/);
  await expect(widget.locator('[data-readout="stage"]')).toContainText(
    '4 samples per pixel each, done',
  );
  await expect(plot).toHaveAttribute('data-points', '2,2,2');
  await expect(plot.locator('.u-over')).toBeVisible();
  for (const name of ['One channel at a time', 'Hero wavelength', 'Spectral tracking'])
    await expect(plot.locator('.u-legend')).toContainText(name);

  const rendered = Number(await widget.getAttribute('data-rendered'));
  const spread = widget.locator('input[type="number"][name="spread"]');
  const stagesShown = await recordStagesFromNextInput(widget, spread);
  await spread.fill('16');
  await spread.press('Enter');
  await waitForRender(widget, rendered + 1);
  // The input's first picture is a one-sample preview of the new medium at half the side
  // (no frame of the old one is shown after the input), then the passes of spp (2) at the
  // full side, which start their own accumulation.
  await expect.poll(async () => (await stagesShown()).length).toBeGreaterThanOrEqual(2);
  const stages = await stagesShown();
  expect(stages[0]).toMatch(/^Preview: 1 of 4 samples per pixel each \(32×32 pixels/);
  expect(stages[1]).toMatch(/^2 of 4 samples per pixel each \(64×64 pixels/);
  const [, heroAfter] = await colourNoise(widget);
  expect(heroAfter).toBeGreaterThan(0);
  // An input starts the plot again: two points each at the target, not four.
  await expect(widget.locator('[data-readout="stage"]')).toContainText('done');
  await expect(plot).toHaveAttribute('data-points', '2,2,2');
  expect(errors).toEqual([]);
});

test('?backend=cpu: the float64 twin draws the smaller picture and says so', async ({ page }) => {
  const widget = await open(page, { ...CHEAP, spread: '1' }, '?backend=cpu');
  await expect(widget.locator('.sb-cost')).toContainText('float64 twin');
  await expect(widget.locator('[data-readout="samples"]')).toContainText('24×24');
  const [one, hero, spectral] = await colourNoise(widget);
  expect(one).toBeGreaterThan(0);
  expect(hero).toBe(0);
  expect(spectral).toBe(0);
});
