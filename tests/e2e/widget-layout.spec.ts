// A widget's layout stands still while it refines, and its pictures are the only
// composited layers it adds. Under DESIGN.md's Chromium flags the page is rasterised
// and composited on the same software GPU as WebGPU, in the GPU process whose main
// thread also runs the page's WebGPU calls; a swap there holds them back. Two things
// made those swaps long (bench/firstPictureProbe.ts --trace):
// - readouts that wrapped onto one line, then two, as their digits changed moved the
//   widget's height at nearly every frame, and each new layout rasterised large layers
//   anew (src/widgets/base/heightHold.ts holds the readout area's height);
// - content painted after a WebGPU canvas whose paint chunk's bounds covered the canvas
//   went into an extra "Overlap" layer, up to the size of the widget (widgets.css:
//   each block of a widget is its own stacking context; labels over a picture are a
//   layer of their own box);
// - a chapter's sticky table of contents, painted before the chapter, made every
//   formula and widget block after it a layer (book.css paints it after the chapter).
import { expect, test, type Locator, type Page } from '@playwright/test';
import { waitForSettled } from './support.ts';

test.setTimeout(120_000);

async function openEmbed(page: Page, widget: string): Promise<Locator> {
  await page.setViewportSize({ width: 1280, height: 900 });
  await page.goto(`/embed/${widget}.html`);
  const element = page.locator(`sb-${widget}`).first();
  await waitForSettled(element, 90_000);
  return element;
}

/** The widget's height at each animation frame for `ms` (distinct values, in order). */
async function heightsOver(widget: Locator, ms: number): Promise<number[]> {
  return widget.evaluate(async (element, duration) => {
    const section = element.querySelector('.sb-widget') ?? element;
    const heights: number[] = [];
    const start = performance.now();
    while (performance.now() - start < duration) {
      const height = Math.round(section.getBoundingClientRect().height * 10) / 10;
      if (heights.at(-1) !== height) heights.push(height);
      await new Promise((resolve) => requestAnimationFrame(resolve));
    }
    return heights;
  }, ms);
}

// Both accumulate in the background after settling: new numbers every few hundred ms,
// whose standard errors and ratios change length (and wrapping) from frame to frame.
for (const name of ['volume-path-tracer', 'single-scatter']) {
  test(`${name}: the widget's height never shrinks back while it accumulates`, async ({ page }) => {
    const widget = await openEmbed(page, name);
    const before = Number(await widget.getAttribute('data-rendered'));
    const heights = await heightsOver(widget, 4000);
    // It did refine meanwhile (new readouts), so the check had something to hold.
    expect(Number(await widget.getAttribute('data-rendered'))).toBeGreaterThan(before);
    for (let i = 1; i < heights.length; i++)
      expect(heights[i], `heights ${heights.join(' → ')}`).toBeGreaterThanOrEqual(heights[i - 1]!);
  });
}

/** Every composited layer of the page: its size and Chromium's reasons for it. */
async function layers(page: Page): Promise<{ size: string; reasons: string[] }[]> {
  const cdp = await page.context().newCDPSession(page);
  // The compositor reports its layers as they change; the latest report is the tree.
  let found: { layerId: string; width: number; height: number }[] = [];
  cdp.on('LayerTree.layerTreeDidChange', ({ layers }) => {
    if (layers) found = layers;
  });
  await cdp.send('LayerTree.enable');
  const withReasons = async (): Promise<{ size: string; reasons: string[] }[]> => {
    const out: { size: string; reasons: string[] }[] = [];
    for (const layer of found) {
      // A layer of a tree replaced meanwhile is gone: the next report has the new one.
      const reasons = await cdp
        .send('LayerTree.compositingReasons', { layerId: layer.layerId })
        .then(({ compositingReasonIds }) => compositingReasonIds ?? [])
        .catch(() => null);
      if (reasons) out.push({ size: `${layer.width}x${layer.height}`, reasons });
    }
    return out;
  };
  // Paints, until a reported tree has the pictures' layers: a report can leave them out
  // (seen in the full test run, on a loaded machine, for seconds on end).
  let out: { size: string; reasons: string[] }[] = [];
  for (let i = 0; i < 80; i++) {
    await page.evaluate((n) => {
      document.body.style.outline = `${n % 2}px solid transparent`;
    }, i);
    await page.waitForTimeout(250);
    out = await withReasons();
    if (out.some((layer) => layer.reasons.includes('Canvas'))) break;
  }
  await cdp.detach();
  return out;
}

// Widgets whose WebGPU pictures have plots, captions, labels or readouts painted after
// them. transfer-function and dipole-profile are left out: uPlot's own elements over
// its (composited) chart canvas overlap it, which the page does not control.
for (const name of [
  'beer-law',
  'single-scatter',
  'volume-path-tracer',
  'hg-lobe',
  'rayleigh-sky',
]) {
  test(`${name}: no layer is made for content that overlaps its pictures`, async ({ page }) => {
    await openEmbed(page, name);
    const all = await layers(page);
    expect(
      all.some((layer) => layer.reasons.includes('Canvas')),
      JSON.stringify(all),
    ).toBe(true);
    const overlapping = all.filter((layer) => layer.reasons.includes('Overlap'));
    expect(overlapping, JSON.stringify(all)).toEqual([]);
  });
}

// A chapter's sticky table of contents moves as the page scrolls; painted before the
// chapter, it made Chromium layerise every formula, equation and widget block after it
// (50 layers in chapter 9). Painted after it (book.css), only its own layer is left.
test('chapter 9: the table of contents does not turn the chapter into layers', async ({ page }) => {
  await page.setViewportSize({ width: 1280, height: 900 });
  await page.goto('/chapters/09-single-scattering.html');
  const widget = page.locator('sb-single-scatter').first();
  await widget.scrollIntoViewIfNeeded();
  await waitForSettled(widget, 90_000);
  const all = await layers(page);
  const overlapping = all.filter((layer) => layer.reasons.includes('Overlap'));
  expect(overlapping.length, JSON.stringify(overlapping)).toBeLessThanOrEqual(1);
});
