// The drawing vocabulary of the book's static diagrams (src/book/figures/*.ts): lines,
// arrows with solid heads, dimension lines and labels, emitted as SVG text at build time.
//
// Nothing here names a colour. Every element carries a class (`fig-ink`, `fig-accent`,
// `fig-medium`, …) that src/book/styles/figures.css maps to the theme's tokens, so the
// light/dark switch recolours a diagram like the prose around it. Arrowheads are drawn as
// polygons rather than SVG markers: a marker needs a document-unique id and takes its
// colour from `context-stroke`, which not every engine supports, whereas a polygon shares
// its arrow's class. Coordinates are rounded to 0.01 so that a generator's output is a
// stable string (tests/book/figures.test.ts compares two builds).

/** A diagram before it is wrapped in <svg>: user units are CSS pixels at 100 % scale. */
export interface Diagram {
  width: number;
  height: number;
  /** Short name of the picture, read first by a screen reader (<title>). */
  title: string;
  /** What the picture shows, in words, for readers who cannot see it (<desc>). */
  description: string;
  /** SVG elements, already serialized. */
  body: string;
}

export function num(value: number): string {
  if (!Number.isFinite(value)) throw new Error(`figure coordinate is not finite: ${value}`);
  const rounded = Math.round(value * 100) / 100;
  return String(Object.is(rounded, -0) ? 0 : rounded);
}

