// The book as a reader meets it: every page loads without errors, math is
// typeset, navigation works, the pages pass an accessibility check in both themes,
// and pages stay readable without JavaScript.
import { expect, test, type Locator, type Page } from '@playwright/test';
import {
  axeViolations,
  bookPages,
  chapterPages,
  trackErrors,
  waitForPicture,
  WIDGET_SELECTOR,
} from './support.ts';

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

/**
 * The shader-library appendix has one entry per library function (328), each written by
 * the same template (src/book/build/appendix.ts: heading, signature, prose with math,
 * twin note). axe checks the page with the first two entries of each module (about 50):
 * every part the template writes, in every module, at a twentieth of the cost. The
 * table of contents and every entry's id were checked on the whole page before.
 */
async function sampleAppendixEntries(page: Page): Promise<void> {
  const kept = await page.evaluate(() => {
    const perModule = new Map<string, number>();
    let count = 0;
    for (const entry of document.querySelectorAll('section.api-entry')) {
      const module = entry.id.split('-')[0] ?? '';
      const seen = (perModule.get(module) ?? 0) + 1;
      perModule.set(module, seen);
      if (seen > 2) entry.remove();
      else count += 1;
    }
    return count;
  });
  expect(kept).toBeGreaterThan(20);
}

// One test per page: loading a page and drawing its widgets on SwiftShader is most of the
// cost, so the page is loaded once and checked in the light theme, then switched to the
// dark theme with the page's own button (as a reader does) and checked again.
for (const [index, chapter] of pages.entries()) {
  test(`${chapter.slug}: typeset math, table of contents, chapter links, no console errors, axe-core in both themes`, async ({
    page,
  }) => {
    test.setTimeout(300_000); // two axe-core runs after the widgets have drawn (the appendix is long)
    const errors = trackErrors(page);
    await page.emulateMedia({ colorScheme: 'light' });
    await page.goto(chapter.path);
    await expect(page.locator('main h1')).toBeVisible();
    await expect(page.locator('nav.toc a').first()).toBeVisible();
    // KaTeX ran at build time: the HTML already holds typeset math.
    const raw = await (await page.request.get(chapter.path)).text();
    if (chapter.hasMath) expect(raw).toContain('class="katex');
    expect(raw).not.toMatch(/\$\$|\\label\{/);
    // Every entry leads to exactly one element of the page (one evaluation: the appendix's
    // table of contents has over 200 entries, each a round trip as a locator check).
    const tocTargets = await page.evaluate(() =>
      [...document.querySelectorAll('nav.toc a')].map((link) => {
        const id = (link.getAttribute('href') ?? '').slice(1);
        return { id, count: document.querySelectorAll(`[id="${CSS.escape(id)}"]`).length };
      }),
    );
    expect(tocTargets.length).toBeGreaterThan(0);
    expect(tocTargets.filter((target) => target.count !== 1)).toEqual([]);
    const previous = pages[index - 1];
    const next = pages[index + 1];
    if (previous) expect(await resolvedPath(page.locator('a[rel="prev"]'))).toBe(previous.path);
    if (next) expect(await resolvedPath(page.locator('a[rel="next"]'))).toBe(next.path);
    for (const widget of await page.locator('[class="sb-widget"]').all())
      await widget.scrollIntoViewIfNeeded();
    // The first picture is enough here: each widget's own spec checks its final numbers.
    for (const widget of await page.locator(WIDGET_SELECTOR).all()) await waitForPicture(widget);
    expect(errors).toEqual([]);

    if (chapter.slug === 'appendix-shader-library') await sampleAppendixEntries(page);
    expect(await axeViolations(page), 'light theme').toEqual([]);
    await page.locator('.theme-toggle').click();
    await expect(page.locator('html')).toHaveAttribute('data-theme', 'dark');
    expect(await axeViolations(page, true), 'dark theme').toEqual([]);
    expect(errors).toEqual([]);
  });
}

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
  test('chapters are readable and widgets say what they need', async ({ page }) => {
    for (const chapter of pages) {
      await page.goto(chapter.path);
      await expect(page.locator('main h1')).toBeVisible();
      if (chapter.hasMath) await expect(page.locator('.katex').first()).toBeAttached();
      for (const widget of await page.locator(WIDGET_SELECTOR).all()) {
        await expect(widget.locator('.widget-fallback')).toContainText('needs JavaScript');
      }
    }
  });
  // Equation numbers and references are written at build time, so the pages need no
  // script for them (and loading every page with its figures drawing cost minutes).
  test('equation references resolve to numbered, existing equations', async ({ page }) => {
    let references = 0;
    for (const chapter of pages) {
      await page.goto(chapter.path);
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
