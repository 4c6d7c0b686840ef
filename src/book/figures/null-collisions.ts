// Figure for null collisions and delta tracking (chapter 6, eq:null-collision and
// eq:delta-estimator). The upper plot is the extinction σt(s) of the chapter's smooth
// medium, σt(s) = σ0(1 + 0.8 sin 3s) from the float64 twin (src/reference/medium.ts),
// under its constant majorant σ̄. The tentative collisions are a Poisson process of rate σ̄:
// their exponential gaps come from the library's own free-flight sampler and PCG stream
// (src/reference/tracking.ts, rng.ts), and each collision is drawn at the height ξ·σ̄ of its
// acceptance number ξ: below the curve it is real, above it null. Delta tracking stops at
// the first real collision; ratio tracking multiplies 1 − σt/σ̄ at every one of them.
import { mediumExtinction, sineMedium } from '../../reference/medium.ts';
import { sampleFreeFlight } from '../../reference/tracking.ts';
import {
  arrow,
  circle,
  curvedArrow,
  dimension,
  group,
  line,
  math,
  num,
  path,
  rngNextFloat,
  text,
  type Diagram,
  type RngState,
} from './svg.ts';

export interface NullCollisionParameters {
  sigma0: number;
  amplitude: number;
  frequency: number;
  /** Majorant σ̄ in 1/m (≥ max σt = σ0(1 + amplitude)). */
  majorant: number;
  /** Segment length d in m. */
  length: number;
  /** First seed to try; the generator takes the first seed whose walk shows at least
   * `minimumNull` null collisions before the first real one (deterministic). */
  seed: number;
  minimumNull: number;
}

export const NULL_COLLISIONS: NullCollisionParameters = {
  sigma0: 1,
  amplitude: 0.8,
  frequency: 3,
  majorant: 2,
  length: 2,
  seed: 1,
  minimumNull: 2,
};

export interface TentativeCollision {
  /** Distance along the ray, m. */
  t: number;
  /** Acceptance number ξ of the collision. */
  xi: number;
  real: boolean;
}

/** The tentative collisions on [0, d] for one seed, as delta and ratio tracking see them. */
export function tentativeCollisions(
  p: NullCollisionParameters,
  seed: number,
): TentativeCollision[] {
  const medium = sineMedium(p.sigma0, p.amplitude, p.frequency);
  const state: RngState = { value: seed >>> 0 };
  const collisions: TentativeCollision[] = [];
  let t = 0;
  for (;;) {
    t += sampleFreeFlight(p.majorant, rngNextFloat(state));
    if (t >= p.length || collisions.length > 64) return collisions;
    const xi = rngNextFloat(state);
    collisions.push({ t, xi, real: xi < mediumExtinction(medium, t) / p.majorant });
  }
}

export function chooseWalk(p: NullCollisionParameters): {
  seed: number;
  walk: TentativeCollision[];
} {
  for (let seed = p.seed; seed < p.seed + 10000; seed++) {
    const walk = tentativeCollisions(p, seed);
    const firstReal = walk.findIndex((c) => c.real);
    const afterReal = firstReal >= 0 ? walk.length - firstReal - 1 : 0;
    // Legible: gaps of at least a twentieth of the segment, spread over most of it.
    const spaced = walk.every((c, i) => c.t - (walk[i - 1]?.t ?? 0) >= p.length / 20);
    const spread = (walk[walk.length - 1]?.t ?? 0) >= 0.75 * p.length;
    if (
      firstReal >= p.minimumNull &&
      afterReal >= 1 &&
      walk.length >= 5 &&
      walk.length <= 8 &&
      spaced &&
      spread
    )
      return { seed, walk };
  }
  throw new Error('no seed gives the walk the null-collision figure needs');
}

const WIDTH = 640;
const HEIGHT = 330;
const LEFT = 64;
const RIGHT = 590;
const PLOT_BOTTOM = 190;
const PLOT_TOP = 40;
const RAY_Y = 250;

