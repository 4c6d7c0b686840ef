// Fits a slide's figure into the room the slide layout leaves it (deck CSS: a grid
// whose figure row takes what the title, caption and controls do not). A widget's
// height has two kinds of parts: canvases, whose height follows their width (an
// aspect ratio), and text (controls, readouts), whose height grows as its column
// narrows. No single knob fits both, so the fit turns three:
//   stage  the stage column's share of the widget (--deck-stage, in fr beside the
//          controls' 0.75fr and the readouts' 1.1fr): a narrower stage has smaller
//          canvases and wider text columns;
//   zoom   CSS `zoom` on the widget, which scales text and canvases alike and, unlike
//          a transform, lays the figure out again (canvases, pointer coordinates and
//          ResizeObservers see real sizes); 1 is preferred, text stays readable ≥ 0.6;
//   width  the widget's width (centred), for a widget whose own layout puts the
//          stage above everything else (its canvases shrink with it).
// Each probe is one synchronous layout of one figure (the browser paints only the
// last), and a heavy widget's layout is not free, so the search is short: the stage
// share that leaves the figure shortest at full size, then the largest zoom for it
// by bisection, then narrower widths only while the zoom is below what a room reads
// comfortably (READABLE_ZOOM): a narrower figure has smaller canvases but taller text,
// so narrowing helps some widgets and hurts others, and the search keeps whichever
// width gave the largest zoom. A figure that overflows even at MIN_ZOOM keeps the
// width with the least overflow (not the narrowest), and the deck makes its box a
// scroll region rather than let it run over the caption (deck.ts).
export const STAGE_SHARES = ['1.3fr', '1.1fr', '0.9fr', '0.75fr', '0.6fr'] as const;
export const WIDTHS = [0.85, 0.7, 0.55] as const;
export const MIN_ZOOM = 0.6;
/** A zoom a room reads without effort: below it, narrower widths are tried too. */
export const READABLE_ZOOM = 0.7;

export interface Fit {
  zoom: number;
  stage: string;
  width: number;
  fits: boolean;
  /** How far the figure runs past its box at this layout, in px (0 when it fits). */
  overflow: number;
}

type Layout = Omit<Fit, 'fits' | 'overflow'>;

function apply(content: HTMLElement, layout: Layout): void {
  content.style.zoom = layout.zoom === 1 ? '' : String(layout.zoom);
  content.style.setProperty('--deck-stage', layout.stage);
  content.style.maxWidth = layout.width === 1 ? '' : `${layout.width * 100}%`;
}

/** How far `content` overflows `box` (≤ 0: it fits), in px, after laying it out so. */
function overflow(content: HTMLElement, box: HTMLElement, layout: Layout): number {
  apply(content, layout);
  const available = box.getBoundingClientRect();
  const used = content.getBoundingClientRect();
  const sideways = Math.max(0, content.scrollWidth - content.clientWidth - 1);
  return (
    Math.max(used.height - available.height - 0.5, used.width - available.width - 0.5) + sideways
  );
}

/**
 * The largest zoom in [floor, 1] at which the layout fits, or null with the overflow
 * at `floor` (floor ≥ MIN_ZOOM: a zoom already found elsewhere need not be beaten by
 * less).
 */
function largestZoom(
  content: HTMLElement,
  box: HTMLElement,
  layout: Layout,
  floor: number,
): { zoom: number } | { zoom: null; overflow: number } {
  if (overflow(content, box, { ...layout, zoom: 1 }) <= 0) return { zoom: 1 };
  const atFloor = overflow(content, box, { ...layout, zoom: floor });
  if (atFloor > 0) return { zoom: null, overflow: atFloor };
  let low = floor;
  let high = 1;
  for (let i = 0; i < 5; i++) {
    const middle = (low + high) / 2;
    if (overflow(content, box, { ...layout, zoom: middle }) <= 0) low = middle;
    else high = middle;
  }
  return { zoom: Math.floor(low * 100) / 100 };
}

/** Chooses and applies the most readable layout of `content` that fits `box`. */
export function fitToBox(content: HTMLElement, box: HTMLElement): Fit {
  const full: Layout = { zoom: 1, stage: STAGE_SHARES[1], width: 1 };
  if (box.getBoundingClientRect().height <= 0) {
    apply(content, full);
    return { ...full, fits: false, overflow: 0 };
  }
  // The stage share that leaves the least overflow at full size (the largest on a tie).
  let stageShare: Layout = { ...full, stage: STAGE_SHARES[0] };
  let bestOverflow = Infinity;
  for (const stage of STAGE_SHARES) {
    const excess = Math.max(0, overflow(content, box, { ...full, stage }));
    if (excess < bestOverflow - 1) {
      stageShare = { ...full, stage };
      bestOverflow = excess;
    }
    if (excess <= 0) break;
  }
  let fitted: Layout | null = null;
  // Without a fit: the width that overflows least at MIN_ZOOM (the wider on a tie).
  let leastOverflow: { layout: Layout; overflow: number } | null = null;
  for (const width of [1, ...WIDTHS]) {
    const layout = { ...stageShare, width };
    const found = largestZoom(content, box, layout, fitted ? fitted.zoom + 0.01 : MIN_ZOOM);
    if (found.zoom !== null) {
      if (!fitted || found.zoom > fitted.zoom) fitted = { ...layout, zoom: found.zoom };
    } else if (!fitted && (!leastOverflow || found.overflow < leastOverflow.overflow - 1))
      leastOverflow = { layout: { ...layout, zoom: MIN_ZOOM }, overflow: found.overflow };
    if (fitted && fitted.zoom >= READABLE_ZOOM) break;
  }
  if (fitted) {
    apply(content, fitted);
    return { ...fitted, fits: true, overflow: 0 };
  }
  const last = leastOverflow ?? { layout: { ...stageShare, zoom: MIN_ZOOM }, overflow: 0 };
  apply(content, last.layout);
  return { ...last.layout, fits: false, overflow: Math.round(last.overflow) };
}

/**
 * Whether `content`, laid out as it is now, still fits `box` (nothing is changed). The
 * deck keeps a layout that still fits when only the figure's contents change, so that
 * controls do not move under the pointer while a widget refines or a sweep runs.
 */
export function stillFits(content: HTMLElement, box: HTMLElement): boolean {
  const available = box.getBoundingClientRect();
  if (available.height <= 0) return false;
  const used = content.getBoundingClientRect();
  const sideways = content.scrollWidth - content.clientWidth - 1;
  return (
    used.height <= available.height + 0.5 && used.width <= available.width + 0.5 && sideways <= 0
  );
}

/** Removes a fit (narrow screens, where the deck scrolls like a page instead). */
export function unfit(content: HTMLElement): void {
  content.style.zoom = '';
  content.style.removeProperty('--deck-stage');
  content.style.maxWidth = '';
}
