// Printing a chapter (issue 18): each figure prints its current picture and its
// readouts instead of an empty canvas, and no controls. Chromium's print media is
// emulated; the book's print command (the header's Print button) draws every figure
// first, and `beforeprint` copies each canvas into a print-only 2D canvas
// (src/widgets/base/print.ts). The WebGPU canvases (beer-law's full-screen pass,
// hg-lobe's 3D view) lose their picture once presented, so their images are the
// real test of the copy. Chromium's PDF of the chapter is written to the test's
// output folder (`chapter.pdf`) for a look.
import { writeFileSync } from 'node:fs';
import { expect, test, type Page } from '@playwright/test';
import { WIDGET_SELECTOR } from './support.ts';

interface PrintedImage {
  widget: string;
  /** The canvas's display on screen: a canvas hidden there stays hidden in print. */
  sourceDisplay: string;
  /** A WebGPU canvas's copy, re-drawn right before it was taken. */
  redrawn: boolean;
  visible: boolean;
  width: number;
  height: number;
  /** Standard deviation of luminance (0–255) over the image's pixels. */
  deviation: number;
  /** Fraction of pixels that are not transparent black (a blank WebGPU copy is all 0). */
  drawn: number;
}

/** Reads every print copy of the page's canvases (while print media is emulated). */
function printedImages(page: Page): Promise<PrintedImage[]> {
  return page.evaluate(() => {
    const out: PrintedImage[] = [];
    for (const image of document.querySelectorAll<HTMLCanvasElement>('canvas.sb-print-image')) {
      const context = image.getContext('2d');
      if (!context) throw new Error('no 2D context');
      const { data } = context.getImageData(0, 0, image.width, image.height);
      let sum = 0;
      let squares = 0;
      let drawn = 0;
      const n = data.length / 4;
      for (let i = 0; i < data.length; i += 4) {
        const y = 0.2126 * data[i]! + 0.7152 * data[i + 1]! + 0.0722 * data[i + 2]!;
        sum += y;
        squares += y * y;
        if (data[i]! + data[i + 1]! + data[i + 2]! + data[i + 3]! > 0) drawn += 1;
      }
      const mean = sum / n;
      const box = image.getBoundingClientRect();
      out.push({
        widget: image.closest('.sb-widget')?.parentElement?.localName ?? '',
        sourceDisplay: image.style.getPropertyValue('--sb-print-display'),
        redrawn: image.hasAttribute('data-print-redrawn'),
        visible: getComputedStyle(image).display !== 'none' && box.width > 0 && box.height > 0,
        width: image.width,
        height: image.height,
        deviation: Math.sqrt(Math.max(0, squares / n - mean * mean)),
        drawn: drawn / n,
      });
    }
    return out;
  });
}

/** Controls (buttons, inputs, selects) of the figures and the header that would print. */
function visibleControls(page: Page): Promise<string[]> {
  return page.evaluate(() =>
    [
      ...document.querySelectorAll<HTMLElement>(
        '.sb-widget :is(button, input, select, textarea), .site-header button, canvas:not(.sb-print-image)',
      ),
    ]
      .filter((element) => element.getClientRects().length > 0)
      .filter((element) => getComputedStyle(element).visibility !== 'hidden')
      .map(
        (element) =>
          `${element.closest('.sb-widget')?.parentElement?.localName ?? 'header'} ${element.localName}.${element.className}`,
      ),
  );
}

