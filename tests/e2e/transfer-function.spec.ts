// <sb-transfer-function> in Chromium with WebGPU (SwiftShader): it draws the CT
// phantom, a preset and the arrow keys change the picture, the step size changes the
// error against the fine-step reference and the time, early termination reports its
// saving, the transfer-function handles work from the keyboard, a deep link restores
// the state, a garbled link is reported, presentation mode works, the sweep fits an
// order, and without WebGPU the float64 twin draws at reduced resolution and says so.
import { expect, test, type Locator } from '@playwright/test';
import {
  canvasStats,
  parseDisplayed,
  readout,
  trackErrors,
  waitForRender,
  widgetOpener,
  widgetPictureOpener,
} from './support.ts';

const CHAPTER = '/chapters/07-volume-visualization.html';
const ID = 'transfer-function-1';

const openWidget = widgetOpener(CHAPTER, 'sb-transfer-function', ID);
/** Opens the chapter waiting for the first picture only (for controls, notices and the cost line). */
const openPicture = widgetPictureOpener(CHAPTER, 'sb-transfer-function', ID);

function control(widget: Locator, name: string): Locator {
  return widget.locator(`input[type="number"][name="${name}"], select[name="${name}"]`);
}

/** Waits until the reference is ready and the RMSE is a number. */
async function waitForRmse(widget: Locator): Promise<number> {
  await expect
    .poll(async () => /^[\d.]+(×10[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)?$/.test(await readout(widget, 'rmse')), {
      timeout: 120_000,
    })
    .toBe(true);
  return parseDisplayed(await readout(widget, 'rmse'));
}

async function rendered(widget: Locator): Promise<number> {
  return Number(await widget.getAttribute('data-rendered'));
}

// The fine-step reference is computed on the GPU in bands after each new view or
// transfer function, and cached by them, not by the step: one page load pays for it
// once, and checks the error at two step sizes and the sweep over the step against
// it; early termination comes last, as its preset is a new transfer function.
test('draws the phantom on the GPU, with the time, the reference error and the steps; a larger step raises the RMSE against the cached reference, and the time and cost change; the sweep over the step size fits an order and can be cancelled; early termination stops most rays of the skin preset early, and off marches every step', async ({
  page,
}) => {
  test.setTimeout(600_000);
  const errors = trackErrors(page);
  const widget = await openWidget(page);
  const fine =
    await test.step('the phantom, the time, the reference error and the steps', async () => {
      const canvases = widget.locator('canvas.sb-canvas');
      await expect(canvases).toHaveCount(2);
      const image = await canvasStats(canvases.nth(0));
      expect(image.luminanceDeviation).toBeGreaterThan(10);
      expect(image.distinctColours).toBeGreaterThan(20);
      await expect(widget.locator('.sb-cost')).toContainText('WebGPU');
      await expect(widget.locator('.sb-cost')).toContainText('160×160 rays');
      expect(await readout(widget, 'time')).toMatch(/ms \((GPU timestamp query|wall time)/);
      expect(await readout(widget, 'steps')).toMatch(/of .* \(\d/);
      const rmse = await waitForRmse(widget);
      expect(rmse).toBeGreaterThan(0);
      expect(rmse).toBeLessThan(0.05);
      await expect(widget.locator('.sb-tf-reference')).toContainText('Reference ready');
      const error = await canvasStats(canvases.nth(1));
      expect(error.distinctColours).toBeGreaterThan(5);
      await expect
        .poll(() => readout(widget, 'saving'), { timeout: 60_000 })
        .toMatch(/% of the steps/);
      return rmse;
    });
  await test.step('a larger step raises the RMSE against the cached reference; the time and cost change', async () => {
    const time = await readout(widget, 'time');
    const count = await rendered(widget);
    await control(widget, 'step').fill('3');
    await control(widget, 'step').press('Enter');
    await waitForRender(widget, count + 1);
    await expect(widget.locator('.sb-cost')).toContainText('Δs = 3 voxels');
    // The reference depends on the transfer function and the view, not the step: the
    // RMSE is there at once. The twin gives ≈ 5× the error at 2 voxels, more at 3 (O(Δs²)).
    const coarse = await waitForRmse(widget);
    expect(coarse).toBeGreaterThan(2 * fine);
    expect(await readout(widget, 'time')).not.toBe(time);
    await expect(widget.locator('.sb-tf-reference')).toContainText('Reference ready');
  });
  await test.step('the sweep over the step size completes with a fitted order, and can be cancelled', async () => {
    // It sweeps its own Δs = 4, 2, 1, ½ voxel against the reference of this transfer
    // function and view, cached above, whatever step is chosen.
    const run = widget.getByRole('button', { name: /Run sweep/ });
    await run.click();
    await expect(widget.locator('.sb-tf-sweep-status')).toContainText('Sweep done', {
      timeout: 220_000,
    });
    await expect(widget.locator('.sb-sweep progress')).toHaveJSProperty('value', 4);
    // Twin at 32×32: RMSE 4.6e-2, 1.4e-2, 2.8e-3, 1.0e-3 at Δs = 4, 2, 1, ½ voxel: q = 1.87.
    const q = parseDisplayed((await readout(widget, 'slope')).replace(/^q = /, ''));
    expect(q).toBeGreaterThan(1.3);
    expect(q).toBeLessThan(2.8);
    await expect(widget.locator('.sb-plot .u-over').last()).toBeVisible();
    await run.click();
    await widget.getByRole('button', { name: 'Cancel', exact: true }).click();
    await expect(widget.locator('.sb-tf-sweep-status')).toContainText('cancelled');
    await expect(run).toBeEnabled();
  });
  await test.step('early termination: the skin preset stops most rays early; switching it off marches every step', async () => {
    // Back to the default step of one voxel, where the saving below was derived.
    let count = await rendered(widget);
    await control(widget, 'step').fill('1');
    await control(widget, 'step').press('Enter');
    await waitForRender(widget, count + 1);
    await expect(widget.locator('.sb-cost')).toContainText('Δs = 1 voxel');
    count = await rendered(widget);
    await widget.locator('canvas.sb-tf-volume').focus();
    await page.keyboard.press('2');
    await waitForRender(widget, count + 1);
    await expect(widget.locator('.sb-preset-toast')).toContainText('skin');
    const steps = await readout(widget, 'steps');
    const share = Number(/\(([\d.]+)%\)/.exec(steps)?.[1]);
    // Opacity 0.4–0.6 per voxel from the skin inward: T < 0.01 within ~10 voxels.
    expect(share).toBeLessThan(80);
    await expect
      .poll(() => readout(widget, 'saving'), { timeout: 150_000 })
      .toMatch(/% of the steps/);
    const saving = parseDisplayed(await readout(widget, 'saving'));
    expect(saving).toBeGreaterThan(20);
    const again = await rendered(widget);
    await control(widget, 'termination').selectOption('off');
    await waitForRender(widget, again + 1);
    await expect.poll(() => readout(widget, 'steps')).toContain('every ray to its end');
    await expect.poll(() => readout(widget, 'bias')).toContain('no termination');
  });
  expect(errors).toEqual([]);
});

// One page load for what a reader does with the view and the transfer function: each
// step starts from the state the previous one left, so its expected values follow it.
test('the arrow keys orbit the camera; a preset changes the transfer function, the picture and the link, and keeps the view; a drag orbits the camera; the opacity handles move with the arrow keys; presentation mode', async ({
  page,
}) => {
  test.setTimeout(180_000);
  const errors = trackErrors(page);
  // A step other than the default, to see that a preset keeps it.
  const widget = await openWidget(page, { step: '1.5' });
  const canvas = widget.locator('canvas.sb-tf-volume');
  await test.step('the arrow keys on the image orbit the camera', async () => {
    await expect(control(widget, 'azimuth')).toHaveValue('35');
    const before = await canvasStats(canvas);
    const count = await rendered(widget);
    await canvas.focus();
    await page.keyboard.press('ArrowLeft');
    await expect(control(widget, 'azimuth')).toHaveValue('40');
    await page.keyboard.press('ArrowUp');
    await expect(control(widget, 'elevation')).toHaveValue('20');
    await waitForRender(widget, count + 1);
    await expect
      .poll(async () => (await canvasStats(canvas)).png.equals(before.png), { timeout: 30_000 })
      .toBe(false);
    await expect.poll(() => page.url()).toContain(`${ID}.azimuth=40`);
  });
  await test.step('a preset changes the transfer function, the picture and the link, and keeps the view', async () => {
    // The picture the arrow keys drew is complete (waited for above).
    const before = await canvasStats(widget.locator('canvas.sb-canvas').first());
    const count = await rendered(widget);
    await widget.getByRole('button', { name: /bone \(> 300 HU\)/ }).click();
    await waitForRender(widget, count + 1);
    await expect(control(widget, 'colormap')).toHaveValue('bone');
    await expect(control(widget, 'hu-3')).toHaveValue('250');
    await expect(control(widget, 'azimuth')).toHaveValue('40');
    await expect(control(widget, 'elevation')).toHaveValue('20');
    await expect(control(widget, 'step')).toHaveValue('1.5');
    const after = await canvasStats(widget.locator('canvas.sb-canvas').first());
    expect(after.png.equals(before.png)).toBe(false);
    await expect.poll(() => page.url()).toContain(`${ID}.colormap=bone`);
  });
  await test.step('dragging the image orbits the camera', async () => {
    const box = (await canvas.boundingBox())!;
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width / 2 + 40, box.y + box.height / 2, { steps: 4 });
    await page.mouse.up();
    // 0.5° per pixel to the right: the azimuth falls by 20°, from 40° to 20°.
    await expect(control(widget, 'azimuth')).toHaveValue('20');
    await expect(control(widget, 'elevation')).toHaveValue('20');
  });
  await test.step('the opacity handles move with the arrow keys and update the link', async () => {
    // Control point 3 of the bone preset: 250 HU, opacity 0; one key step is 10 HU, 0.01.
    const handle = widget.locator('.sb-tf-handle').nth(2);
    await expect(handle).toHaveAttribute('aria-label', /Control point 3: 250 HU, opacity 0\.00/);
    await handle.focus();
    await page.keyboard.press('ArrowUp');
    await page.keyboard.press('ArrowRight');
    await expect(control(widget, 'opacity-3')).toHaveValue('0.01');
    await expect(control(widget, 'hu-3')).toHaveValue('260');
    await expect(handle).toHaveAttribute('aria-label', /260 HU, opacity 0\.01/);
    await expect.poll(() => page.url()).toContain(`${ID}.hu-3=260`);
  });
  await test.step('presentation mode: F enters, number keys recall the presets, Esc leaves', async () => {
    await widget.locator('select[name="colormap"]').focus();
    await page.keyboard.press('f');
    const shell = widget.locator('.sb-widget');
    await expect(shell).toHaveClass(/is-presenting/);
    await expect(widget.locator('canvas.sb-tf-volume')).toBeInViewport();
    await page.keyboard.press('1');
    await expect(control(widget, 'colormap')).toHaveValue('tissue');
    await page.keyboard.press('3');
    await expect(widget.locator('.sb-preset-toast')).toHaveText('3 · bone (> 300 HU)');
    await expect(control(widget, 'colormap')).toHaveValue('bone');
    await page.keyboard.press('Escape');
    await expect(shell).not.toHaveClass(/is-presenting/);
  });
  expect(errors).toEqual([]);
});

test('a deep link restores the state exactly', async ({ page }) => {
  // Controls, the cost line and the panels are the same in every refinement stage.
  const widget = await openPicture(page, {
    step: '0.5',
    termination: 'off',
    colormap: 'viridis',
    azimuth: '-60',
    elevation: '-10',
    'hu-4': '120',
    'opacity-4': '0.2',
    panel: 'steps',
  });
  await expect(control(widget, 'step')).toHaveValue('0.5');
  await expect(control(widget, 'termination')).toHaveValue('off');
  await expect(control(widget, 'colormap')).toHaveValue('viridis');
  await expect(control(widget, 'azimuth')).toHaveValue('-60');
  await expect(control(widget, 'hu-4')).toHaveValue('120');
  await expect(widget.locator('.sb-cost')).toContainText('Δs = 0.5 voxels');
  await expect(widget.locator('.sb-image-panel figcaption').nth(1)).toContainText('Steps taken');
  await expect(widget.locator('.sb-notice--warning')).toHaveCount(0);
});

test('a garbled link still opens and says what it clamped, sorted or ignored', async ({ page }) => {
  const errors = trackErrors(page);
  // The notices come with the first picture, which is enough to see that it drew.
  const widget = await openPicture(page, {
    'hu-2': '2000',
    'opacity-3': '7',
    step: 'fast',
    bogus: '1',
  });
  const notices = widget.locator('.sb-notice--warning');
  await expect(notices.filter({ hasText: 'clamped to 1' })).toHaveCount(1);
  await expect(notices.filter({ hasText: 'is not a number' })).toHaveCount(1);
  await expect(notices.filter({ hasText: 'not in increasing order' })).toHaveCount(1);
  await expect(notices.filter({ hasText: 'bogus' })).toHaveCount(1);
  const stats = await canvasStats(widget.locator('canvas.sb-canvas').first());
  expect(stats.luminanceDeviation).toBeGreaterThan(5);
  expect(errors).toEqual([]);
});

test('?backend=cpu: the float64 twin draws at reduced resolution, says so, and computes the error', async ({
  page,
}) => {
  test.setTimeout(180_000);
  const errors = trackErrors(page);
  const widget = await openWidget(page, { step: '2' }, '?backend=cpu');
  await expect(widget.locator('.sb-notice--warning')).toContainText('WebGPU is not available');
  await expect(widget.locator('.sb-cost')).toContainText('CPU fallback');
  await expect(widget.locator('.sb-cost')).toContainText('64×64 rays');
  const stats = await canvasStats(widget.locator('canvas.sb-canvas').first());
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  expect(await readout(widget, 'time')).toContain('CPU wall time');
  expect(await waitForRmse(widget)).toBeGreaterThan(0);
  expect(errors).toEqual([]);
});