export function nullCollisions(p: NullCollisionParameters = NULL_COLLISIONS): Diagram {
  const medium = sineMedium(p.sigma0, p.amplitude, p.frequency);
  const { walk } = chooseWalk(p);
  const xOf = (t: number): number => LEFT + ((RIGHT - LEFT) * t) / p.length;
  const yOf = (sigma: number): number =>
    PLOT_BOTTOM - ((PLOT_BOTTOM - PLOT_TOP) * sigma) / (p.majorant * 1.12);
  const curve: string[] = [];
  for (let i = 0; i <= 120; i++) {
    const t = (p.length * i) / 120;
    curve.push(`${num(xOf(t))} ${num(yOf(mediumExtinction(medium, t)))}`);
  }
  const area = `M${num(xOf(0))} ${num(PLOT_BOTTOM)}L${curve.join('L')}L${num(xOf(p.length))} ${num(PLOT_BOTTOM)}Z`;
  const firstReal = walk.findIndex((c) => c.real);
  let thinnest = 0;
  for (let i = 0; i <= 200; i++) {
    const t = (p.length * i) / 200;
    if (mediumExtinction(medium, t) < mediumExtinction(medium, thinnest)) thinnest = t;
  }

  const marks = walk.map((collision, index) => {
    const x = xOf(collision.t);
    const y = yOf(collision.xi * p.majorant);
    const afterStop = index > firstReal;
    const cls = collision.real ? 'fig-solid-warm' : 'fig-hollow';
    return group(afterStop ? 'fig-after-stop' : 'fig-walk', [
      line(x, RAY_Y, x, y, 'fig-ink fig-thin fig-dot'),
      circle(x, y, 5, cls),
      circle(x, RAY_Y, 4, collision.real ? 'fig-solid-warm' : 'fig-hollow'),
    ]);
  });
  // Exponential gaps between successive tentative collisions, as arcs over the ray.
  const stops = [0, ...walk.map((c) => c.t)];
  const gaps = stops.slice(1).map((t, i) => {
    const a = xOf(stops[i] ?? 0) + 3;
    const b = xOf(t) - 5;
    const mid = (a + b) / 2;
    return curvedArrow(a, RAY_Y - 6, mid, RAY_Y - 30, b, RAY_Y - 6, 'fig-muted fig-thin');
  });
  const stop = walk[firstReal];
  const stopX = stop ? xOf(stop.t) : RIGHT;

  const body = [
    path(area, 'fig-medium'),
    path(`M${curve.join('L')}`, 'fig-stroke fig-accent fig-thick'),
    line(LEFT, yOf(p.majorant), RIGHT, yOf(p.majorant), 'fig-ink fig-dash'),
    math(RIGHT + 8, yOf(p.majorant) + 6, 'σ̄', 'start'),
    math(
      xOf(p.length * 0.36),
      yOf(mediumExtinction(medium, p.length * 0.36)) + 34,
      'σ_t(s)',
      'middle',
      'fig-math fig-accent-text',
    ),
    // The null-collision coefficient where it is largest, at the medium's thinnest point.
    dimension(
      xOf(thinnest),
      yOf(p.majorant),
      xOf(thinnest),
      yOf(mediumExtinction(medium, thinnest)),
    ),
    text(xOf(thinnest) + 10, yOf(p.majorant) + 26, 'null', 'start', 'fig-text fig-small fig-halo'),
    math(
      xOf(thinnest) + 10,
      yOf(p.majorant) + 50,
      'σ_n = σ̄ − σ_t',
      'start',
      'fig-math fig-halo',
      15,
    ),
    line(LEFT, PLOT_BOTTOM, RIGHT, PLOT_BOTTOM, 'fig-ink fig-thin'),
    line(LEFT, PLOT_BOTTOM, LEFT, PLOT_TOP - 8, 'fig-ink fig-thin'),
    math(LEFT - 10, PLOT_TOP, 'σ', 'end'),
    math(LEFT - 10, PLOT_BOTTOM + 5, '0', 'end'),
    // The ray and its segment [0, d].
    arrow(LEFT - 30, RAY_Y, RIGHT + 36, RAY_Y, { cls: 'fig-ink' }),
    line(LEFT, RAY_Y - 7, LEFT, RAY_Y + 7, 'fig-ink'),
    line(RIGHT, RAY_Y - 7, RIGHT, RAY_Y + 7, 'fig-ink'),
    math(LEFT, RAY_Y + 26, '0'),
    math(RIGHT, RAY_Y + 26, 'd'),
    math(RIGHT + 30, RAY_Y + 26, 's'),
    ...gaps,
    ...marks,
    arrow(stopX, RAY_Y + 32, stopX, RAY_Y + 9, { cls: 'fig-warm fig-thin' }),
    text(stopX, RAY_Y + 48, 'delta tracking stops here', 'middle', 'fig-text fig-warm-text'),
    text(LEFT + 4, RAY_Y - 40, 'gaps ~ Exp(σ̄)', 'start', 'fig-text fig-small'),
    circle(LEFT + 6, HEIGHT - 14, 4, 'fig-hollow'),
    text(LEFT + 16, HEIGHT - 9, 'null collision', 'start', 'fig-text fig-small'),
    circle(LEFT + 136, HEIGHT - 14, 4, 'fig-solid-warm'),
    text(LEFT + 146, HEIGHT - 9, 'real collision', 'start', 'fig-text fig-small'),
  ];

  const nulls = walk.filter((c) => !c.real).length;
  return {
    width: WIDTH,
    height: HEIGHT,
    title: 'Null collisions along a ray under a constant majorant',
    description:
      `Above: the extinction σt(s) of a smooth medium along a ray segment from 0 to d, under a dashed ` +
      `horizontal line at the majorant σ̄; the gap between them is the null-collision coefficient. ` +
      `Below: the ray, with ${walk.length} tentative collisions placed at exponentially distributed ` +
      `gaps of rate σ̄. Each collision is marked above at the height ξ·σ̄ of its random number ξ: ` +
      `${nulls} fall above the curve and are null collisions (hollow), ${walk.length - nulls} below it, ` +
      `real collisions (filled). Delta tracking stops at the first real collision, number ${firstReal + 1}; ` +
      `ratio tracking visits every tentative collision and multiplies their weights 1 − σt/σ̄.`,
    body: body.join(''),
  };
}
