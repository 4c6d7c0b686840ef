// Lecture use: the demo deck walked with the keyboard, slide deep links,
// presentation mode at projector resolutions, preset names, and links with
// garbage in the hash (which must open without errors).
import AxeBuilder from '@axe-core/playwright';
import { expect, test } from '@playwright/test';
import { canvasStats, trackErrors, waitForRender, WIDGET_SELECTOR } from './support.ts';

const CHAPTER = '/chapters/02-extinction-and-transmittance.html';

test('the deck walks slide by slide with the keyboard, each slide a deep link', async ({
  page,
}) => {
  const errors = trackErrors(page);
  await page.goto('/deck.html');
  const slides = page.locator('.deck-slide');
  const count = await slides.count();
  expect(count).toBeGreaterThanOrEqual(2);
  // Every slide draws its widget on a CPU WebGPU: allow each slide its own time.
  test.setTimeout(30_000 + count * 12_000);
  for (let i = 1; i <= count; i++) {
    const slide = page.locator(`#slide-${i}`);
    await expect(slide).toBeVisible();
    await expect(page.locator('.deck-slide:visible')).toHaveCount(1);
    await expect(page.locator('.deck-current')).toHaveText(String(i));
    expect(page.url()).toContain(`slide=${i}`);
    const widget = slide.locator(WIDGET_SELECTOR);
    await waitForRender(widget);
    const stats = await canvasStats(widget.locator('canvas.sb-canvas').first());
    expect(stats.luminanceDeviation).toBeGreaterThan(10);
    await page.keyboard.press('ArrowRight');
  }
  await expect(page.locator('.deck-current')).toHaveText(String(count));
  await page.keyboard.press('Home');
  await expect(page.locator('.deck-current')).toHaveText('1');
  await page.keyboard.press('End');
  await expect(page.locator('.deck-current')).toHaveText(String(count));
  await page.keyboard.press('ArrowLeft');
  await expect(page.locator('.deck-current')).toHaveText(String(count - 1));
  await page.getByRole('button', { name: 'Previous slide' }).click();
  await expect(page.locator('.deck-current')).toHaveText(String(count - 2));
  expect(errors).toEqual([]);
});

test('a slide link opens that slide with its widget state', async ({ page }) => {
  await page.goto('/deck.html#slide=3&slide-3-widget.split=4');
  await expect(page.locator('#slide-3')).toBeVisible();
  const widget = page.locator('#slide-3 sb-beer-law');
  await waitForRender(widget);
  await expect(widget.locator('select[name="profile"]')).toHaveValue('layered');
  await expect(widget.locator('input[type="number"][name="split"]')).toHaveValue('4');
});

for (const [width, height] of [
  [1280, 720],
  [800, 600],
] as const) {
  test(`presentation mode at ${width}×${height}: fills the screen with larger type`, async ({
    page,
  }, info) => {
    await page.setViewportSize({ width, height });
    await page.goto(CHAPTER);
    const widget = page.locator('sb-beer-law').first();
    await waitForRender(widget);
    const title = widget.locator('.sb-widget-title');
    const normalSize = await title.evaluate((el) => parseFloat(getComputedStyle(el).fontSize));
    await widget.locator('input[type="range"]').first().focus();
    await page.keyboard.press('f');
    const shell = widget.locator('.sb-widget');
    await expect(shell).toHaveClass(/is-presenting/);
    const box = await shell.boundingBox();
    expect(box?.x).toBe(0);
    expect(box?.y).toBe(0);
    expect(box?.width).toBe(width);
    expect(box?.height).toBe(height);
    const presentedSize = await title.evaluate((el) => parseFloat(getComputedStyle(el).fontSize));
    expect(presentedSize).toBeGreaterThanOrEqual(1.4 * normalSize);
    await expect(widget.locator('canvas.sb-canvas')).toBeInViewport();
    await page.screenshot({ path: info.outputPath(`presenting-${width}x${height}.png`) });
    await page.keyboard.press('3');
    await expect(widget.locator('.sb-preset-toast')).toHaveText('3 · layered');
    await expect(widget.locator('select[name="profile"]')).toHaveValue('layered');
    await page.keyboard.press('Escape');
    await expect(shell).not.toHaveClass(/is-presenting/);
    expect(page.url()).not.toContain('present=1');
  });
}

