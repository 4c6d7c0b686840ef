// The image widgets' pictures: a pixelated canvas with its caption and a
// labelled false-colour scale, and the colour-scale helpers they share
// (piecewise-linear interpolation of sRGB stops, the legend's CSS gradient and
// a 1–2–5 rounding of the scale's top).

export type Rgb = [number, number, number];

/** Piecewise-linear interpolation of colour stops at x ∈ [0, 1] (clamped). */
export function interpolate(stops: readonly Rgb[], x: number): Rgb {
  const t = Math.min(Math.max(x, 0), 1) * (stops.length - 1);
  const i = Math.min(Math.floor(t), stops.length - 2);
  const f = t - i;
  const a = stops[i]!;
  const b = stops[i + 1]!;
  return [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f];
}

/**
 * CSS gradient of a colour scale for its legend, sampled at x = (k/10)², so a
 * scale with a square-root mapping shows its stops evenly.
 */
export function gradientCss(colour: (x: number) => Rgb): string {
  const stops = Array.from({ length: 11 }, (_, k) => {
    const [r, g, b] = colour((k / 10) ** 2);
    return `rgb(${Math.round(r)}, ${Math.round(g)}, ${Math.round(b)}) ${k * 10}%`;
  });
  return `linear-gradient(to right, ${stops.join(', ')})`;
}

/** The top of a colour scale: the largest value rounded up to 1, 2 or 5 × 10^k. */
export function niceScale(largest: number): number {
  if (!(largest > 0)) return 1e-6;
  const decade = 10 ** Math.floor(Math.log10(largest));
  for (const m of [1, 2, 5, 10]) if (largest <= m * decade) return m * decade;
  return 10 * decade;
}

/** The row of image panels. */
export function imageFigure(...panels: HTMLElement[]): HTMLElement {
  const figure = document.createElement('div');
  figure.className = 'sb-image-figure';
  figure.append(...panels);
  return figure;
}

export function imageCanvas(label: string, width: number, height: number): HTMLCanvasElement {
  const canvas = document.createElement('canvas');
  canvas.className = 'sb-canvas';
  canvas.setAttribute('role', 'img');
  canvas.setAttribute('aria-label', label);
  canvas.width = width;
  canvas.height = height;
  return canvas;
}

export interface ColourScale {
  /** CSS background of the bar (see gradientCss). */
  gradient: string;
  low: string;
  /** A fixed label, or the data-readout key of a label the widget updates. */
  top: { text: string } | { readout: string };
}

/**
 * A canvas with its caption and, optionally, a colour-scale legend. Returns the
 * panel and the legend's top label (to update when the scale is a readout).
 */
export function imagePanel(
  canvas: HTMLCanvasElement,
  caption: string,
  scale?: ColourScale,
): { panel: HTMLElement; top: HTMLElement | null } {
  const panel = document.createElement('figure');
  panel.className = 'sb-image-panel';
  const text = document.createElement('figcaption');
  text.textContent = caption;
  panel.append(canvas, text);
  if (!scale) return { panel, top: null };
  const legend = document.createElement('div');
  legend.className = 'sb-image-scale';
  const bar = document.createElement('span');
  bar.className = 'sb-image-scale-bar';
  bar.style.background = scale.gradient;
  bar.setAttribute('aria-hidden', 'true');
  const low = document.createElement('span');
  low.textContent = scale.low;
  const top = document.createElement('span');
  if ('readout' in scale.top) top.dataset['readout'] = scale.top.readout;
  else top.textContent = scale.top.text;
  legend.append(low, bar, top);
  panel.appendChild(legend);
  return { panel, top };
}
