// Fits a slide's figure into the room the slide layout leaves it (deck CSS: a grid
// whose figure row takes what the title, caption and controls do not). A widget's
// height has two kinds of parts: canvases, whose height follows their width (an
// aspect ratio), and text (controls, readouts), whose height grows as its column
// narrows. No single knob fits both, so the fit tries, in order of preference:
//   zoom   CSS `zoom` on the widget, which scales text and canvases alike and, unlike
//          a transform, lays the figure out again (canvases, pointer coordinates and
//          ResizeObservers see real sizes); 1 is preferred, text stays readable ≥ 0.6;
//   stage  the stage column's share of the widget (--deck-stage, in fr beside the
//          controls' 0.75fr and the readouts' 1.1fr): a narrower stage has smaller
//          canvases and wider text columns;
//   width  the widget's width (centred), for widgets whose own layout puts the
//          stage above everything else (its canvases shrink with it).
// The first combination that fits wins: each probe is one synchronous layout of one
// figure, and the browser paints only the last.

export const ZOOMS = [1, 0.92, 0.84, 0.76, 0.68, 0.6, 0.52] as const;
export const STAGE_SHARES = ['1.3fr', '1.1fr', '0.9fr', '0.75fr', '0.6fr'] as const;
export const WIDTHS = [0.85, 0.7, 0.55] as const;

export interface Fit {
  zoom: number;
  stage: string;
  width: number;
  fits: boolean;
}

function apply(content: HTMLElement, fit: Omit<Fit, 'fits'>): void {
  content.style.zoom = fit.zoom === 1 ? '' : String(fit.zoom);
  content.style.setProperty('--deck-stage', fit.stage);
  content.style.maxWidth = fit.width === 1 ? '' : `${fit.width * 100}%`;
}

/** Does `content` fit `box`: no taller, and nothing in it overflowing sideways? */
function fitsIn(content: HTMLElement, box: HTMLElement): boolean {
  const available = box.getBoundingClientRect();
  const used = content.getBoundingClientRect();
  return (
    used.height <= available.height + 0.5 &&
    used.width <= available.width + 0.5 &&
    content.scrollWidth <= content.clientWidth + 1
  );
}

/** Chooses and applies the most readable layout of `content` that fits `box`. */
export function fitToBox(content: HTMLElement, box: HTMLElement): Fit {
  const candidates: Omit<Fit, 'fits'>[] = [];
  for (const zoom of ZOOMS) {
    for (const stage of STAGE_SHARES) candidates.push({ zoom, stage, width: 1 });
    for (const width of WIDTHS) candidates.push({ zoom, stage: '0.9fr', width });
  }
  if (box.getBoundingClientRect().height <= 0) {
    apply(content, { zoom: 1, stage: '1.1fr', width: 1 });
    return { zoom: 1, stage: '1.1fr', width: 1, fits: false };
  }
  for (const candidate of candidates) {
    apply(content, candidate);
    if (fitsIn(content, box)) return { ...candidate, fits: true };
  }
  const last = candidates[candidates.length - 1] ?? { zoom: 1, stage: '1.1fr', width: 1 };
  return { ...last, fits: false };
}

/** Removes a fit (narrow screens, where the deck scrolls like a page instead). */
export function unfit(content: HTMLElement): void {
  content.style.zoom = '';
  content.style.removeProperty('--deck-stage');
  content.style.maxWidth = '';
}
