// Figure for Beer's law (chapter 2, eq:beer): a collimated beam of radiance L0 crosses a
// homogeneous slab of thickness d and extinction σt. The beam is drawn as a band whose
// height is proportional to its radiance, so inside the slab its edges are the curve
// L(x) = L0·e^{−σt x} itself, sampled from the parameters below, and it leaves with
// L0·e^{−σt d}.
import {
  arrow,
  circle,
  dimension,
  group,
  line,
  math,
  polygon,
  rect,
  rngNextFloat,
  text,
  type Diagram,
  type RngState,
} from './svg.ts';

export interface BeerSlabParameters {
  /** Extinction coefficient σt in 1/m. */
  sigmaT: number;
  /** Slab thickness d in m. */
  thickness: number;
  /** Drawing scale: pixels per metre along the beam. */
  pixelsPerMetre: number;
  /** Particles drawn in the slab (decoration: where collisions happen). */
  particles: number;
  seed: number;
}

export const BEER_SLAB: BeerSlabParameters = {
  sigmaT: 1,
  thickness: 1.5,
  pixelsPerMetre: 120,
  particles: 46,
  seed: 7,
};

const WIDTH = 640;
const HEIGHT = 250;
const AXIS_Y = 112;
/** Half-height of the incident band, for L = L0. */
const BAND = 30;
const SLAB_TOP = 34;
const SLAB_BOTTOM = 190;

export function beerSlab(p: BeerSlabParameters = BEER_SLAB): Diagram {
  const slabWidth = p.thickness * p.pixelsPerMetre;
  const x0 = (WIDTH - slabWidth) / 2 - 10;
  const x1 = x0 + slabWidth;
  const transmittance = Math.exp(-p.sigmaT * p.thickness);
  const half = (x: number): number =>
    BAND * Math.exp((-p.sigmaT * Math.min(Math.max(x - x0, 0), slabWidth)) / p.pixelsPerMetre);

  // Upper edge left to right, then lower edge right to left: one polygon for the beam.
  const samples = 32;
  const xs = [40, ...Array.from({ length: samples + 1 }, (_, i) => x0 + (slabWidth * i) / samples)];
  const exitEnd = WIDTH - 76;
  xs.push(exitEnd);
  const upper = xs.map((x) => [x, AXIS_Y - half(x)] as const);
  const lower = [...xs].reverse().map((x) => [x, AXIS_Y + half(x)] as const);
  const exitHalf = BAND * transmittance;
  const tip: [number, number][] = [
    [exitEnd, AXIS_Y - exitHalf - 7],
    [exitEnd + 26, AXIS_Y],
    [exitEnd, AXIS_Y + exitHalf + 7],
  ];
  const beam = polygon([...upper, ...tip, ...lower], 'fig-beam');
  const state: RngState = { value: p.seed >>> 0 };
  const dots: string[] = [];
  for (let i = 0; i < p.particles; i++) {
    const x = x0 + 6 + rngNextFloat(state) * (slabWidth - 12);
    const y = SLAB_TOP + 8 + rngNextFloat(state) * (SLAB_BOTTOM - SLAB_TOP - 16);
    dots.push(circle(x, y, 2.2, 'fig-particle'));
  }

  // Two of the collisions that remove light from the beam: one scatters out of it, one absorbs.
  const scatterX = x0 + slabWidth * 0.3;
  const absorbX = x0 + slabWidth * 0.62;
  const removal = group('fig-removal', [
    circle(scatterX, AXIS_Y - half(scatterX) * 0.35, 3.2, 'fig-collision'),
    arrow(scatterX, AXIS_Y - half(scatterX) * 0.35, scatterX + 30, SLAB_TOP - 4, {
      cls: 'fig-ink fig-thin',
    }),
    text(scatterX + 34, SLAB_TOP - 6, 'scattered out', 'start', 'fig-text fig-small'),
    circle(absorbX, AXIS_Y + half(absorbX) * 0.4, 3.2, 'fig-collision'),
    line(absorbX, AXIS_Y + half(absorbX) * 0.4, absorbX + 30, SLAB_BOTTOM - 16, 'fig-ink fig-thin'),
    text(absorbX + 34, SLAB_BOTTOM - 12, 'absorbed', 'start', 'fig-text fig-small'),
  ]);

  const body = [
    rect(x0, SLAB_TOP, slabWidth, SLAB_BOTTOM - SLAB_TOP, 'fig-medium'),
    group('fig-particles', dots),
    beam,
    removal,
    math(x0 + 22, SLAB_BOTTOM - 14, 'σ_t'),
    math(96, AXIS_Y - BAND - 12, 'L_0'),
    math(exitEnd - 34, AXIS_Y - BAND - 12, 'L_0 e^{−σ_t d}'),
    line(x0, SLAB_BOTTOM, x0, SLAB_BOTTOM + 32, 'fig-ink fig-thin fig-dash'),
    line(x1, SLAB_BOTTOM, x1, SLAB_BOTTOM + 32, 'fig-ink fig-thin fig-dash'),
    dimension(x0, SLAB_BOTTOM + 24, x1, SLAB_BOTTOM + 24),
    math((x0 + x1) / 2, SLAB_BOTTOM + 46, 'd'),
    math(x0 - 8, SLAB_BOTTOM + 46, 'x = 0', 'end'),
    math(x1 + 8, SLAB_BOTTOM + 46, 'x = d', 'start'),
  ];

  const percent = Math.round(transmittance * 100);
  return {
    width: WIDTH,
    height: HEIGHT,
    title: "Beer's law in a slab",
    description:
      `A beam of radiance L0 enters a homogeneous slab from the left at x = 0. The slab has ` +
      `extinction coefficient σt and thickness d. Inside it, particles scatter some light out of the ` +
      `beam and absorb some; the beam's height, drawn in proportion to its radiance, shrinks ` +
      `exponentially, as L0·e^(−σt·x). It leaves the slab at x = d with radiance L0·e^(−σt·d): ` +
      `${percent} % of L0 for the optical thickness σt·d = ${p.sigmaT * p.thickness} drawn here.`,
    body: body.join(''),
  };
}
