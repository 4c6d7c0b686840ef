// Float64 twin of shaders/phase.wesl (physics.md §2): isotropic, Henyey–Greenstein
// and Rayleigh phase functions and their samplers. Direction convention: the one
// stated at the top of shaders/phase.wesl — μ is the cosine between the directions
// of travel before and after scattering (g > 0 forward), wo and wi both point away
// from the scattering point as in pbrt-v4, so μ = −wo·wi, 1 − μ = ½|wo + wi|² and
// 1 + μ = ½|wo − wi|².
//
// Written from the formulas, not from the shader: the g < 0 sampler recurses on
// the mirrored lobe, the complements divide by D² instead of scaling by 1/D, the
// Rayleigh cubic is solved in its hyperbolic form, and the power d^{3/2} is taken
// with Math.pow (accurate in float64). The clamps, the rule that picks μ from the
// smaller complement and the basis/azimuth conventions are shared, because a WGSL
// result can only be compared with a twin that draws the same point.
//
// orthonormalBasis, directionAroundAxis and sampleUniformSphere are twinned in
// directions.ts, as their WGSL moved to shaders/directions.wesl.

import { directionAroundAxis, type Vec3 } from './directions.ts';

export type { Vec3 };

/** Same numbers as the shader: its f32 |g| limit (see HG_MAX_ABS_G in phase.wesl). */
export const HG_MAX_ABS_G = Math.fround(0.99999);

export interface HgMuSample {
  mu: number;
  oneMinusMu: number;
  onePlusMu: number;
}

export interface PhaseSample {
  wi: Vec3;
  pdf: number;
}

const clamp = (x: number, lo: number, hi: number): number => Math.min(Math.max(x, lo), hi);
const clampG = (g: number): number => clamp(g, -HG_MAX_ABS_G, HG_MAX_ABS_G);
const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

/** p = 1/(4π) (physics.md §2.1). */
export function phaseIsotropic(): number {
  return 1 / (4 * Math.PI);
}

/**
 * HG from the two complements of μ (physics.md §2.5): the denominator
 * 1 + g² − 2gμ written as (1 − g)² + 2g(1 − μ) for g ≥ 0 and (1 + g)² − 2g(1 + μ)
 * for g < 0. Even float64 needs this form: the naive one is off by 1.3e-10 at
 * g = 0.999, μ = 1.
 */
export function hgEvalTerms(g: number, oneMinusMu: number, onePlusMu: number): number {
  const gc = clampG(g);
  const d =
    gc >= 0
      ? (1 - gc) ** 2 + 2 * gc * clamp(oneMinusMu, 0, 2)
      : (1 + gc) ** 2 - 2 * gc * clamp(onePlusMu, 0, 2);
  return ((1 - gc) * (1 + gc)) / (4 * Math.PI * Math.pow(d, 1.5));
}

/** p_HG(μ; g) = (1/4π)(1 − g²)/(1 + g² − 2gμ)^{3/2} (physics.md §2.2). */
export function hgEval(g: number, mu: number): number {
  const m = clamp(mu, -1, 1);
  return hgEvalTerms(g, 1 - m, 1 + m);
}

/** μ = −wo·wi with 1 − μ = ½|wo + wi|² and 1 + μ = ½|wo − wi|² (physics.md §2.5). */
export function hgEvalDirections(g: number, wo: Vec3, wi: Vec3): number {
  const sum: Vec3 = [wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]];
  const difference: Vec3 = [wo[0] - wi[0], wo[1] - wi[1], wo[2] - wi[2]];
  return hgEvalTerms(g, 0.5 * dot(sum, sum), 0.5 * dot(difference, difference));
}

/**
 * Inverse CDF of HG in μ (physics.md §2.4, textbook mapping ξ = 0 → μ = −1) in the
 * product form: with D = 1 − g + 2gξ, 1 − μ = 2(1 − g)²(1 − ξ)(1 + gξ)/D² and
 * 1 + μ = 2(1 + g)²ξ(1 − g + gξ)/D². Backward lobes mirror the forward one:
 * μ(g, ξ) = −μ(−g, 1 − ξ).
 */
export function hgSampleMu(g: number, xi: number, oneMinusXi: number): HgMuSample {
  const gc = clampG(g);
  if (gc < 0) {
    const mirrored = hgSampleMu(-gc, oneMinusXi, xi);
    return {
      mu: -mirrored.mu,
      oneMinusMu: mirrored.onePlusMu,
      onePlusMu: mirrored.oneMinusMu,
    };
  }
  const x = clamp(xi, 0, 1);
  const y = clamp(oneMinusXi, 0, 1);
  const denominator = (1 - gc + 2 * gc * x) ** 2;
  const oneMinusMu = Math.min((2 * (1 - gc) ** 2 * y * (1 + gc * x)) / denominator, 2);
  const onePlusMu = Math.min((2 * (1 + gc) ** 2 * x * (1 - gc + gc * x)) / denominator, 2);
  // μ from the smaller complement (§2.4): the zero complement at ξ = 0 or 1 is
  // exactly 0, so μ = ∓1 exactly there.
  const mu = oneMinusMu < onePlusMu ? 1 - oneMinusMu : onePlusMu - 1;
  return { mu, oneMinusMu, onePlusMu };
}

/** HG sample around the direction of travel −wo; pdf = HG at the sampled complements. */
export function hgSample(g: number, wo: Vec3, u: readonly [number, number]): PhaseSample {
  const { mu, oneMinusMu, onePlusMu } = hgSampleMu(g, u[0], 1 - u[0]);
  const sinTheta = Math.sqrt(Math.max(0, oneMinusMu * onePlusMu));
  const travel: Vec3 = [-wo[0], -wo[1], -wo[2]];
  return {
    wi: directionAroundAxis(travel, mu, sinTheta, u[1]),
    pdf: hgEvalTerms(g, oneMinusMu, onePlusMu),
  };
}

/** p_R(μ) = 3/(16π)(1 + μ²) (physics.md §2.6). */
export function rayleighEval(mu: number): number {
  const m = clamp(mu, -1, 1);
  return (3 / (16 * Math.PI)) * (1 + m * m);
}

/** The real cube root (negative for negative x). */
export function cbrtReal(x: number): number {
  return Math.cbrt(x);
}

/**
 * Solves F(μ) = (μ³ + 3μ + 4)/8 = ξ (physics.md §2.6), i.e. μ³ + 3μ = 2z with
 * z = 2(2ξ − 1). With μ = 2 sinh t the cubic becomes 2 sinh 3t = 2z, so
 * μ = 2 sinh(asinh(z)/3): the hyperbolic form of Cardano's root.
 */
export function rayleighSampleMu(xi: number): number {
  const z = 2 * (2 * clamp(xi, 0, 1) - 1);
  return clamp(2 * Math.sinh(Math.asinh(z) / 3), -1, 1);
}

/** Rayleigh sample around −wo; pdf = rayleighEval(μ). */
export function rayleighSample(wo: Vec3, u: readonly [number, number]): PhaseSample {
  const mu = rayleighSampleMu(u[0]);
  const travel: Vec3 = [-wo[0], -wo[1], -wo[2]];
  return {
    wi: directionAroundAxis(travel, mu, Math.sqrt(Math.max(0, 1 - mu * mu)), u[1]),
    pdf: rayleighEval(mu),
  };
}
