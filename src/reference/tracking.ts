// Float64 twin of shaders/tracking.wesl: unbiased transmittance estimators on a
// segment [0, d] of a Medium1D (physics.md §1, §4). Written from the estimators'
// definitions rather than from the shader: the tentative collisions come from one
// generator (a Poisson process of rate σ̄, §4.1) that every tracker consumes, and
// the unbiased ray-marching series builds its elementary symmetric polynomials as
// the coefficients of ∏(1 + y·z). The random numbers are drawn in the same order
// as on the GPU (rngNextFloat), so a seed gives the same walk on both sides up to
// f32-versus-float64 ties at thresholds. Shared conventions with the shader: the
// caps and their `capped` flag, the clamps on null-collision ratios and weights,
// the clamp of comb estimates to 128 optical depths, σ̄ ≤ 0 meaning "no collisions".
import { mediumExtinction, type Medium1D } from './medium.ts';
import { rngNextFloat, type RngState } from './rng.ts';
import { opticalThicknessHomogeneous, transmittanceHomogeneous } from './transmittance.ts';

/** Default cap on density lookups per walk (see shaders/tracking.wesl for the choice). */
export const TRACKING_MAX_STEPS = 65536;
/** "Never": the largest finite f32, 0x1.fffffep+127 (physics.md §10). */
export const FREE_FLIGHT_NEVER = (2 - 2 ** -23) * 2 ** 127;
/** Largest uniform number of the stream, 1 − 2⁻²⁴ (§9 row 16). */
const XI_MAX = 1 - 2 ** -24;
/** Bound on |σ|/σ̄ in a null-collision weight. */
export const NULL_RATIO_LIMIT = 2 ** 20;
/** Bound on |weight| in (residual) ratio tracking. */
export const TRACKING_WEIGHT_LIMIT = 2 ** 100;

/** Kettunen et al. 2021 roulette constants (physics.md §4.4): p_z, K, c. */
export const URM_ZERO_ORDER_PROBABILITY = 0.9;
export const URM_MIN_ORDER = 2;
export const URM_CONTINUATION = 2;
/** Cap on the expansion order N. */
export const URM_MAX_ORDER = 16;
/** Comb estimates of τ are clamped to [0, 128] (changes nothing f32 can represent). */
export const URM_TAU_LIMIT = 128;

/** Same field names as the WGSL struct TransmittanceEstimate. */
export interface TransmittanceEstimate {
  estimate: number;
  lookups: number;
  /** 1 when a cap cut the walk short. */
  capped: number;
}

const estimateOf = (estimate: number, lookups = 0, capped = 0): TransmittanceEstimate => ({
  estimate,
  lookups,
  capped,
});

/** Free path of pdf σ̄·e^{−σ̄t} by inversion, t = −ln(1 − ξ)/σ̄ (§1); "never" for σ̄ ≤ 0 or beyond f32. */
export function sampleFreeFlight(sigmaMaj: number, xi: number): number {
  if (!(sigmaMaj > 0)) return FREE_FLIGHT_NEVER;
  const u = Math.min(Math.max(xi, 0), XI_MAX);
  return Math.min(-Math.log1p(-u) / sigmaMaj, FREE_FLIGHT_NEVER);
}

/** Binary estimator (§4.1): is the free path at least the segment length? */
export function transmittanceTrackLength(sigmaT: number, d: number, xi: number): number {
  return sampleFreeFlight(sigmaT, xi) >= d ? 1 : 0;
}

/** σn/σ̄ = 1 − σ/σ̄ (§4.2), with σ/σ̄ clamped to ±2²⁰ (σ̄ ≤ 0 counts as an infinite ratio). */
export function nullCollisionWeight(sigma: number, sigmaMaj: number): number {
  if (sigma === 0) return 1;
  const ratio = sigmaMaj > 0 ? sigma / sigmaMaj : Math.sign(sigma) * Infinity;
  return 1 - Math.min(Math.max(ratio, -NULL_RATIO_LIMIT), NULL_RATIO_LIMIT);
}

