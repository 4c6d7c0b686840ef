// Printing (or saving as PDF) a page shows each figure's current picture, not an
// empty canvas. Right before printing (the `beforeprint` event, or the book's own
// print command, src/book/print.ts) every canvas of a widget is copied into a 2D
// canvas (class sb-print-image) next to it; the print stylesheet (book.css) shows
// the copy in the canvas's place and hides the canvas and the controls.
//
// Why a copy: a WebGPU canvas keeps its picture only until the browser presents it,
// and prints (or is read) as transparent black after that (Chromium). Its owner
// therefore registers a synchronous re-draw of its last frame (keepForPrint);
// printing runs it and copies the canvas in the same task, while the fresh frame is
// still current. Why a 2D canvas and not an <img>: Chromium fires beforeprint when it
// prints (to PDF too) and lays the page out at once, and an <img> given a new data:
// URL in beforeprint is decoded asynchronously, so it printed as an empty box; a 2D
// canvas holds its pixels as soon as drawImage returns.
import { context2d } from './canvas2d.ts';

const redraws = new WeakMap<HTMLCanvasElement, () => void>();

/**
 * Registers how to draw `canvas`'s last frame again, synchronously (encode and
 * submit, no awaits): called only right before the canvas is copied for printing.
 */
export function keepForPrint(canvas: HTMLCanvasElement, redraw: () => void): void {
  redraws.set(canvas, redraw);
}

/** The print copy that follows `canvas`, made on first use. */
function printCopy(canvas: HTMLCanvasElement): HTMLCanvasElement {
  const next = canvas.nextElementSibling;
  if (next instanceof HTMLCanvasElement && next.classList.contains('sb-print-image')) return next;
  const copy = document.createElement('canvas');
  canvas.after(copy);
  return copy;
}

/**
 * Copies every canvas under `root` into its print copy. The copy takes the canvas's
 * classes, label and inline size, so the widget's own layout rules size it the same
 * way. Returns how many canvases were copied.
 */
export function snapshotCanvases(root: ParentNode): number {
  let copied = 0;
  for (const canvas of root.querySelectorAll('canvas')) {
    if (canvas.classList.contains('sb-print-image')) continue;
    if (canvas.width === 0 || canvas.height === 0) continue;
    // The canvas's own display, without the print rule that hides it once copied
    // (Chromium may already lay out for print when it fires beforeprint).
    canvas.classList.remove('sb-print-source');
    const display = getComputedStyle(canvas).display;
    const copy = printCopy(canvas);
    const redraw = redraws.get(canvas);
    try {
      // Resizing clears the copy; the re-draw and the copy then happen in this task.
      copy.width = canvas.width;
      copy.height = canvas.height;
      const context = context2d(copy);
      if (!context) throw new Error('no 2D context for the print copy');
      redraw?.();
      context.drawImage(canvas, 0, 0);
    } catch {
      // A lost device: the canvas itself stays in the print.
      copy.remove();
      continue;
    }
    copy.className = canvas.className;
    copy.classList.remove('sb-print-source');
    copy.classList.add('sb-print-image');
    copy.setAttribute('role', 'img');
    copy.setAttribute('aria-label', canvas.getAttribute('aria-label') ?? '');
    copy.style.cssText = canvas.style.cssText;
    // Marks a copy re-drawn for printing (a WebGPU canvas), for tests and debugging.
    copy.toggleAttribute('data-print-redrawn', redraw !== undefined);
    // A canvas hidden on screen stays hidden in print.
    copy.style.setProperty('--sb-print-display', display);
    canvas.classList.add('sb-print-source');
    copied += 1;
  }
  return copied;
}
