// The book as a reader meets it: the home page lists the chapters, the theme button
// works, and pages stay readable without JavaScript, with their equation references
// resolved. Every page's typeset math, table of contents, chapter links, console and
// axe-core check in both themes are in tests/e2e/offline.spec.ts (see below).
import { expect, test, type Locator } from '@playwright/test';
import { bookPages, chapterPages, trackErrors, WIDGET_SELECTOR } from './support.ts';

const chapters = chapterPages();
const pages = bookPages();

/** The path a link leads to, resolved against its page. */
function resolvedPath(link: Locator): Promise<string> {
  return link.evaluate((a) => (a as HTMLAnchorElement).pathname);
}

test('the home page lists every chapter in order', async ({ page }) => {
  const errors = trackErrors(page);
  await page.goto('/index.html');
  const links = page.locator('ol.chapter-list a');
  await expect(links).toHaveCount(chapters.length);
  // Links are relative to their page (any base path works); they resolve to the chapters.
  for (const [index, chapter] of chapters.entries()) {
    expect(await links.nth(index).getAttribute('href')).not.toMatch(/^\//);
    expect(await resolvedPath(links.nth(index))).toBe(chapter.path);
  }
  expect(errors).toEqual([]);
});

// Each page's own checks (typeset math, table of contents, chapter links, no console
// errors, axe-core in both themes) run in tests/e2e/offline.spec.ts, on the page as the
// saved copy serves it: that spec opens every page and waits for every figure's first
// picture anyway, which is most of the cost, so the page is loaded and drawn once.

test('the theme button switches between light and dark', async ({ page }) => {
  await page.emulateMedia({ colorScheme: 'light' });
  await page.goto('/index.html');
  const button = page.locator('.theme-toggle');
  await expect(button).toBeVisible();
  await expect(page.locator('html')).toHaveAttribute('data-theme', 'light');
  const lightBackground = await page.evaluate(
    () => getComputedStyle(document.body).backgroundColor,
  );
  await button.click();
  await expect(page.locator('html')).toHaveAttribute('data-theme', 'dark');
  const darkBackground = await page.evaluate(() => getComputedStyle(document.body).backgroundColor);
  expect(darkBackground).not.toBe(lightBackground);
});

test.describe('without JavaScript', () => {
  test.use({ javaScriptEnabled: false });
  // Equation numbers and references are written at build time, so the pages need no
  // script for them (and loading every page with its figures drawing cost minutes).
  // One load of each page for both checks (they were two sweeps over the same pages).
  test('chapters are readable, widgets say what they need, and equation references resolve to numbered, existing equations', async ({
    page,
  }) => {
    let references = 0;
    for (const chapter of pages) {
      await page.goto(chapter.path);
      await expect(page.locator('main h1'), chapter.slug).toBeVisible();
      if (chapter.hasMath)
        await expect(page.locator('.katex').first(), chapter.slug).toBeAttached();
      for (const widget of await page.locator(WIDGET_SELECTOR).all()) {
        await expect(widget.locator('.widget-fallback'), chapter.slug).toContainText(
          'needs JavaScript',
        );
      }
      // One evaluation per page: each locator check would be a round trip.
      const found = await page.evaluate(() =>
        [...document.querySelectorAll('a.eqref')].map((reference) => {
          const href = reference.getAttribute('href') ?? '';
          return {
            text: reference.textContent ?? '',
            href,
            targets: href.startsWith('#')
              ? document.querySelectorAll(`[id="${CSS.escape(href.slice(1))}"]`).length
              : 1,
          };
        }),
      );
      references += found.length;
      expect(
        found.filter((r) => !/^\(\d+\.\d+\)$/.test(r.text) || r.targets !== 1),
        chapter.slug,
      ).toEqual([]);
    }
    expect(references).toBeGreaterThan(10);
  });
});