const clampWeight = (weight: number): number =>
  Math.min(Math.max(weight, -TRACKING_WEIGHT_LIMIT), TRACKING_WEIGHT_LIMIT);

/**
 * Positions of the tentative collisions in [0, d): a Poisson process of rate σ̄,
 * one random number per point (the free path to it). The consumer may draw more
 * numbers between points; the order of draws is then the shader's.
 */
function* tentativeCollisions(sigmaMaj: number, d: number, state: RngState): Generator<number> {
  let position = 0;
  for (;;) {
    const flight = sampleFreeFlight(sigmaMaj, rngNextFloat(state));
    if (position + flight >= d) return;
    position += flight;
    yield position;
  }
}

/** Woodcock tracking (§4.1): 1 if no tentative collision is accepted (probability min(σt/σ̄, 1)). */
export function transmittanceDeltaTracking(
  medium: Medium1D,
  d: number,
  sigmaMaj: number,
  state: RngState,
  maxSteps: number,
): TransmittanceEstimate {
  if (!(sigmaMaj > 0) || !(d > 0)) return estimateOf(1);
  let lookups = 0;
  for (const position of tentativeCollisions(sigmaMaj, d, state)) {
    if (lookups === maxSteps) return estimateOf(1, lookups, 1);
    lookups++;
    const acceptance = Math.min(mediumExtinction(medium, position) / sigmaMaj, 1);
    if (rngNextFloat(state) < acceptance) return estimateOf(0, lookups);
  }
  return estimateOf(1, lookups);
}

/** Ratio tracking (§4.2): ∏(1 − σt/σ̄) over the tentative collisions; stops when it is 0. */
export function transmittanceRatioTracking(
  medium: Medium1D,
  d: number,
  sigmaMaj: number,
  state: RngState,
  maxSteps: number,
): TransmittanceEstimate {
  if (!(sigmaMaj > 0) || !(d > 0)) return estimateOf(1);
  let weight = 1;
  let lookups = 0;
  for (const position of tentativeCollisions(sigmaMaj, d, state)) {
    if (lookups === maxSteps) return estimateOf(weight, lookups, 1);
    lookups++;
    weight = clampWeight(
      weight * nullCollisionWeight(mediumExtinction(medium, position), sigmaMaj),
    );
    if (weight === 0) break;
  }
  return estimateOf(weight, lookups);
}

/** Residual ratio tracking (§4.3): e^{−σc·d}·∏(1 − (σt − σc)/σ̄r), σc clamped to ≥ 0. */
export function transmittanceResidualRatioTracking(
  medium: Medium1D,
  d: number,
  sigmaControl: number,
  sigmaResidualMaj: number,
  state: RngState,
  maxSteps: number,
): TransmittanceEstimate {
  const sigmaC = Math.max(sigmaControl, 0);
  const control = transmittanceHomogeneous(sigmaC, d);
  if (!(sigmaResidualMaj > 0) || !(d > 0) || control === 0) return estimateOf(control);
  let weight = 1;
  let lookups = 0;
  let capped = 0;
  for (const position of tentativeCollisions(sigmaResidualMaj, d, state)) {
    if (lookups === maxSteps) {
      capped = 1;
      break;
    }
    lookups++;
    const residual = mediumExtinction(medium, position) - sigmaC;
    weight = clampWeight(weight * nullCollisionWeight(residual, sigmaResidualMaj));
    if (weight === 0) break;
  }
  return estimateOf(control * weight, lookups, capped);
}

/**
 * P_n of the null-scattering path integral (Miller, Georgiev & Jarosz 2019) for a shadow
 * ray: 1 − (1 − β)·σt/(|σn| + σt), σn = σ̄ − σt, β = nullBlend clamped to [0, 1]. β = 0 is
 * delta tracking's σn/σ̄ where 0 ≤ σt ≤ σ̄ (|σn|/(|σn| + σt) above), β = 1 ratio tracking's 1.
 * The fraction is written as in the shader (σt/σ̄, or 1/(2 − σ̄/σt) for σt > σ̄).
 */