export function escapeXml(text: string): string {
  return text
    .replace(/&/g, '&amp;')
    .replace(/</g, '&lt;')
    .replace(/>/g, '&gt;')
    .replace(/"/g, '&quot;');
}

type Attributes = Record<string, string | number | undefined>;

function attributes(attrs: Attributes): string {
  return Object.entries(attrs)
    .filter((entry): entry is [string, string | number] => entry[1] !== undefined)
    .map(([key, value]) => ` ${key}="${typeof value === 'number' ? num(value) : escapeXml(value)}"`)
    .join('');
}

export function element(tag: string, attrs: Attributes, children = ''): string {
  return children === ''
    ? `<${tag}${attributes(attrs)}/>`
    : `<${tag}${attributes(attrs)}>${children}</${tag}>`;
}

export function group(cls: string, children: readonly string[]): string {
  return element('g', { class: cls }, children.join(''));
}

export function line(x1: number, y1: number, x2: number, y2: number, cls = 'fig-ink'): string {
  return element('line', { x1, y1, x2, y2, class: cls });
}

export function rect(
  x: number,
  y: number,
  width: number,
  height: number,
  cls: string,
  radius?: number,
): string {
  return element('rect', { x, y, width, height, rx: radius, class: cls });
}

export function circle(cx: number, cy: number, r: number, cls: string): string {
  return element('circle', { cx, cy, r, class: cls });
}

export function polyline(points: readonly (readonly [number, number])[], cls: string): string {
  return element('polyline', {
    points: points.map(([x, y]) => `${num(x)},${num(y)}`).join(' '),
    class: cls,
  });
}

export function polygon(points: readonly (readonly [number, number])[], cls: string): string {
  return element('polygon', {
    points: points.map(([x, y]) => `${num(x)},${num(y)}`).join(' '),
    class: cls,
  });
}

export function path(d: string, cls: string): string {
  return element('path', { d, class: cls });
}

/** Length of an arrowhead along the shaft, and its half width, in user units. */
export const HEAD_LENGTH = 10;
export const HEAD_HALF_WIDTH = 4;

/** A solid arrowhead with its tip at (x, y), pointing along the unit direction (dx, dy). */
export function arrowhead(x: number, y: number, dx: number, dy: number, cls: string): string {
  const bx = x - dx * HEAD_LENGTH;
  const by = y - dy * HEAD_LENGTH;
  return polygon(
    [
      [x, y],
      [bx - dy * HEAD_HALF_WIDTH, by + dx * HEAD_HALF_WIDTH],
      [bx + dy * HEAD_HALF_WIDTH, by - dx * HEAD_HALF_WIDTH],
    ],
    `fig-head ${cls}`,
  );
}

function unit(dx: number, dy: number): [number, number] {
  const length = Math.hypot(dx, dy);
  if (length === 0) throw new Error('an arrow needs two distinct points');
  return [dx / length, dy / length];
}

export interface ArrowOptions {
  /** Class of shaft and head (a colour role and optionally a width or dash). */
  cls?: string;
  /** A head at the start as well (dimension lines). */
  both?: boolean;
}

/** A straight arrow from (x1, y1) to (x2, y2); the shaft stops where the head begins. */
export function arrow(
  x1: number,
  y1: number,
  x2: number,
  y2: number,
  options: ArrowOptions = {},
): string {
  const cls = options.cls ?? 'fig-ink';
  const [dx, dy] = unit(x2 - x1, y2 - y1);
  const inset = HEAD_LENGTH * 0.8;
  const sx = options.both ? x1 + dx * inset : x1;
  const sy = options.both ? y1 + dy * inset : y1;
  const parts = [
    line(sx, sy, x2 - dx * inset, y2 - dy * inset, cls),
    arrowhead(x2, y2, dx, dy, cls),
  ];
  if (options.both) parts.push(arrowhead(x1, y1, -dx, -dy, cls));
  return parts.join('');
}

/** A quadratic Bézier arrow through the control point (cx, cy), head tangent to the curve. */
export function curvedArrow(
  x1: number,
  y1: number,
  cx: number,
  cy: number,
  x2: number,
  y2: number,
  cls = 'fig-ink',
): string {
  const [dx, dy] = unit(x2 - cx, y2 - cy);
  const inset = HEAD_LENGTH * 0.8;
  const d = `M${num(x1)} ${num(y1)}Q${num(cx)} ${num(cy)} ${num(x2 - dx * inset)} ${num(y2 - dy * inset)}`;
  return path(d, `fig-stroke ${cls}`) + arrowhead(x2, y2, dx, dy, cls);
}

/**
 * A dimension line: a double-headed arrow between two points with short end ticks
 * across it, e.g. the thickness d of a slab.
 */
export function dimension(
  x1: number,
  y1: number,
  x2: number,
  y2: number,
  cls = 'fig-ink fig-thin',
): string {
  const [dx, dy] = unit(x2 - x1, y2 - y1);
  const tick = 6;
  return (
    arrow(x1, y1, x2, y2, { cls, both: true }) +
    line(x1 - dy * tick, y1 + dx * tick, x1 + dy * tick, y1 - dx * tick, cls) +
    line(x2 - dy * tick, y2 + dx * tick, x2 + dy * tick, y2 - dx * tick, cls)
  );
}

export type Anchor = 'start' | 'middle' | 'end';

/** Plain words (sans serif, like the captions): "camera", "real collision". */
export function text(
  x: number,
  y: number,
  content: string,
  anchor: Anchor = 'start',
  cls = 'fig-text',
): string {
  return element('text', { x, y, 'text-anchor': anchor, class: cls }, escapeXml(content));
}

/** Font size of math labels in user units; scripts are 0.7 of it, as in TeX's \scriptstyle. */
export const MATH_SIZE = 18;
const SCRIPT_SCALE = 0.7;
const SUB_SHIFT = 0.28;
const SUP_SHIFT = -0.42;

interface MathRun {
  content: string;
  /** Italic variable (KaTeX_Math), upright digit, operator or word, or bold point (KaTeX_Main). */
  style: 'fig-mi' | 'fig-mn' | 'fig-mb';
  /** Script depth: 0 on the baseline; each sub- or superscript adds one level. */
  depth: number;
  /** Baseline offset from the label's baseline, in units of the label's font size (down +). */
  shift: number;
}

const ITALIC = /[A-Za-z\u0370-\u03ff]/;

/** Reads a script argument at `index`: `{…}` (nested braces allowed) or one character. */
function scriptArgument(source: string, index: number): [string, number] {
  if (source[index] === '{') {
    let depth = 0;
    for (let end = index; end < source.length; end++) {
      if (source[end] === '{') depth += 1;
      if (source[end] === '}') depth -= 1;
      if (depth === 0) return [source.slice(index + 1, end), end + 1];
    }
    throw new Error(`unbalanced brace in figure label "${source}"`);
  }
  const char = String.fromCodePoint(source.codePointAt(index) ?? 32);
  return [char, index + char.length];
}

function pushRuns(runs: MathRun[], source: string, depth: number, shift: number): void {
  const scale = SCRIPT_SCALE ** depth;
  let index = 0;
  while (index < source.length) {
    const char = source[index] ?? '';
    if (char === '_' || char === '^') {
      const [argument, next] = scriptArgument(source, index + 1);
      const offset = (char === '_' ? SUB_SHIFT : SUP_SHIFT) * scale;
      pushRuns(runs, argument, depth + 1, shift + offset);
      index = next;
      continue;
    }
    if (char === '"' || char === '*') {
      // "word": upright text inside math, e.g. T_"shadow"; *x*: a bold point, \mathbf{x}.
      const close = source.indexOf(char, index + 1);
      if (close < 0) throw new Error(`unbalanced ${char} in figure label "${source}"`);
      const style = char === '"' ? 'fig-mn' : 'fig-mb';
      runs.push({ content: source.slice(index + 1, close), style, depth, shift });
      index = close + 1;
      continue;
    }
    const point = String.fromCodePoint(source.codePointAt(index) ?? 32);
    // A combining mark (the bar of σ̄) or a prime stays with the letter before it.
    const style = ITALIC.test(point) || /[\u0300-\u036f′]/.test(point) ? 'fig-mi' : 'fig-mn';
    const last = runs[runs.length - 1];
    if (last && last.style === style && last.depth === depth && last.shift === shift)
      last.content += point;
    else runs.push({ content: point, style, depth, shift });
    index += point.length;
  }
}

/**
 * A math label in the book's math fonts (KaTeX_Math italic for variables, KaTeX_Main
 * upright for digits and operators, as KaTeX sets them in the prose). `source` is a
 * small TeX-like notation: `σ_t`, `L_0 e^{−σ_t d}`, `T_"shadow"` (quoted words upright),
 * `*x*_i` (a bold point, as \mathbf{x} in the prose);
 * scripts nest, each level at 0.7 of the size above it.
 */
export function math(
  x: number,
  y: number,
  source: string,
  anchor: Anchor = 'middle',
  cls = 'fig-math',
  size = MATH_SIZE,
): string {
  const runs: MathRun[] = [];
  pushRuns(runs, source, 0, 0);
  let shift = 0;
  const spans = runs.map((run) => {
    // In ems of the tspan's own size, so that CSS may resize a label (figures.css does on
    // phones) and its scripts follow: the script's size is relative to the <text>.
    const scale = SCRIPT_SCALE ** run.depth;
    const dy = (run.shift - shift) / scale;
    shift = run.shift;
    return element(
      'tspan',
      {
        class: run.style,
        dy: dy === 0 ? undefined : `${num(dy)}em`,
        'font-size': run.depth === 0 ? undefined : `${num(scale)}em`,
      },
      escapeXml(run.content),
    );
  });
  return element(
    'text',
    {
      x,
      y,
      'text-anchor': anchor,
      // figures.css enlarges labels on phones; a smaller label is marked to stay smaller there.
      class: size < MATH_SIZE ? `${cls} fig-math-small` : cls,
      'font-size': size,
    },
    spans.join(''),
  );
}

/** The document-unique ids of a diagram's <title> and <desc>, from its figure id. */
export function diagramIds(id: string): { title: string; desc: string } {
  const base = id.replace(/[^A-Za-z0-9_-]/g, '-');
  return { title: `${base}-title`, desc: `${base}-desc` };
}

/**
 * The <svg> element of a diagram: scalable (viewBox, width 100 % up to its natural
 * width, via figures.css), announced as one image whose name is the title and whose
 * description is the text alternative.
 */
export function renderSvg(diagram: Diagram, id: string): string {
  const ids = diagramIds(id);
  return (
    `<svg class="diagram" viewBox="0 0 ${num(diagram.width)} ${num(diagram.height)}" ` +
    `width="${num(diagram.width)}" height="${num(diagram.height)}" role="img" ` +
    `aria-labelledby="${ids.title}" aria-describedby="${ids.desc}" xmlns="http://www.w3.org/2000/svg">` +
    `<title id="${ids.title}">${escapeXml(diagram.title)}</title>` +
    `<desc id="${ids.desc}">${escapeXml(diagram.description)}</desc>` +
    diagram.body +
    `</svg>`
  );
}

/**
 * A small deterministic generator for the scatter of particles and random walks that
 * decorate diagrams: the book's PCG stream (src/reference/rng.ts), so a figure is the
 * same string on every build.
 */
export { rngNextFloat, type RngState } from '../../reference/rng.ts';
