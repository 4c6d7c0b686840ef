// Display math, tables and code fit the reading column: at 1280×800 no display
// equation, table, code block or inline formula is wider than the column it sits in;
// on a phone (390×844) whatever still overflows scrolls inside a labelled,
// keyboard-focusable region (with a fade at its overflowing edge, book.css) and
// nothing widens the page. One test per viewport walks every page.
import { expect, test, type Page } from '@playwright/test';
import { bookPages } from './support.ts';

const PAGES = [{ slug: 'home', path: '/index.html' }, ...bookPages()];

/** One element that does not fit, as the page measured it. */
interface Overflow {
  what: string;
  /** Pixels past the column (or hidden inside its own scroll box). */
  by: number;
  /** The scroll container that holds it, if any: focusable, with a label? */
  scroller: { focusable: boolean; label: string } | null;
}

/**
 * Every display equation (`.equation`, KaTeX's `.katex-display`), table, code block and
 * inline formula of the page's prose that is wider than its column, plus the page's
 * own horizontal overflow. Widgets lay out their own controls and are left out, except
 * an exercise's statement (Markdown rendered by the chapter build).
 */
async function measure(page: Page): Promise<{ items: Overflow[]; pageOverflow: number }> {
  await page.evaluate(() => document.fonts.ready.then(() => undefined));
  return page.evaluate(() => {
    const inWidget = (element: Element): boolean => {
      for (let node: Element | null = element; node; node = node.parentElement) {
        if (node.matches('.sb-exercise-statement')) return false;
        if (node.localName.startsWith('sb-')) return true;
      }
      return false;
    };
    const scrolls = (element: Element): boolean =>
      /auto|scroll/.test(getComputedStyle(element).overflowX);
    /** Right edge of an element's content box, where its children must end. */
    const contentRight = (element: Element): number => {
      const style = getComputedStyle(element);
      return (
        element.getBoundingClientRect().right -
        parseFloat(style.borderRightWidth) -
        parseFloat(style.paddingRight)
      );
    };
    const describe = (element: Element): string => {
      const tex = element.querySelector('annotation')?.textContent?.trim();
      const id = element.closest('[id]')?.id ?? '';
      const text = tex ?? element.textContent?.trim().slice(0, 60) ?? '';
      return `${element.localName}.${[...element.classList].join('.')}#${id}: ${text.replace(/\s+/g, ' ').slice(0, 90)}`;
    };
    const items: Overflow[] = [];
    const candidates = document.querySelectorAll<HTMLElement>(
      'main .equation, main .katex-display, main table, main pre, main .katex',
    );
    for (const element of candidates) {
      if (inWidget(element) || element.getClientRects().length === 0) continue;
      // A display is measured once, as its .equation box; a formula, as the display or
      // (inline) on its own.
      if (element.matches('.katex-display') && element.closest('.equation')) continue;
      if (element.matches('.katex') && element.closest('.katex-display')) continue;
      let by = 0;
      if (scrolls(element)) by = element.scrollWidth - element.clientWidth;
      const parent = element.parentElement;
      if (parent) by = Math.max(by, element.getBoundingClientRect().right - contentRight(parent));
      if (by <= 1) continue;
      let scroller: Element | null = null;
      if (scrolls(element) && element.scrollWidth > element.clientWidth + 1) scroller = element;
      else {
        for (
          let node = element.parentElement;
          node && node !== document.body;
          node = node.parentElement
        )
          if (scrolls(node) && node.scrollWidth > node.clientWidth + 1) {
            scroller = node;
            break;
          }
      }
      items.push({
        what: describe(element),
        by: Math.round(by),
        scroller: scroller && {
          focusable: (scroller as HTMLElement).tabIndex >= 0,
          label:
            scroller.getAttribute('aria-label') ??
            (scroller.getAttribute('aria-labelledby') ? 'labelledby' : ''),
        },
      });
    }
    return {
      items,
      pageOverflow: document.documentElement.scrollWidth - document.documentElement.clientWidth,
    };
  });
}

test.describe('at 1280×800', () => {
  test.use({ viewport: { width: 1280, height: 800 } });
  test('every display equation, table, code block and formula fits its column', async ({
    page,
  }) => {
    test.setTimeout(180_000);
    const problems: string[] = [];
    for (const { slug, path } of PAGES) {
      await page.goto(path);
      const { items, pageOverflow } = await measure(page);
      for (const item of items) problems.push(`${slug}: ${item.what} — ${item.by} px too wide`);
      if (pageOverflow > 0)
        problems.push(`${slug}: the page scrolls sideways by ${pageOverflow} px`);
    }
    expect(problems).toEqual([]);
  });
});

test.describe('at 390×844', () => {
  test.use({ viewport: { width: 390, height: 844 } });
  test('what is wider than the screen scrolls in a labelled, focusable region; the page does not', async ({
    page,
  }) => {
    test.setTimeout(180_000);
    const problems: string[] = [];
    for (const { slug, path } of PAGES) {
      await page.goto(path);
      const { items, pageOverflow } = await measure(page);
      for (const item of items) {
        if (!item.scroller)
          problems.push(`${slug}: ${item.what} runs ${item.by} px past the column`);
        else if (!item.scroller.focusable || !item.scroller.label)
          problems.push(
            `${slug}: ${item.what} scrolls ${item.by} px without ${item.scroller.focusable ? 'a label' : 'a tab stop'}`,
          );
      }
      if (pageOverflow > 0)
        problems.push(`${slug}: the page scrolls sideways by ${pageOverflow} px`);
    }
    expect(problems).toEqual([]);
  });
});