export function nullScatteringProbability(
  sigmaT: number,
  sigmaMaj: number,
  nullBlend: number,
): number {
  const beta = Math.min(Math.max(nullBlend, 0), 1);
  let fraction = 1;
  if (!(sigmaT > 0)) fraction = 0;
  else if (sigmaT <= sigmaMaj) fraction = sigmaT / sigmaMaj;
  else if (sigmaMaj > 0) fraction = 1 / (2 - sigmaMaj / sigmaT);
  return 1 - (1 - beta) * fraction;
}

/** One vertex of a null-scattering walk, for figures: where, what, and the weight after it. */
export interface NullScatteringVertex {
  t: number;
  /** The real/null number ξ of the vertex. */
  xi: number;
  nullProbability: number;
  kind: 'null' | 'real';
  /** The walk's weight after this vertex (0 after a real one). */
  weight: number;
}

/**
 * The walk of transmittanceNullScattering, vertex by vertex (same stream, same decisions,
 * same clamps): the estimate is the weight after the last vertex, or 1 without vertices.
 */
export function nullScatteringWalk(
  medium: Medium1D,
  d: number,
  sigmaMaj: number,
  nullBlend: number,
  state: RngState,
  maxSteps: number,
): { vertices: NullScatteringVertex[]; result: TransmittanceEstimate } {
  const vertices: NullScatteringVertex[] = [];
  if (!(sigmaMaj > 0) || !(d > 0)) return { vertices, result: estimateOf(1) };
  let weight = 1;
  for (const position of tentativeCollisions(sigmaMaj, d, state)) {
    if (vertices.length === maxSteps) return { vertices, result: estimateOf(weight, maxSteps, 1) };
    const sigmaT = mediumExtinction(medium, position);
    const probability = nullScatteringProbability(sigmaT, sigmaMaj, nullBlend);
    const xi = rngNextFloat(state);
    // Real vertex when ξ < 1 − P_n (delta tracking's ξ < σt/σ̄ for β = 0): the shadow path ends, 0.
    if (xi < 1 - probability) {
      vertices.push({ t: position, xi, nullProbability: probability, kind: 'real', weight: 0 });
      return { vertices, result: estimateOf(0, vertices.length) };
    }
    // Null vertex: f/p gains σn/(σ̄·P_n), clamped like the shader's factor and product.
    const factor = Math.min(
      Math.max(nullCollisionWeight(sigmaT, sigmaMaj) / probability, -NULL_RATIO_LIMIT),
      NULL_RATIO_LIMIT,
    );
    weight = clampWeight(weight * factor);
    vertices.push({ t: position, xi, nullProbability: probability, kind: 'null', weight });
    if (weight === 0) break;
  }
  return { vertices, result: estimateOf(weight, vertices.length) };
}

/**
 * Null-scattering transmittance (Miller et al. 2019; shaders/tracking.wesl): the product of
 * σn/(σ̄·P_n) over the tentative collisions if all are taken as null vertices, else 0.
 * Unbiased for every P_n > 0 where σn ≠ 0; see nullScatteringSecondMoment for its variance.
 */
export function transmittanceNullScattering(
  medium: Medium1D,
  d: number,
  sigmaMaj: number,
  nullBlend: number,
  state: RngState,
  maxSteps: number,
): TransmittanceEstimate {
  return nullScatteringWalk(medium, d, sigmaMaj, nullBlend, state, maxSteps).result;
}

/**
 * Integrand of the second moment's exponent, E[T̂²] = exp(−∫(σ̄ − σn²/(σ̄·P_n)) ds): the
 * Campbell identity on the Poisson process of rate σ̄ with E[factor² | x] = σn²/(σ̄²·P_n).
 * P_n = 0 with σn ≠ 0 makes the estimator biased (never null where it should be), so it is
 * reported as NaN; P_n = 0 with σn = 0 contributes σ̄.
 */
