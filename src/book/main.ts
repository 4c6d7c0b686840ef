// The script of every page: theme switch, quiz checking, and the widgets the page
// embeds (each loaded on demand, each isolated so that one failing widget never
// takes down the page).

// The widgets' host rules (display: block), generated from their definitions.
import 'virtual:scatterbook/widget-hosts.css';
import { setupThemeToggle } from './theme.ts';
import { setupQuizzes } from './quiz.ts';
import { setupDeck } from './deck.ts';
import { setupPrint } from './print.ts';
import { setupOfflineReading } from './offline.ts';

async function loadWidgets(): Promise<void> {
  // The registry (every widget's definition, ~25 KB gzip) is loaded only by pages that
  // embed a widget: the home page, chapter 1 and the appendix have none.
  const hasWidget = [...document.body.querySelectorAll('*')].some((element) =>
    element.localName.startsWith('sb-'),
  );
  if (!hasWidget) return;
  const [{ defineWidgetElement, WIDGETS }, { tagName }] = await Promise.all([
    import('../widgets/registry.ts'),
    import('../widgets/base/definition.ts'),
  ]);
  await Promise.all(
    WIDGETS.map(async (definition) => {
      const elements = document.querySelectorAll(tagName(definition));
      if (elements.length === 0) return;
      try {
        await defineWidgetElement(definition);
      } catch (error) {
        for (const element of elements) {
          const message = document.createElement('p');
          message.className = 'sb-notice sb-notice--error';
          message.setAttribute('role', 'alert');
          message.textContent = `This figure could not be loaded: ${error instanceof Error ? error.message : String(error)}`;
          element.replaceChildren(message);
        }
      }
    }),
  );
}

/**
 * A region that scrolls sideways (a wide equation or table on a phone, a long code
 * line) must be reachable by keyboard (WCAG 2.1.1) and say what it is; only those
 * that actually overflow get a tab stop, and lose it again when the window widens.
 */
function makeScrollableRegionsFocusable(): void {
  for (const region of document.querySelectorAll<HTMLElement>('.equation, .table-scroll, pre')) {
    const overflows = region.scrollWidth > region.clientWidth + 1;
    if (overflows && !region.hasAttribute('tabindex')) {
      region.tabIndex = 0;
      region.dataset['scrollRegion'] = '';
      region.setAttribute('role', 'region');
      region.setAttribute('aria-label', `${scrollRegionName(region)} (scrolls sideways)`);
    } else if (!overflows && region.hasAttribute('data-scroll-region')) {
      for (const name of ['tabindex', 'role', 'aria-label', 'data-scroll-region'])
        region.removeAttribute(name);
    }
  }
}

function scrollRegionName(region: HTMLElement): string {
  if (region.classList.contains('equation')) {
    const number = region.querySelector('.equation-number')?.textContent;
    return number ? `Equation ${number}` : 'Equation';
  }
  if (region.classList.contains('table-scroll')) {
    const caption = region.querySelector('caption')?.textContent?.trim();
    return caption ? `Table: ${caption}` : 'Table';
  }
  return 'Code';
}

setupThemeToggle();
makeScrollableRegionsFocusable();
// Widths change once the KaTeX fonts arrive and when the window is resized.
void document.fonts.ready.then(makeScrollableRegionsFocusable);
window.addEventListener('load', makeScrollableRegionsFocusable);
let resizeTimer: ReturnType<typeof setTimeout> | undefined;
window.addEventListener('resize', () => {
  clearTimeout(resizeTimer);
  resizeTimer = setTimeout(makeScrollableRegionsFocusable, 150);
});
setupQuizzes();
setupDeck();
setupPrint();
void loadWidgets();
// The service worker that saves the book for offline reading, and its status line.
void setupOfflineReading().catch((error: unknown) => console.error('offline reading:', error));