test('a link with garbage in the hash opens without errors and says what it ignored', async ({
  page,
}) => {
  const errors = trackErrors(page);
  await page.goto(
    `${CHAPTER}#%%zz&&==&beer-law-1.sigma-a=NaN&beer-law-1.bogus=1&beer-law-1.thickness=1e400&v=99`,
  );
  const widget = page.locator('sb-beer-law').first();
  await waitForRender(widget);
  const notices = widget.locator('.sb-notice--warning');
  await expect(notices.filter({ hasText: 'unknown setting “bogus”' })).toHaveCount(1);
  await expect(notices.filter({ hasText: 'format version “99”' })).toHaveCount(1);
  await expect(notices.filter({ hasText: 'not a number' })).toHaveCount(1);
  await expect(widget.locator('input[type="number"][name="thickness"]')).toHaveValue('10');
  const stats = await canvasStats(widget.locator('canvas.sb-canvas').first());
  expect(stats.luminanceDeviation).toBeGreaterThan(10);
  // The other widget on the page is untouched by the first one's garbage.
  const second = page.locator('sb-beer-law').nth(1);
  await waitForRender(second);
  await expect(second.locator('.sb-notice--warning')).toHaveCount(0);
  expect(errors).toEqual([]);
});

test('links written by the widgets carry the format version', async ({ page }) => {
  await page.goto(CHAPTER);
  const widget = page.locator('sb-beer-law').first();
  await waitForRender(widget);
  await widget.locator('select[name="profile"]').selectOption('smooth');
  await expect.poll(() => page.url()).toContain('v=1');
});

for (const path of ['/index.html', '/deck.html']) {
  for (const theme of ['light', 'dark'] as const) {
    test(`${path} passes the axe-core accessibility check (${theme} theme)`, async ({ page }) => {
      await page.emulateMedia({ colorScheme: theme });
      await page.goto(path);
      for (const widget of await page.locator(WIDGET_SELECTOR).filter({ visible: true }).all())
        await waitForRender(widget);
      const results = await new AxeBuilder({ page })
        .withTags(['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa'])
        .analyze();
      expect(
        results.violations.map(
          (v) => `${v.id}: ${v.nodes.map((n) => n.target.join(' ')).join(', ')}`,
        ),
      ).toEqual([]);
    });
  }
}

test('a deep link restores the picture exactly, not only the numbers', async ({ page }) => {
  await page.goto(
    `${CHAPTER}#beer-law-1.sigma-a=1.5&beer-law-1.thickness=3&beer-law-1.profile=smooth&v=1`,
  );
  const linked = page.locator('sb-beer-law').first();
  await waitForRender(linked);
  const fromLink = await canvasStats(linked.locator('canvas.sb-canvas'));
  await page.goto('about:blank');
  await page.goto(CHAPTER);
  const widget = page.locator('sb-beer-law').first();
  await waitForRender(widget);
  const rendered = Number(await widget.getAttribute('data-rendered'));
  await widget.locator('select[name="profile"]').selectOption('smooth');
  await widget.locator('input[type="number"][name="thickness"]').fill('3');
  await widget.locator('input[type="number"][name="thickness"]').dispatchEvent('change');
  await widget.locator('input[type="number"][name="sigma-a"]').fill('1.5');
  await widget.locator('input[type="number"][name="sigma-a"]').dispatchEvent('change');
  await waitForRender(widget, rendered + 1);
  await expect(widget.locator('input[type="number"][name="sigma-a"]')).toHaveValue('1.5');
  await expect
    .poll(
      async () =>
        (await canvasStats(widget.locator('canvas.sb-canvas').first())).png.equals(fromLink.png),
      { timeout: 10_000 },
    )
    .toBe(true);
});