export function nullScatteringSecondMomentRate(
  sigmaT: number,
  sigmaMaj: number,
  nullProbability: number,
): number {
  const sigmaN = sigmaMaj - sigmaT;
  if (sigmaN === 0) return sigmaMaj;
  if (!(nullProbability > 0)) return NaN;
  return sigmaMaj - (sigmaN * sigmaN) / (sigmaMaj * nullProbability);
}

/** w_k = P(N ≥ k) of the Kettunen et al. roulette (§4.4), without the order cap. */
export function unbiasedRayMarchingOrderProbability(k: number): number {
  if (k <= 0) return 1;
  let probability = 1 - URM_ZERO_ORDER_PROBABILITY;
  for (let i = URM_MIN_ORDER + 1; i <= k; i++) probability *= Math.min(URM_CONTINUATION / i, 1);
  return probability;
}

/** E[N] = Σ_{k≥1} P(N ≥ k); physics.md §4.4 gives 0.1·(2 + (e² − 5)/2) = 0.31945. */
export function unbiasedRayMarchingExpectedOrder(): number {
  let sum = 0;
  for (let k = 1; k < 64; k++) sum += unbiasedRayMarchingOrderProbability(k);
  return sum;
}

/** E[N] as a constant, from the closed form above. */
const URM_MEAN_ORDER = 0.1 * (2 + (Math.E ** 2 - 5) / 2);

/** M = max(1, round(N_CMF(τ̄)/(E[N] + 1))), limited so that URM_MAX_ORDER + 1 combs fit maxSteps (§4.4). */
export function unbiasedRayMarchingCombSize(tauMaj: number, maxSteps: number): number {
  const tau = Math.min(Math.max(tauMaj, 0), 1e6);
  const cmf = Math.ceil(Math.cbrt((0.015 + tau) * (0.65 + tau) * (60.3 + tau)));
  const size = Math.max(1, Math.round(cmf / (1 + URM_MEAN_ORDER)));
  return Math.min(size, Math.max(1, Math.floor(maxSteps / (URM_MAX_ORDER + 1))));
}

/** Draws N: 0 with probability p_z, else K and then k with probability w_k/w_{k−1}. */
function sampleExpansionOrder(state: RngState): { order: number; capped: boolean } {
  if (rngNextFloat(state) < URM_ZERO_ORDER_PROBABILITY) return { order: 0, capped: false };
  let order = URM_MIN_ORDER;
  for (;;) {
    const continuation =
      unbiasedRayMarchingOrderProbability(order + 1) / unbiasedRayMarchingOrderProbability(order);
    if (rngNextFloat(state) >= continuation) return { order, capped: false };
    if (order + 1 > URM_MAX_ORDER) return { order, capped: true };
    order++;
  }
}

function binomial(n: number, k: number): number {
  let value = 1;
  for (let i = 1; i <= k; i++) value = (value * (n - k + i)) / i;
  return value;
}

function factorial(k: number): number {
  let value = 1;
  for (let i = 2; i <= k; i++) value *= i;
  return value;
}

/** Coefficients e_0..e_n of ∏_i (1 + y_i·z): the elementary symmetric polynomials of y. */
function elementarySymmetric(values: readonly number[]): number[] {
  let coefficients = [1];
  for (const y of values) {
    coefficients = [...coefficients, 0].map(
      (c, k) => c + (k > 0 ? y * (coefficients[k - 1] ?? 0) : 0),
    );
  }
  return coefficients;
}

