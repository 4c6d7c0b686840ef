// The neural field of <sb-inverse-render> (model "hash grid + MLP", chapter 8) in
// Chromium: a deep link selects it, its size is shown beside the grid's, a few GPU
// iterations lower the batch loss below the empty start; without WebGPU the float64
// twin draws the same views at its smaller size and says so.
import { expect, test, type Locator, type Page } from '@playwright/test';
import { canvasStats, parseDisplayed, readout, trackErrors, waitForRender } from './support.ts';

/**
 * Opens chapter 8 with the widget's state in the hash. The neural field's set-up builds
 * the grid's pipelines (for the targets) and its own, which takes SwiftShader up to a
 * minute on a loaded machine: wait for the status line before the usual render wait.
 */
async function openWidget(page: Page, state: Record<string, string>, query = ''): Promise<Locator> {
  const hash = Object.entries(state)
    .map(([k, v]) => `inverse-render-1.${k}=${v}`)
    .join('&');
  await page.goto(`/chapters/08-inverse-volume-rendering.html${query}#${hash}`);
  const widget = page.locator('sb-inverse-render').first();
  await widget.scrollIntoViewIfNeeded();
  await expect(widget.locator('.sb-ir-status')).toContainText('Ready', { timeout: 150_000 });
  await waitForRender(widget);
  return widget;
}

// The neural field's preset (key 7): a small problem, so that a few iterations run
// quickly on SwiftShader.
const SMALL = { model: 'neural', views: '4', steps: '16', batch: '256', rate: '0.05' };

test.setTimeout(300_000);

test('deep link to the neural field: its size and cost line, and a few GPU iterations lower the loss', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page, SMALL);
  await expect(widget.locator('select[name="model"]')).toHaveValue('neural');
  await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
  await expect(widget.locator('.sb-cost')).toContainText('a neural field (hash encoding 8 levels');
  expect(await readout(widget, 'memory')).toContain('65,876 parameters');
  const start = parseDisplayed(await readout(widget, 'train-mse'));
  expect(start).toBeGreaterThan(0.01);
  await widget.locator('[data-action="start"]').click();
  await expect
    .poll(async () => parseDisplayed(await readout(widget, 'iteration')), { timeout: 120_000 })
    .toBeGreaterThanOrEqual(10);
  await widget.locator('[data-action="start"]').click();
  // The batch loss of the 10th iteration on: well below the empty box's error (measured
  // ≈ half of it after 10 iterations with the float64 twin).
  expect(parseDisplayed(await readout(widget, 'loss'))).toBeLessThan(0.85 * start);
  await expect(widget.locator('.sb-plot .u-over')).toBeVisible();
  expect(errors).toEqual([]);
});

test('?backend=cpu: the neural field’s float64 twin draws the views in a Web Worker and says so', async ({
  page,
}) => {
  const errors = trackErrors(page);
  const widget = await openWidget(page, { ...SMALL, table: '14' }, '?backend=cpu');
  const notice = widget.locator('.sb-notice--warning');
  await expect(notice).toContainText('in a Web Worker');
  await expect(notice).toContainText('a neural field with 2^12 table entries per level (not 2^14)');
  await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
  const stats = await canvasStats(widget.locator('.sb-ir-novel canvas').nth(1));
  expect(stats.luminanceDeviation).toBeGreaterThan(0);
  const target = await canvasStats(widget.locator('.sb-ir-novel canvas').first());
  expect(target.luminanceDeviation).toBeGreaterThan(10);
  expect(errors).toEqual([]);
});