for (const [chapter, gpuCanvasWidget] of [
  ['02-extinction-and-transmittance', 'sb-beer-law'],
  ['03-phase-functions-and-in-scattering', 'sb-hg-lobe'],
] as const) {
  test(`chapter ${chapter.slice(0, 2)} prints every figure's picture, readouts and settings, and no controls`, async ({
    page,
  }, testInfo) => {
    test.setTimeout(180_000);
    await page.goto(`/chapters/${chapter}.html`);
    const widgets = page.locator(WIDGET_SELECTOR);
    const count = await widgets.count();
    expect(count).toBeGreaterThan(1);
    await expect(page.locator('.sb-widget')).toHaveCount(count);
    // Figures below the fold have not drawn: the Print button draws them all first.
    // The dialog itself is replaced; what it would print is emulated below.
    await page.evaluate(() => {
      window.print = () => {
        document.documentElement.dataset['printed'] = 'yes';
      };
    });
    await page.locator('.print-button').click();
    await expect(page.locator('html')).toHaveAttribute('data-printed', 'yes', {
      timeout: 150_000,
    });
    for (const widget of await widgets.all())
      expect(Number(await widget.getAttribute('data-rendered'))).toBeGreaterThanOrEqual(1);
    // Chromium lays out for print and fires beforeprint (page.pdf() too); here the
    // print media is emulated first and the event fired by hand, a second time for the
    // copies already taken by the Print button.
    await page.emulateMedia({ media: 'print' });
    await page.evaluate(() => window.dispatchEvent(new Event('beforeprint')));

    const images = await printedImages(page);
    const canvases = await page.locator('.sb-widget canvas:not(.sb-print-image)').count();
    expect(images.length).toBe(canvases);
    for (const image of images.filter((i) => i.sourceDisplay !== 'none')) {
      expect(image.visible, `${image.widget} image shown in print`).toBe(true);
      expect(image.width * image.height).toBeGreaterThan(0);
    }
    // The WebGPU canvas's copy holds its picture (a late copy would be all zero).
    const gpu = images.filter((image) => image.widget === gpuCanvasWidget && image.redrawn);
    expect(gpu.length).toBeGreaterThan(0);
    for (const image of gpu) {
      testInfo.annotations.push({ type: 'gpu copy', description: JSON.stringify(image) });
      expect(image.drawn, `${image.widget} copy is drawn`).toBeGreaterThan(0.5);
      expect(image.deviation, `${image.widget} copy has structure`).toBeGreaterThan(2);
    }
    // No control prints, and no canvas either (its image takes its place).
    expect(await visibleControls(page)).toEqual([]);
    // Readouts and settings print.
    for (const widget of await page.locator(`:is(${WIDGET_SELECTOR}) > .sb-widget`).all()) {
      await expect(widget.locator('.sb-print-settings')).toBeVisible();
      await expect(widget.locator('.sb-print-settings')).toContainText('Settings:');
    }
    const readout = page.locator(`${gpuCanvasWidget} .sb-readout-area`).first();
    await expect(readout).toBeVisible();
    expect(((await readout.textContent()) ?? '').trim().length).toBeGreaterThan(10);

    const pdf = await page.pdf({ format: 'A4', printBackground: false });
    writeFileSync(testInfo.outputPath('chapter.pdf'), pdf);
    expect(pdf.subarray(0, 5).toString()).toBe('%PDF-');
    // The WebGPU figure's picture is in the PDF, as an image of its canvas's size
    // (Chromium fires beforeprint for page.pdf() too, and the copy is taken again).
    const pdfText = pdf.toString('latin1');
    for (const image of gpu) expect(pdfText).toContain(`/Width ${image.width}`);
  });
}

test('printing from the browser menu: a drawn figure prints its picture, one never drawn says so', async ({
  page,
}) => {
  await page.goto('/chapters/02-extinction-and-transmittance.html');
  const first = page.locator('sb-beer-law').first();
  await first.scrollIntoViewIfNeeded();
  await expect
    .poll(async () => Number((await first.getAttribute('data-rendered')) ?? '0'), {
      timeout: 30_000,
    })
    .toBeGreaterThanOrEqual(1);
  const last = page.locator('sb-exercise');
  expect(await last.getAttribute('data-rendered')).toBeNull();
  await page.evaluate(() => window.dispatchEvent(new Event('beforeprint')));
  await page.emulateMedia({ media: 'print' });
  const images = await printedImages(page);
  const beer = images.filter((image) => image.widget === 'sb-beer-law' && image.redrawn);
  expect(beer.length).toBeGreaterThan(0);
  expect(beer[0]?.drawn).toBeGreaterThan(0.5);
  await expect(last.locator('.sb-print-settings')).toContainText('had not been drawn');
  await expect(first.locator('.sb-print-settings')).not.toContainText('had not been drawn');
  // Back on screen, the copies and the settings line are hidden again.
  await page.emulateMedia({ media: 'screen' });
  await expect(first.locator('canvas.sb-print-image').first()).toBeHidden();
  await expect(first.locator('.sb-print-settings')).toBeHidden();
  await expect(first.locator('canvas:not(.sb-print-image)').first()).toBeVisible();
});