/** Unbiased ray marching (Kettunen et al. 2021, physics.md §4.4). */
export function transmittanceUnbiasedRayMarching(
  medium: Medium1D,
  d: number,
  sigmaMaj: number,
  state: RngState,
  maxSteps: number,
): TransmittanceEstimate {
  if (!(d > 0)) return estimateOf(1);
  const combSize = unbiasedRayMarchingCombSize(opticalThicknessHomogeneous(sigmaMaj, d), maxSteps);
  const drawn = sampleExpansionOrder(state);
  let order = drawn.order;
  let capped = drawn.capped ? 1 : 0;
  if (combSize > maxSteps) return estimateOf(1, 0, 1);
  if ((order + 1) * combSize > maxSteps) {
    order = Math.floor(maxSteps / combSize) - 1;
    capped = 1;
  }
  // Each comb: M equidistant points (m + u)·d/M with its own offset u; τ̂ = Σ σt·d/M.
  const spacing = d / combSize;
  const tau: number[] = [];
  for (let i = 0; i <= order; i++) {
    const offset = rngNextFloat(state);
    let sum = 0;
    for (let m = 0; m < combSize; m++) {
      const position = ((m + offset) / combSize) * d;
      sum += opticalThicknessHomogeneous(mediumExtinction(medium, position), spacing);
    }
    tau.push(Math.min(sum, URM_TAU_LIMIT));
  }
  // T̂ = 1/(N+1) Σ_j e^{−τ_j} Σ_k m_k/(k!·w_k), m_k = e_k(τ_j − τ_i, i ≠ j)/C(N, k).
  let total = 0;
  tau.forEach((pivot, j) => {
    const e = elementarySymmetric(tau.filter((_, i) => i !== j).map((t) => pivot - t));
    let series = 0;
    for (let k = 0; k <= order; k++)
      series +=
        (e[k] ?? 0) / (binomial(order, k) * factorial(k) * unbiasedRayMarchingOrderProbability(k));
    total += Math.exp(-pivot) * series;
  });
  return estimateOf(total / (order + 1), (order + 1) * combSize, capped);
}

// Closed forms of physics.md §4 for tests and benchmarks.

/** Delta tracking / track length: X ∈ {0, 1} with E[X] = T, so Var = T(1 − T) (§4.1). */
export function deltaTrackingVariance(transmittance: number): number {
  return transmittance * (1 - transmittance);
}

/**
 * Ratio tracking in a homogeneous medium (§4.2): Var = e^{−2τ}(e^{τ²/τ̄} − 1) with
 * τ = σt·d and τ̄ = σ̄·d. It equals T(1 − T) for a tight majorant τ̄ = τ; τ̄ → 0 with
 * τ > 0 diverges (Infinity).
 */
export function ratioTrackingVarianceHomogeneous(tau: number, tauMaj: number): number {
  if (tau === 0) return 0;
  if (!(tauMaj > 0)) return Infinity;
  return Math.exp(-2 * tau) * Math.expm1((tau * tau) / tauMaj);
}

/**
 * Ratio tracking in general (§4.2): Var = T²(exp(∫σt²/σ̄ ds) − 1); with ∫(σt − σc)²/σ̄r
 * in place of the integral it is residual ratio tracking's variance (§4.3).
 */
export function ratioTrackingVariance(transmittance: number, squaredRatioIntegral: number): number {
  return transmittance * transmittance * Math.expm1(squaredRatioIntegral);
}

/**
 * Mean number of σt lookups of delta tracking in a homogeneous medium with
 * σ ≤ σ̄ (§4.1): (σ̄/σ)(1 − e^{−σd}) — the majorant rate times the expected path
 * length min(X, d), X ~ Exp(σ). σ = 0 gives the limit σ̄·d; σ̄ ≤ 0 gives 0.
 */
export function expectedDeltaTrackingLookups(sigma: number, sigmaMaj: number, d: number): number {
  if (!(sigmaMaj > 0) || !(d > 0)) return 0;
  if (sigma === 0) return sigmaMaj * d;
  return (sigmaMaj / sigma) * -Math.expm1(-sigma * d);
}

/** Mean number of σt lookups of ratio tracking without early exit (§4.2): σ̄·d. */
export function expectedRatioTrackingLookups(sigmaMaj: number, d: number): number {
  return sigmaMaj > 0 && d > 0 ? sigmaMaj * d : 0;
}
