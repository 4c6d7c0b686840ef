// Printing a page with figures: each figure prints its current picture, readouts
// and settings (src/widgets/base/print.ts and the print stylesheet in book.css).
// Figures draw only once they scroll into view, and `beforeprint` cannot wait for a
// GPU, so the book's own print command — the header's Print button, and Ctrl/⌘+P —
// first draws every figure that has not drawn yet, then opens the print dialog.
// Printing from the browser's menu still works: figures on screen (or drawn before)
// print their picture; the others print a note saying they were not drawn.
import { renderAllForPrint } from '../widgets/base/widgetElement.ts';

let printing = false;

/** Whether a widget on the page has not drawn a frame yet. */
function undrawnFigures(): boolean {
  return [...document.querySelectorAll<HTMLElement>('.sb-widget')].some((root) => {
    const host = root.parentElement;
    return host !== null && Number(host.dataset['rendered'] ?? '0') === 0;
  });
}

/** Draws every figure, then opens the print dialog; progress goes to `status`. */
export async function printWithFigures(status?: HTMLElement): Promise<void> {
  if (printing) return;
  printing = true;
  try {
    await renderAllForPrint((done, total) => {
      if (status)
        status.textContent =
          done < total ? `Drawing the figures for printing: ${done + 1} of ${total}…` : '';
    });
  } finally {
    printing = false;
    if (status) status.textContent = '';
  }
  window.print();
}

export function setupPrint(): void {
  // Only pages with figures need the command; others print as they are.
  if (!hasWidgetElements()) return;
  const header = document.querySelector('.site-header');
  const status = document.createElement('span');
  status.className = 'print-status';
  status.setAttribute('role', 'status');
  const button = document.createElement('button');
  button.type = 'button';
  button.className = 'button print-button';
  button.textContent = 'Print';
  button.title = 'Print or save as PDF, with every figure drawn (Ctrl+P)';
  button.addEventListener('click', () => void printWithFigures(status));
  const toggle = header?.querySelector('.theme-toggle');
  if (toggle) toggle.before(button, status);
  else header?.append(button, status);

  document.addEventListener('keydown', (event) => {
    if (!(event.ctrlKey || event.metaKey) || event.altKey || event.key.toLowerCase() !== 'p')
      return;
    // Everything drawn already: the browser's own printing is enough (beforeprint copies).
    if (!undrawnFigures()) return;
    event.preventDefault();
    void printWithFigures(status);
  });
}

/** Widgets are custom elements named sb-…; they may not have built their shell yet. */
function hasWidgetElements(): boolean {
  return [...document.querySelectorAll('body *')].some((element) =>
    element.localName.startsWith('sb-'),
  );
}
