// Figure for the BSSRDF (chapter 11, eq:bssrdf): a BRDF relates light arriving at a point
// to light leaving the same point; a BSSRDF relates light entering at x_i to light leaving
// at x_o, after a random walk under the surface. The walk is drawn from the book's PCG
// stream (src/reference/rng.ts): exponential steps in uniform directions, bent into a
// bridge that ends at x_o and kept below the surface, so it is the same on every build.
import {
  arrow,
  circle,
  group,
  line,
  math,
  polyline,
  rect,
  rngNextFloat,
  text,
  type Diagram,
  type RngState,
} from './svg.ts';

export interface BssrdfParameters {
  steps: number;
  /** Mean step length of the walk, in user units. */
  meanStep: number;
  seed: number;
}

export const BSSRDF_FIGURE: BssrdfParameters = { steps: 14, meanStep: 24, seed: 11 };

const WIDTH = 640;
const HEIGHT = 320;
const MATERIAL_DEPTH = 92;
const SURFACE_Y = 150;
const PANEL = 320;

/** A random walk from `start` to `end` below the surface (y > SURFACE_Y). */
export function subsurfaceWalk(
  p: BssrdfParameters,
  start: readonly [number, number],
  end: readonly [number, number],
): [number, number][] {
  const state: RngState = { value: p.seed >>> 0 };
  const raw: [number, number][] = [[0, 0]];
  for (let k = 0; k < p.steps; k++) {
    const length = -Math.log(1 - rngNextFloat(state)) * p.meanStep;
    const angle = 2 * Math.PI * rngNextFloat(state);
    const [x, y] = raw[raw.length - 1] ?? [0, 0];
    raw.push([x + length * Math.cos(angle), y + length * Math.sin(angle)]);
  }
  const [lx, ly] = raw[raw.length - 1] ?? [0, 0];
  // A bridge: subtract the fraction k/n of the walk's end offset and add that of the target;
  // then reflect it into the material (depth |y|) and keep interior vertices 8 units deep.
  return raw.map(([x, y], k) => {
    const f = k / p.steps;
    const px = start[0] + x - f * lx + f * (end[0] - start[0]);
    const depth = Math.abs(y - f * ly + f * (end[1] - start[1]) - 0);
    const interior = k > 0 && k < p.steps;
    return [px, start[1] + (interior ? Math.max(depth, 8) : depth)];
  });
}

/** The first seed from p.seed whose walk stays inside the drawn material and goes deep enough. */
function fittingWalk(p: BssrdfParameters, xi: number, xo: number): [number, number][] {
  for (let seed = p.seed; seed < p.seed + 10000; seed++) {
    const walk = subsurfaceWalk({ ...p, seed }, [xi, SURFACE_Y], [xo, SURFACE_Y]);
    const depth = Math.max(...walk.map(([, y]) => y - SURFACE_Y));
    const inside = walk.every(([x]) => x > PANEL + 30 && x < WIDTH - 30);
    if (inside && depth <= MATERIAL_DEPTH - 12 && depth >= MATERIAL_DEPTH / 2) return walk;
  }
  throw new Error('no seed gives a random walk that fits the BSSRDF figure');
}

export function bssrdfFigure(p: BssrdfParameters = BSSRDF_FIGURE): Diagram {
  const x = 160;
  const xi = PANEL + 78;
  const xo = PANEL + 236;
  const walk = fittingWalk(p, xi, xo);

  const left = group('fig-brdf', [
    rect(20, SURFACE_Y, PANEL - 40, MATERIAL_DEPTH, 'fig-surface-fill'),
    line(20, SURFACE_Y, PANEL - 20, SURFACE_Y, 'fig-ink fig-thick'),
    line(x, SURFACE_Y, x, SURFACE_Y - 110, 'fig-muted fig-thin fig-dash'),
    arrow(x - 96, SURFACE_Y - 104, x - 3, SURFACE_Y - 3, { cls: 'fig-ink fig-thick' }),
    arrow(x + 2, SURFACE_Y - 2, x + 96, SURFACE_Y - 100, { cls: 'fig-ink fig-thick' }),
    circle(x, SURFACE_Y, 4, 'fig-solid'),
    math(x - 70, SURFACE_Y - 56, 'ω_i', 'end'),
    math(x + 70, SURFACE_Y - 56, 'ω_o', 'start'),
    math(x, SURFACE_Y + 26, '*x*'),
    text(x, SURFACE_Y + 124, 'BRDF', 'middle'),
    math(x, SURFACE_Y + 152, 'f_r(*x*, ω_i, ω_o)'),
  ]);
  const right = group('fig-bssrdf', [
    rect(PANEL + 20, SURFACE_Y, PANEL - 40, MATERIAL_DEPTH, 'fig-medium'),
    line(PANEL + 20, SURFACE_Y, WIDTH - 20, SURFACE_Y, 'fig-ink fig-thick'),
    polyline(walk, 'fig-stroke fig-accent'),
    ...walk.slice(1, -1).map(([vx, vy]) => circle(vx, vy, 2.4, 'fig-solid-accent')),
    arrow(xi - 80, SURFACE_Y - 96, xi - 3, SURFACE_Y - 3, { cls: 'fig-ink fig-thick' }),
    arrow(xo + 2, SURFACE_Y - 2, xo + 70, SURFACE_Y - 98, { cls: 'fig-ink fig-thick' }),
    circle(xi, SURFACE_Y, 4, 'fig-solid'),
    circle(xo, SURFACE_Y, 4, 'fig-solid'),
    math(xi - 56, SURFACE_Y - 56, 'ω_i', 'end'),
    math(xo + 52, SURFACE_Y - 56, 'ω_o', 'start'),
    math(xi + 10, SURFACE_Y - 10, '*x*_i', 'start'),
    math(xo - 10, SURFACE_Y - 10, '*x*_o', 'end'),
    text(PANEL + PANEL / 2, SURFACE_Y + 124, 'BSSRDF', 'middle'),
    math(PANEL + PANEL / 2, SURFACE_Y + 152, 'S(*x*_i, ω_i; *x*_o, ω_o)'),
  ]);

  return {
    width: WIDTH,
    height: HEIGHT,
    title: 'BRDF and BSSRDF compared',
    description:
      'Two panels. Left, the BRDF: light arrives at a point x of an opaque surface from direction ω_i ' +
      'and leaves the same point in direction ω_o; it is written f_r(x, ω_i, ω_o). Right, the BSSRDF: ' +
      'light enters a translucent material at x_i from direction ω_i, wanders under the surface along a ' +
      `random walk of ${p.steps} steps, and leaves at a different point x_o in direction ω_o; it is ` +
      'written S(x_i, ω_i; x_o, ω_o).',
    body: [left, right, line(PANEL, 20, PANEL, HEIGHT - 20, 'fig-muted fig-thin')].join(''),
  };
}
