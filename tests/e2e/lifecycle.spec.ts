// The widget lifecycle: a widget moved in the DOM (disconnected and connected again,
// as appendChild elsewhere does) must draw again. Every widget of the registry is put
// on one page, built while off screen, moved into view (it draws), then moved to
// another parent (it draws again). Before the fix a moved widget had dropped its
// IntersectionObserver on disconnect and never drew again.
import { expect, test, type Page } from '@playwright/test';
import { WIDGET_DEFINITIONS } from '../../src/widgets/catalog.ts';
import { trackErrors } from './support.ts';

/**
 * Attributes a widget needs to be meaningful on a page of its own, and smaller pictures
 * or fewer samples for the figures whose first frame takes many seconds on SwiftShader
 * (the ones tests/e2e/embed.spec.ts makes cheaper the same way): what is checked here is
 * that a moved widget draws again, which does not depend on the size of its work. The
 * translucent room's first frame took 18 s at its default 48×48 pixels (10 s at 16×16,
 * on a loaded machine).
 */
const REQUIRED_ATTRIBUTES: Readonly<Record<string, Record<string, string>>> = {
  exercise: { exercise: 'beer-law' },
  'translucent-room': { size: '16', spp: '2' },
  'translucent-render': { size: '32', spp: '6' },
  'volume-path-tracer': { spp: '1' },
};

const NAMES = WIDGET_DEFINITIONS.map((definition) => definition.entry.name);

/**
 * Opens the home page with one element of every widget in an off-screen holder. The
 * elements are inserted when parsing ends, before the page's module script runs, so the
 * script loads and defines every one of them.
 */
async function openAllWidgets(page: Page): Promise<void> {
  await page.addInitScript(
    ({ names, required }) => {
      document.addEventListener('readystatechange', () => {
        if (document.readyState !== 'interactive') return;
        const holder = document.createElement('div');
        holder.id = 'lifecycle-holder';
        // Laid out (so the shells are built) but far off screen: nothing draws yet.
        holder.style.cssText = 'position:absolute;left:-20000px;top:0;width:900px';
        for (const name of names) {
          const element = document.createElement(`sb-${name}`);
          element.id = `lifecycle-${name}`;
          for (const [key, value] of Object.entries(required[name] ?? {}))
            element.setAttribute(key, value);
          holder.appendChild(element);
        }
        const first = document.createElement('div');
        first.id = 'lifecycle-first';
        const second = document.createElement('div');
        second.id = 'lifecycle-second';
        document.body.prepend(first, second, holder);
      });
    },
    { names: NAMES, required: REQUIRED_ATTRIBUTES },
  );
  await page.goto('/index.html');
}

const renderedCount = (page: Page, name: string): Promise<number> =>
  page
    .locator(`#lifecycle-${name}`)
    .evaluate((element) => Number((element as HTMLElement).dataset['rendered'] ?? '0'));

test('every widget draws again after it is moved to another parent', async ({ page }) => {
  // Two frames per widget, one after the other; the path tracers' first frames are the
  // longest (each poll below still fails a widget that stops drawing after 30 s).
  test.setTimeout(NAMES.length * 40_000);
  const errors = trackErrors(page);
  await openAllWidgets(page);
  for (const name of NAMES) {
    await expect(page.locator(`#lifecycle-${name} .sb-widget`)).toHaveCount(1);
    expect(await renderedCount(page, name), `${name} draws only once on screen`).toBe(0);
  }
  for (const name of NAMES) {
    // Into view: the widget was built off screen and connected again here.
    await page.evaluate((id) => {
      const element = document.getElementById(id);
      if (element) document.getElementById('lifecycle-first')?.appendChild(element);
      window.scrollTo(0, 0);
    }, `lifecycle-${name}`);
    await expect
      .poll(() => renderedCount(page, name), {
        timeout: 30_000,
        // Every 100 ms: the default back-off (up to 1 s) adds about half a second to each
        // of the two waits of every widget, one after the other.
        intervals: [100],
        message: `${name} draws`,
      })
      .toBeGreaterThan(0);
    const before = await renderedCount(page, name);
    // Moved again, to another parent: it must draw again without any input.
    await page.evaluate((id) => {
      const element = document.getElementById(id);
      if (element) document.getElementById('lifecycle-second')?.appendChild(element);
      window.scrollTo(0, 0);
    }, `lifecycle-${name}`);
    await expect
      .poll(() => renderedCount(page, name), {
        timeout: 30_000,
        intervals: [100],
        message: `${name} draws again`,
      })
      .toBeGreaterThan(before);
    // Off the page for good: it stops (and a defined widget releases its resources).
    await page.evaluate((id) => document.getElementById(id)?.remove(), `lifecycle-${name}`);
  }
  expect(errors).toEqual([]);
});
