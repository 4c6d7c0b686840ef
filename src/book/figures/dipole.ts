// Figure for the classical dipole (chapter 11, eq:dipole-boundary, eq:dipole-sources,
// eq:dipole-profile; Jensen et al. 2001): the real source at depth z_r = 1/σt′ below the
// surface, the extrapolated boundary at height z_b = 2AD above it, and the negative
// virtual source, the real one mirrored in that plane, at height z_v = z_r + 4AD. The
// geometry is to scale: z_r, z_v and A come from the float64 twin (src/reference/dipole.ts,
// dipoleParameters) for the refractive index below; the figure checks z_b = (z_v − z_r)/2.
import { dipoleParameters } from '../../reference/dipole.ts';
import { arrow, circle, dimension, group, line, math, rect, text, type Diagram } from './svg.ts';

export interface DipoleParameters {
  /** Reduced scattering and absorption coefficients (1/mm); only σt′ = σs′ + σa sets z_r. */
  sigmaSPrime: number;
  sigmaA: number;
  /** Relative refractive index η; it sets A, hence z_b and z_v. */
  eta: number;
  /** Radius r of the surface point x_o, in units of z_r. */
  radiusOverZr: number;
  /** Pixels per z_r. */
  scale: number;
}

export const DIPOLE_FIGURE: DipoleParameters = {
  sigmaSPrime: 1,
  sigmaA: 0.01,
  eta: 1.3,
  radiusOverZr: 3.2,
  scale: 40,
};

const WIDTH = 640;
const HEIGHT = 322;
const SURFACE_Y = 214;
const SOURCE_X = 236;

export function dipoleFigure(p: DipoleParameters = DIPOLE_FIGURE): Diagram {
  const dipole = dipoleParameters(p.sigmaSPrime, p.sigmaA, p.eta);
  const zr = dipole.zr;
  const diffusion = 1 / (3 * dipole.sigmaTPrime);
  const zb = 2 * dipole.boundaryA * diffusion;
  // The virtual source is the real one mirrored in the extrapolated boundary (Jensen eq. 5).
  if (Math.abs(dipole.zv - (zr + 2 * zb)) > 1e-12 * dipole.zv) {
    throw new Error('dipole figure: z_v ≠ z_r + 2 z_b; the twin and the figure disagree');
  }
  const px = p.scale / zr;
  const realY = SURFACE_Y + zr * px;
  const boundaryY = SURFACE_Y - zb * px;
  const virtualY = SURFACE_Y - dipole.zv * px;
  const xo = SOURCE_X + p.radiusOverZr * p.scale;
  const xi = SOURCE_X;

  const body = [
    rect(0, SURFACE_Y, WIDTH, HEIGHT - SURFACE_Y, 'fig-medium'),
    line(0, SURFACE_Y, WIDTH, SURFACE_Y, 'fig-ink fig-thick'),
    line(0, boundaryY, WIDTH, boundaryY, 'fig-ink fig-dash'),
    text(
      WIDTH - 8,
      boundaryY - 8,
      'extrapolated boundary (fluence 0)',
      'end',
      'fig-text fig-small',
    ),
    text(WIDTH - 8, SURFACE_Y - 8, 'surface', 'end', 'fig-text fig-small'),
    text(WIDTH - 8, SURFACE_Y + 22, 'medium', 'end', 'fig-text fig-small'),
    // Incident light at x_i, normal to the surface, and light leaving at x_o.
    arrow(xi - 70, SURFACE_Y - 122, xi - 2, SURFACE_Y - 3, { cls: 'fig-ink fig-thick' }),
    text(xi - 76, SURFACE_Y - 128, 'incident light', 'end', 'fig-text fig-small'),
    arrow(xo, SURFACE_Y - 2, xo + 30, SURFACE_Y - 76, { cls: 'fig-ink fig-thick' }),
    circle(xi, SURFACE_Y, 3.5, 'fig-solid'),
    circle(xo, SURFACE_Y, 3.5, 'fig-solid'),
    math(xi + 10, SURFACE_Y + 22, '*x*_i', 'start'),
    math(xo + 8, SURFACE_Y + 22, '*x*_o', 'start'),
    // Distances from the two sources to x_o.
    line(SOURCE_X, realY, xo, SURFACE_Y, 'fig-accent'),
    line(SOURCE_X, virtualY, xo, SURFACE_Y, 'fig-warm'),
    math(
      (SOURCE_X + xo) / 2 + 6,
      (realY + SURFACE_Y) / 2 + 24,
      'd_r',
      'start',
      'fig-math fig-accent-text',
    ),
    math(
      (SOURCE_X + xo) / 2 + 12,
      (virtualY + SURFACE_Y) / 2 - 2,
      'd_v',
      'start',
      'fig-math fig-warm-text',
    ),
    // The radius r along the surface, between the boundary and the surface.
    dimension(xi, SURFACE_Y - 22, xo, SURFACE_Y - 22),
    math((xi + xo) / 2, SURFACE_Y - 30, 'r'),
    group('fig-sources', [
      circle(SOURCE_X, realY, 11, 'fig-solid-accent'),
      text(SOURCE_X, realY + 5, '+', 'middle', 'fig-text fig-on-dark'),
      text(SOURCE_X, realY + 30, 'real source', 'middle', 'fig-text fig-small'),
      circle(SOURCE_X, virtualY, 11, 'fig-hollow-warm'),
      text(SOURCE_X, virtualY + 5, '−', 'middle', 'fig-text fig-warm-text'),
      text(SOURCE_X + 18, virtualY + 5, 'virtual source (negative)', 'start', 'fig-text fig-small'),
    ]),
    // Heights on the left, measured from the surface.
    line(SOURCE_X - 12, virtualY, 52, virtualY, 'fig-muted fig-thin fig-dot'),
    line(SOURCE_X - 12, realY, 128, realY, 'fig-muted fig-thin fig-dot'),
    dimension(140, SURFACE_Y, 140, realY),
    math(132, (SURFACE_Y + realY) / 2 + 6, 'z_r', 'end'),
    dimension(104, SURFACE_Y, 104, boundaryY),
    math(96, (SURFACE_Y + boundaryY) / 2 + 6, 'z_b', 'end'),
    dimension(60, SURFACE_Y, 60, virtualY),
    math(52, (SURFACE_Y + virtualY) / 2 + 6, 'z_v', 'end'),
  ];

  const ratio = (value: number): string => (value / zr).toFixed(2);
  return {
    width: WIDTH,
    height: HEIGHT,
    title: 'The dipole: real and virtual sources and the extrapolated boundary',
    description:
      `A horizontal surface separates air above from a scattering medium below. Light enters at x_i. ` +
      `A positive real point source sits at depth z_r = 1/σt′ directly below x_i. A dashed plane, the ` +
      `extrapolated boundary, lies at height z_b = 2AD above the surface, and a negative virtual ` +
      `source sits at height z_v = z_r + 4AD, the mirror image of the real source in that plane. ` +
      `Light leaves at a surface point x_o at distance r from x_i; lines of length d_r and d_v join it ` +
      `to the real and the virtual source. Drawn to scale for η = ${p.eta}: A = ${dipole.boundaryA.toFixed(2)}, ` +
      `z_b = ${ratio(zb)} z_r, z_v = ${ratio(dipole.zv)} z_r.`,
    body: body.join(''),
  };
}
