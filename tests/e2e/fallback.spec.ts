// With WebGPU switched off, widgets fall back to the float64 CPU reference, say
// so, and still draw and compute the right numbers.
import { expect, test } from '@playwright/test';
import {
  canvasStats,
  chapterPages,
  parseDisplayed,
  trackErrors,
  waitForPicture,
  waitForRender,
  WIDGET_SELECTOR,
} from './support.ts';

// One test per chapter (a chapter's CPU twins take tens of seconds on two cores; the whole
// book in one test outgrew its timeout as widgets were added).
for (const chapter of chapterPages()) {
  test(`${chapter.slug}: every widget falls back to the CPU with a visible notice`, async ({
    page,
  }) => {
    test.setTimeout(180_000);
    const errors = trackErrors(page);
    await page.goto(chapter.path);
    for (const widget of await page.locator(WIDGET_SELECTOR).all()) {
      // The first picture is enough to show the fallback and its notice; the float64
      // twins' full refinement takes tens of seconds per chapter on two cores, and the
      // numbers are checked below and in each widget's own ?backend=cpu test.
      await waitForPicture(widget);
      await expect(widget.locator('.sb-notice--warning')).toContainText('WebGPU is not available');
      // An exercise (sb-exercise) is an editor, not a figure: without WebGPU it has nothing
      // to draw (its checks run WGSL on a GPU), so only figures are checked for a picture.
      if ((await widget.evaluate((element) => element.localName)) !== 'sb-exercise') {
        const stats = await canvasStats(widget.locator('canvas.sb-canvas').first());
        expect(stats.luminanceDeviation).toBeGreaterThan(10);
      }
      await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
    }
    expect(errors).toEqual([]);
  });
}

test("the CPU fallback computes Beer's law", async ({ page }) => {
  await page.goto(
    '/chapters/02-extinction-and-transmittance.html#beer-law-1.sigma-a=0.5&beer-law-1.sigma-s=0.5&beer-law-1.thickness=2&beer-law-1.profile=homogeneous',
  );
  const widget = page.locator('sb-beer-law').first();
  await waitForRender(widget);
  const shown = parseDisplayed((await widget.locator('[data-readout="exit"]').textContent()) ?? '');
  expect(shown).toBeCloseTo(Math.exp(-2), 6);
});
