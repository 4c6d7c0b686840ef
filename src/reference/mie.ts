// Lorenz–Mie scattering by a homogeneous sphere, in float64 (issue 21), and the float64
// twins of the tabulated phase function of shaders/mie.wesl.
//
// The series runs on the CPU (a worker in the widget, setup in a scene): for x = 10⁴ it
// sums ten thousand terms whose ratios f32 cannot hold, so the GPU only evaluates and
// samples a table of p(μ) that this file builds (mieTabulatePhase).
//
// Conventions (Bohren & Huffman 1983, "Absorption and Scattering of Light by Small
// Particles", ch. 4, hereafter BH):
// - size parameter x = 2πr/λ (λ in the surrounding medium), relative refractive index
//   m = n + iκ with κ ≥ 0 for an absorbing sphere (time dependence e^{−iωt}, BH's sign).
//   Wiscombe's MIEV0 writes m = n − iκ (e^{+iωt}); its coefficients and S1, S2 are the
//   complex conjugates of BH's, and every real quantity (Q's, g, |S|², p) is the same.
// - Riccati–Bessel functions ψ_n(x) = x j_n(x), χ_n(x) = −x y_n(x), ξ_n = ψ_n − iχ_n (BH 4.56).
// - a_n, b_n from the logarithmic derivative D_n(mx) = ψ_n'(mx)/ψ_n(mx) (BH 4.88):
//     a_n = [(D_n/m + n/x) ψ_n − ψ_{n−1}] / [(D_n/m + n/x) ξ_n − ξ_{n−1}],
//     b_n = [(m D_n + n/x) ψ_n − ψ_{n−1}] / [(m D_n + n/x) ξ_n − ξ_{n−1}].
// - Q_ext = (2/x²) Σ (2n+1) Re(a_n + b_n), Q_sca = (2/x²) Σ (2n+1)(|a_n|² + |b_n|²) (BH 4.61–62),
//   Q_back = |Σ (2n+1)(−1)ⁿ(a_n − b_n)|²/x² (BH 4.82), and
//   g = (4/(x² Q_sca)) Σ [n(n+2)/(n+1) Re(a_n a*_{n+1} + b_n b*_{n+1}) + (2n+1)/(n(n+1)) Re(a_n b*_n)]
//   (BH 4.80).
// - S1 = Σ (2n+1)/(n(n+1)) (a_n π_n + b_n τ_n), S2 = Σ (2n+1)/(n(n+1)) (a_n τ_n + b_n π_n) (BH 4.74).
// - PHASE FUNCTION, per steradian: dC_sca/dΩ = (|S1|² + |S2|²)/(2k²) for unpolarised light
//   (BH 3.16 with S11 = ½(|S1|² + |S2|²)) and C_sca = Q_sca π r² = Q_sca π x²/k², so
//       p(μ) = (|S1|² + |S2|²) / (2π x² Q_sca),    ∫_{4π} p dω = 1,
//   the same normalisation as shaders/phase.wesl (tests/reference/mie.test.ts integrates it).
//   μ = cos θ is the cosine between the directions of travel (μ = 1 forward), as there.
//
// Algorithm after Wiscombe 1980, "Improved Mie scattering algorithms", Appl. Opt. 19, 1505
// (and NCAR/TN-140+STR, 1979):
// - the number of terms N of mieTermCount (his eq. for N_stop);
// - D_n(mx) by downward recurrence D_{n−1} = n/z − 1/(D_n + n/z) from D = 0 at
//   n = max(N, |mx|) + 15 + 16|mx|^{1/3}: the recurrence is stable downward for every m,
//   but the error of the start decays only once n is past the turning point |mx| by a few
//   of its widths |mx|^{1/3}. BH's BHMIE starts at max(N, |mx|) + 15, which at x = 10⁴,
//   m = 1.33 + 10⁻⁵i leaves D_1 wrong in the first digit and Q_sca off by 0.3%
//   (tests/reference/mie.test.ts holds the published value);
// - ψ_n, χ_n by upward recurrence (stable for n ≲ x, and the terms beyond x are tiny);
//   for x < 1 ψ_n is instead built from the ratios ψ_n/ψ_{n−1} by downward recurrence,
//   because upward it is the difference of nearly equal numbers (ψ_1 = sin x/x − cos x);
// - for x ≤ 0.1 and |m|x ≤ 0.1 his small-particle expansion of a_1, b_1, a_2 to O(x⁴)
//   relative (MIEV0's SMALL1/SMALL2; Wiscombe 1979 eqs. for Â₁, B̂₁, Â₂).

import { directionAroundAxis, type Vec3 } from './directions.ts';

export type { Vec3 };

/** A complex number as a pair: [real part, imaginary part]. */
export type Complex = readonly [number, number];

export const complexAdd = (a: Complex, b: Complex): Complex => [a[0] + b[0], a[1] + b[1]];
export const complexSub = (a: Complex, b: Complex): Complex => [a[0] - b[0], a[1] - b[1]];
export const complexMul = (a: Complex, b: Complex): Complex => [
  a[0] * b[0] - a[1] * b[1],
  a[0] * b[1] + a[1] * b[0],
];
export const complexScale = (a: Complex, s: number): Complex => [a[0] * s, a[1] * s];
export const complexConj = (a: Complex): Complex => [a[0], -a[1]];
export const complexAbs2 = (a: Complex): number => a[0] * a[0] + a[1] * a[1];

/** a/b by Smith's algorithm (no overflow of |b|² for large |b|). */
export function complexDiv(a: Complex, b: Complex): Complex {
  if (Math.abs(b[0]) >= Math.abs(b[1])) {
    const r = b[1] / b[0];
    const d = b[0] + b[1] * r;
    return [(a[0] + a[1] * r) / d, (a[1] - a[0] * r) / d];
  }
  const r = b[0] / b[1];
  const d = b[0] * r + b[1];
  return [(a[0] * r + a[1]) / d, (a[1] * r - a[0]) / d];
}

/** The relative refractive index m = n + iκ (κ ≥ 0 absorbs, BH's convention). */
export interface RefractiveIndex {
  n: number;
  kappa: number;
}

/**
 * Wiscombe's number of terms (1980, eq. for N_stop; MIEV0's NTRM): x + 4x^{1/3} + 1 for
 * x ≤ 8, x + 4.05x^{1/3} + 2 for 8 < x < 4200 and x + 4x^{1/3} + 2 above, truncated.
 * The solver takes at least MIE_MIN_TERMS of them.
 */
export function mieTermCount(x: number): number {
  const cube = Math.cbrt(x);
  if (x <= 8) return Math.floor(x + 4 * cube + 1);
  if (x < 4200) return Math.floor(x + 4.05 * cube + 2);
  return Math.floor(x + 4 * cube + 2);
}

/**
 * At least a_1, b_1, a_2, b_2, a_3, b_3: Wiscombe's count gives one term at x = 0.01, which
 * leaves out a_2 ∝ x⁵ m²… when |m|x > 0.1 sends such an x to the full series.
 */
export const MIE_MIN_TERMS = 3;

/** Largest size parameter the solver accepts (the brief's range; terms ≈ x). */
export const MIE_MAX_SIZE = 2e4;

/**
 * D_n(z) = ψ_n'(z)/ψ_n(z) for n = 0…nMax by downward recurrence (Wiscombe 1980 §IV; BH
 * 4.89): D_{n−1} = n/z − 1/(D_n + n/z), started from 0 at n = max(nMax, |z|) + 15 +
 * 16|z|^{1/3} (header).
 */
export function mieLogDerivative(z: Complex, nMax: number): Complex[] {
  const modulus = Math.hypot(z[0], z[1]);
  const start = Math.ceil(Math.max(nMax, modulus) + 15 + 16 * Math.cbrt(modulus));
  const d: Complex[] = new Array<Complex>(nMax + 1);
  let current: Complex = [0, 0];
  for (let n = start; n >= 1; n--) {
    const nOverZ = complexDiv([n, 0], z);
    if (n <= nMax) d[n] = current;
    current = complexSub(nOverZ, complexDiv([1, 0], complexAdd(current, nOverZ)));
  }
  d[0] = current;
  return d;
}

/**
 * ψ_n(x) for n = 0…nMax. Upward (ψ_{n} = (2n−1)/x ψ_{n−1} − ψ_{n−2}) for x ≥ 1; for x < 1
 * from the ratios r_n = ψ_n/ψ_{n−1} = 1/((2n+1)/x − r_{n+1}) computed downward (Miller's
 * algorithm), with ψ_0 = sin x: every ψ_n then keeps full relative precision.
 */
export function riccatiBesselPsi(x: number, nMax: number): number[] {
  const psi = new Array<number>(nMax + 1);
  psi[0] = Math.sin(x);
  if (x >= 1) {
    let previous = Math.cos(x); // ψ_{−1}
    for (let n = 1; n <= nMax; n++) {
      const next = ((2 * n - 1) / x) * psi[n - 1]! - previous;
      previous = psi[n - 1]!;
      psi[n] = next;
    }
    return psi;
  }
  const ratios = new Array<number>(nMax + 1).fill(0);
  let ratio = 0;
  for (let n = nMax + 20; n >= 1; n--) {
    ratio = 1 / ((2 * n + 1) / x - ratio);
    if (n <= nMax) ratios[n] = ratio;
  }
  for (let n = 1; n <= nMax; n++) psi[n] = ratios[n]! * psi[n - 1]!;
  return psi;
}

/** χ_n(x) = −x y_n(x) for n = 0…nMax by upward recurrence (the dominant solution: stable). */
export function riccatiBesselChi(x: number, nMax: number): number[] {
  const chi = new Array<number>(nMax + 1);
  chi[0] = Math.cos(x);
  let previous = -Math.sin(x); // χ_{−1}
  for (let n = 1; n <= nMax; n++) {
    const next = ((2 * n - 1) / x) * chi[n - 1]! - previous;
    previous = chi[n - 1]!;
    chi[n] = next;
  }
  return chi;
}

/** The Mie coefficients a_n, b_n (index n − 1) and how they were found. */
export interface MieCoefficients {
  x: number;
  m: RefractiveIndex;
  a: Complex[];
  b: Complex[];
  /** Number of terms summed. */
  terms: number;
  /** True when Wiscombe's small-particle expansion gave a_1, b_1, a_2. */
  smallParticle: boolean;
}

/** Size and index inside the solver's range; throws a RangeError otherwise. */
function checkInput(x: number, m: RefractiveIndex): void {
  if (!(x > 0) || x > MIE_MAX_SIZE)
    throw new RangeError(`size parameter x = ${x} outside (0, ${MIE_MAX_SIZE}]`);
  if (!(m.n > 0) || !(m.kappa >= 0) || !Number.isFinite(m.n) || !Number.isFinite(m.kappa))
    throw new RangeError(`refractive index ${m.n} + ${m.kappa}i needs n > 0, κ ≥ 0`);
}

/**
 * Wiscombe's small-particle expansion (1979, MIEV0 SMALL1): with a_n = x³Â_n in his
 * convention (m = n − iκ),
 *   Â₁ = (2i/3)(m²−1)[1 − x²/10 + (4m²+5)x⁴/1400] / D,
 *   D = m²+2 + (1 − 0.7m²)x² − (8m⁴ − 385m² + 350)x⁴/1400 + (2i/3)(m²−1)x³(1 − x²/10),
 *   B̂₁ = (i x²/45)(m²−1)[1 + (2m²−5)x²/70] / [1 − (2m²−5)x²/30],
 *   Â₂ = (i x²/15)(m²−1)(1 − x²/14) / [2m²+3 − (2m²−7)x²/14],
 * evaluated at conj(m) and conjugated back to BH's convention; b_2 = O(x⁷) is dropped.
 */
export function mieSmallParticleCoefficients(x: number, m: RefractiveIndex): MieCoefficients {
  const mW: Complex = [m.n, -m.kappa];
  const m2 = complexMul(mW, mW);
  const m4 = complexMul(m2, m2);
  const m2m1 = complexSub(m2, [1, 0]);
  const x2 = x * x;
  const x3 = x2 * x;
  const x4 = x2 * x2;
  const twoThirdsI: Complex = [0, 2 / 3];
  const denominator = complexAdd(
    complexAdd(complexAdd(m2, [2, 0]), complexScale(complexSub([1, 0], complexScale(m2, 0.7)), x2)),
    complexSub(
      complexMul(complexMul(twoThirdsI, m2m1), [x3 * (1 - 0.1 * x2), 0]),
      complexScale(
        complexAdd(complexSub(complexScale(m4, 8), complexScale(m2, 385)), [350, 0]),
        x4 / 1400,
      ),
    ),
  );
  const a1Hat = complexDiv(
    complexMul(
      complexMul(twoThirdsI, m2m1),
      complexAdd(
        [1 - 0.1 * x2, 0],
        complexScale(complexAdd(complexScale(m2, 4), [5, 0]), x4 / 1400),
      ),
    ),
    denominator,
  );
  const twoM2Minus5 = complexSub(complexScale(m2, 2), [5, 0]);
  const b1Hat = complexDiv(
    complexMul(
      complexMul([0, x2 / 45], m2m1),
      complexAdd([1, 0], complexScale(twoM2Minus5, x2 / 70)),
    ),
    complexSub([1, 0], complexScale(twoM2Minus5, x2 / 30)),
  );
  const a2Hat = complexDiv(
    complexScale(complexMul([0, x2 / 15], m2m1), 1 - x2 / 14),
    complexSub(
      complexAdd(complexScale(m2, 2), [3, 0]),
      complexScale(complexSub(complexScale(m2, 2), [7, 0]), x2 / 14),
    ),
  );
  const toBh = (hat: Complex): Complex => complexConj(complexScale(hat, x3));
  return {
    x,
    m,
    a: [toBh(a1Hat), toBh(a2Hat)],
    b: [toBh(b1Hat), [0, 0]],
    terms: 2,
    smallParticle: true,
  };
}

/** True where Wiscombe's small-particle expansion replaces the series (MIEV0's test). */
export function mieUsesSmallParticle(x: number, m: RefractiveIndex): boolean {
  return x <= 0.1 && x * Math.hypot(m.n, m.kappa) <= 0.1;
}

/** a_n and b_n for n = 1…N (BH 4.88 with Wiscombe's recurrences; see the file's header). */
export function mieCoefficients(x: number, m: RefractiveIndex): MieCoefficients {
  checkInput(x, m);
  return mieUsesSmallParticle(x, m)
    ? mieSmallParticleCoefficients(x, m)
    : mieSeriesCoefficients(x, m);
}

/** The full series for any x (the solver uses it where mieUsesSmallParticle is false). */
export function mieSeriesCoefficients(x: number, m: RefractiveIndex): MieCoefficients {
  checkInput(x, m);
  const terms = Math.max(mieTermCount(x), MIE_MIN_TERMS);
  const index: Complex = [m.n, m.kappa];
  const d = mieLogDerivative(complexScale(index, x), terms);
  const psi = riccatiBesselPsi(x, terms);
  const chi = riccatiBesselChi(x, terms);
  const a: Complex[] = [];
  const b: Complex[] = [];
  for (let n = 1; n <= terms; n++) {
    const nOverX = n / x;
    const xiN: Complex = [psi[n]!, -chi[n]!];
    const xiPrevious: Complex = [psi[n - 1]!, -chi[n - 1]!];
    const dOverM = complexAdd(complexDiv(d[n]!, index), [nOverX, 0]);
    const mTimesD = complexAdd(complexMul(index, d[n]!), [nOverX, 0]);
    a.push(
      complexDiv(
        complexSub(complexScale(dOverM, psi[n]!), [psi[n - 1]!, 0]),
        complexSub(complexMul(dOverM, xiN), xiPrevious),
      ),
    );
    b.push(
      complexDiv(
        complexSub(complexScale(mTimesD, psi[n]!), [psi[n - 1]!, 0]),
        complexSub(complexMul(mTimesD, xiN), xiPrevious),
      ),
    );
  }
  return { x, m, a, b, terms, smallParticle: false };
}

/** Efficiencies and asymmetry of one sphere. */
export interface MieEfficiencies {
  qExt: number;
  qSca: number;
  /** Q_ext − Q_sca. */
  qAbs: number;
  qBack: number;
  /** Asymmetry parameter ⟨μ⟩. */
  g: number;
  /** Single-scattering albedo Q_sca/Q_ext. */
  albedo: number;
  terms: number;
}

/** Q_ext, Q_sca, Q_abs, Q_back and g from the coefficients (BH 4.61, 4.62, 4.80, 4.82). */
export function mieEfficienciesFromCoefficients(c: MieCoefficients): MieEfficiencies {
  const { a, b, x, terms } = c;
  let extinction = 0;
  let scattering = 0;
  let asymmetry = 0;
  let back: Complex = [0, 0];
  for (let n = 1; n <= a.length; n++) {
    const an = a[n - 1]!;
    const bn = b[n - 1]!;
    extinction += (2 * n + 1) * (an[0] + bn[0]);
    scattering += (2 * n + 1) * (complexAbs2(an) + complexAbs2(bn));
    const sign = n % 2 === 0 ? 1 : -1;
    back = complexAdd(back, complexScale(complexSub(an, bn), (2 * n + 1) * sign));
    asymmetry += ((2 * n + 1) / (n * (n + 1))) * (an[0] * bn[0] + an[1] * bn[1]);
    if (n < a.length) {
      const aNext = a[n]!;
      const bNext = b[n]!;
      asymmetry +=
        ((n * (n + 2)) / (n + 1)) *
        (an[0] * aNext[0] + an[1] * aNext[1] + bn[0] * bNext[0] + bn[1] * bNext[1]);
    }
  }
  const x2 = x * x;
  const qSca = (2 / x2) * scattering;
  // Wiscombe's small-particle Â's are not energy-conserving to rounding, so for κ = 0 he
  // sets Q_ext = Q_sca there (MIEV0 SMALL1); likewise an absorption below the expansion's
  // error (κ ≈ 1e-300) is reported as none rather than as Q_ext < Q_sca. The full series
  // is left to show energy conservation by itself (tests/reference/mie.test.ts).
  const seriesExtinction = (2 / x2) * extinction;
  const qExt = c.smallParticle ? Math.max(seriesExtinction, qSca) : seriesExtinction;
  const g = qSca > 0 ? (4 / (x2 * qSca)) * asymmetry : 0;
  return {
    qExt,
    qSca,
    qAbs: qExt - qSca,
    qBack: complexAbs2(back) / x2,
    g,
    albedo: qExt > 0 ? qSca / qExt : 0,
    terms,
  };
}

/** Efficiencies of a sphere of size parameter x and index m. */
export function mieEfficiencies(x: number, m: RefractiveIndex): MieEfficiencies {
  return mieEfficienciesFromCoefficients(mieCoefficients(x, m));
}

/** The amplitude functions at one angle. */
export interface MieAmplitudes {
  s1: Complex;
  s2: Complex;
}

/**
 * S1(μ), S2(μ) (BH 4.74) with the angular functions by their upward recurrences (BH 4.47):
 * π_n = ((2n−1)/(n−1)) μ π_{n−1} − (n/(n−1)) π_{n−2}, τ_n = nμπ_n − (n+1)π_{n−1}.
 */
export function mieAmplitudes(c: MieCoefficients, mu: number): MieAmplitudes {
  // Real and imaginary parts summed separately: for x = 10⁴ a table of 513 angles runs
  // this loop five million times, and pairs allocated per term would dominate.
  let s1Re = 0;
  let s1Im = 0;
  let s2Re = 0;
  let s2Im = 0;
  let piPrevious = 0; // π_0
  let piN = 1; // π_1
  for (let n = 1; n <= c.a.length; n++) {
    const tauN = n * mu * piN - (n + 1) * piPrevious;
    const weight = (2 * n + 1) / (n * (n + 1));
    const an = c.a[n - 1]!;
    const bn = c.b[n - 1]!;
    s1Re += weight * (an[0] * piN + bn[0] * tauN);
    s1Im += weight * (an[1] * piN + bn[1] * tauN);
    s2Re += weight * (an[0] * tauN + bn[0] * piN);
    s2Im += weight * (an[1] * tauN + bn[1] * piN);
    const piNext = ((2 * n + 1) / n) * mu * piN - ((n + 1) / n) * piPrevious;
    piPrevious = piN;
    piN = piNext;
  }
  return { s1: [s1Re, s1Im], s2: [s2Re, s2Im] };
}

/** p(μ) = (|S1|² + |S2|²)/(2π x² Q_sca) in 1/sr (header), for several μ at once. */
export function miePhaseValues(c: MieCoefficients, qSca: number, mus: readonly number[]): number[] {
  const scale = 1 / (2 * Math.PI * c.x * c.x * qSca);
  return mus.map((mu) => {
    const { s1, s2 } = mieAmplitudes(c, mu);
    return (complexAbs2(s1) + complexAbs2(s2)) * scale;
  });
}

/** p(μ) of one sphere at one angle (1/sr). */
export function miePhase(x: number, m: RefractiveIndex, mu: number): number {
  const c = mieCoefficients(x, m);
  return miePhaseValues(c, mieEfficienciesFromCoefficients(c).qSca, [mu])[0]!;
}

// ---------------------------------------------------------------------------
// The tabulated phase function (twins of shaders/mie.wesl)
// ---------------------------------------------------------------------------

/** Intervals of a phase table; it has PHASE_TABLE_INTERVALS + 1 nodes. */
export const PHASE_TABLE_INTERVALS = 512;
export const PHASE_TABLE_NODES = PHASE_TABLE_INTERVALS + 1;

/**
 * A phase function tabulated at nodes θ_k (k = 0…K, θ_0 = 0, θ_K = π), linear in μ between
 * them. Each node stores both complements of μ (1 − μ_k = 2 sin²(θ_k/2), 1 + μ_k =
 * 2 cos²(θ_k/2), each without cancellation), the density p_k (1/sr) and the CDF in 1 − μ
 * from the forward direction, C_k = 2π ∫_0^{1−μ_k} p d(1−μ), with C_K = 1: the table is a
 * normalised density by itself, so sampling's pdf equals its evaluation exactly.
 */
export interface PhaseTable {
  oneMinusMu: Float64Array;
  onePlusMu: Float64Array;
  pdf: Float64Array;
  cdf: Float64Array;
}

/** A sampled cosine with both complements (as hgSampleMu). */
export interface TabulatedMuSample {
  mu: number;
  oneMinusMu: number;
  onePlusMu: number;
}

/**
 * The default nodes θ_k = π(k/K)²: dense at the forward peak, whose width is ≈ 1/x rad
 * (θ_1 = 1.2e-5 rad, so even x = 10⁴'s diffraction peak, first zero at 3.83/x, spans
 * five intervals), and 0.7° apart at the back.
 */
export function phaseTableAngles(intervals = PHASE_TABLE_INTERVALS): Float64Array {
  const angles = new Float64Array(intervals + 1);
  for (let k = 0; k <= intervals; k++) angles[k] = Math.PI * (k / intervals) ** 2;
  return angles;
}

/**
 * Builds the table of a density p(θ) given at the nodes `angles` (increasing from 0 to π):
 * the piecewise-linear-in-μ interpolant is integrated exactly (trapezoids in 1 − μ) and
 * scaled to ∫ p dω = 1; `normalization` reports the factor's inverse (≈ 1 when the nodes
 * resolve p, a measure of the tabulation error).
 */
export function phaseTableFromValues(
  angles: Float64Array,
  values: readonly number[] | Float64Array,
): PhaseTable & { normalization: number } {
  const count = angles.length;
  const oneMinusMu = new Float64Array(count);
  const onePlusMu = new Float64Array(count);
  for (let k = 0; k < count; k++) {
    const half = angles[k]! / 2;
    oneMinusMu[k] = 2 * Math.sin(half) ** 2;
    onePlusMu[k] = 2 * Math.cos(half) ** 2;
  }
  oneMinusMu[0] = 0;
  onePlusMu[count - 1] = 0;
  const cdf = new Float64Array(count);
  for (let k = 1; k < count; k++) {
    const width = oneMinusMu[k]! - oneMinusMu[k - 1]!;
    cdf[k] = cdf[k - 1]! + Math.PI * (values[k - 1]! + values[k]!) * width;
  }
  const total = cdf[count - 1]!;
  const pdf = new Float64Array(count);
  for (let k = 0; k < count; k++) {
    pdf[k] = values[k]! / total;
    cdf[k] = cdf[k]! / total;
  }
  cdf[count - 1] = 1;
  return { oneMinusMu, onePlusMu, pdf, cdf, normalization: total };
}

/**
 * Sub-angles per node for mieTabulatePhase: enough to sample the lobe's ripples, whose
 * period is ≈ π/x in θ, four times per period across the node's cell, at most
 * MIE_TABLE_MAX_SUBSAMPLES.
 */
export const MIE_TABLE_MAX_SUBSAMPLES = 16;

/**
 * The Mie phase function of (x, m) tabulated at `angles` (see PhaseTable). Each node holds
 * the average of p over its cell (from midway to the previous node to midway to the next,
 * weighted by sin θ), not the point value: where the nodes are farther apart than the
 * ripples (x ≳ 100 at the back of the default grid), point values alias them and the
 * table's ∫p dω and mean cosine drift by up to 1% (x = 500), while cell averages keep the
 * ripples' mean, as a polydisperse cloud, which washes them out anyway, would.
 */
export function mieTabulatePhase(
  x: number,
  m: RefractiveIndex,
  angles: Float64Array = phaseTableAngles(),
): PhaseTable & { normalization: number } {
  const c = mieCoefficients(x, m);
  const { qSca } = mieEfficienciesFromCoefficients(c);
  const last = angles.length - 1;
  const values = Array.from(angles, (theta, k) => {
    const lower = k === 0 ? 0 : (angles[k - 1]! + theta) / 2;
    const upper = k === last ? Math.PI : (theta + angles[k + 1]!) / 2;
    const count = Math.min(
      MIE_TABLE_MAX_SUBSAMPLES,
      Math.max(1, Math.ceil((4 * x * (upper - lower)) / Math.PI)),
    );
    if (count === 1) return miePhaseValues(c, qSca, [Math.cos(theta)])[0]!;
    // Midpoint rule in θ over the cell, weighted by sin θ.
    const subAngles = Array.from(
      { length: count },
      (_, j) => lower + ((j + 0.5) * (upper - lower)) / count,
    );
    const subValues = miePhaseValues(c, qSca, subAngles.map(Math.cos));
    let weighted = 0;
    let weights = 0;
    subAngles.forEach((angle, j) => {
      const w = Math.sin(angle);
      weighted += w * subValues[j]!;
      weights += w;
    });
    return weights > 0 ? weighted / weights : subValues[0]!;
  });
  return phaseTableFromValues(angles, values);
}

/** Rounds every entry to f32, as the table the GPU reads (and the shader tests pass). */
export function phaseTableToF32(table: PhaseTable): PhaseTable {
  return {
    oneMinusMu: Float64Array.from(Float32Array.from(table.oneMinusMu)),
    onePlusMu: Float64Array.from(Float32Array.from(table.onePlusMu)),
    pdf: Float64Array.from(Float32Array.from(table.pdf)),
    cdf: Float64Array.from(Float32Array.from(table.cdf)),
  };
}

const clamp = (v: number, lo: number, hi: number): number => Math.min(Math.max(v, lo), hi);

/** Largest k < K with `values[k] ≤ v` (bisection; values non-decreasing). */
function bisect(values: Float64Array, v: number): number {
  let lo = 0;
  let hi = values.length - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (values[mid]! <= v) lo = mid;
    else hi = mid;
  }
  return lo;
}

/** The interval k whose nodes bracket 1 − μ: the largest k < K with 1 − μ_k ≤ oneMinusMu. */
export function phaseTableInterval(table: PhaseTable, oneMinusMu: number): number {
  return bisect(table.oneMinusMu, oneMinusMu);
}

/** The interval k whose CDF values bracket ξ: the largest k < K with C_k ≤ ξ. */
export function phaseTableCdfInterval(table: PhaseTable, xi: number): number {
  return bisect(table.cdf, xi);
}

/**
 * p at the complements of μ: linear in μ inside the interval, with the weight taken from
 * whichever complement is the smaller (exact near the forward and the backward end).
 */
export function phaseTabulatedEvalTerms(
  table: PhaseTable,
  oneMinusMu: number,
  onePlusMu: number,
): number {
  const t = clamp(oneMinusMu, 0, 2);
  const k = phaseTableInterval(table, t);
  const lowerT = table.oneMinusMu[k]!;
  const upperT = table.oneMinusMu[k + 1]!;
  let w: number;
  if (t <= 1) {
    w = upperT > lowerT ? (t - lowerT) / (upperT - lowerT) : 0;
  } else {
    const lowerC = table.onePlusMu[k]!;
    const upperC = table.onePlusMu[k + 1]!;
    w = lowerC > upperC ? (lowerC - clamp(onePlusMu, 0, 2)) / (lowerC - upperC) : 0;
  }
  w = clamp(w, 0, 1);
  return table.pdf[k]! + w * (table.pdf[k + 1]! - table.pdf[k]!);
}

/** p(μ) of the table in 1/sr, μ clamped to [−1, 1]. */
export function phaseTabulatedEval(table: PhaseTable, mu: number): number {
  const m = clamp(mu, -1, 1);
  return phaseTabulatedEvalTerms(table, 1 - m, 1 + m);
}

/**
 * p for the directions (wo, wi), μ = −wo·wi, with 1 − μ = |wo + wi|²/2 and 1 + μ = |wi − wo|²/2
 * taken from the directions (no cancellation near either end), in 1/sr.
 */
export function phaseTabulatedEvalDirections(table: PhaseTable, wo: Vec3, wi: Vec3): number {
  let oneMinusMu = 0;
  let onePlusMu = 0;
  for (let c = 0; c < 3; c++) {
    oneMinusMu += (wo[c]! + wi[c]!) ** 2 / 2;
    onePlusMu += (wi[c]! - wo[c]!) ** 2 / 2;
  }
  return phaseTabulatedEvalTerms(table, oneMinusMu, onePlusMu);
}

/**
 * Inverse CDF of the table: the interval k with C_k ≤ ξ < C_{k+1} by bisection, then inside
 * it the exact inverse of the linear density's quadratic CDF. With p_k = a, p_{k+1} = b and
 * r = (ξ − C_k)/(C_{k+1} − C_k), the fraction s of the interval solves as + (b − a)s²/2 =
 * r(a + b)/2, taken in the form s = r(a + b)/(a + √(a² + (b − a)(a + b)r)) that never
 * subtracts (a, b ≥ 0; the radicand ≥ b² ≥ 0 for r ≤ 1). Both complements are
 * interpolated from their node values, and μ comes from the smaller.
 */
export function phaseTabulatedSampleMu(table: PhaseTable, xi: number): TabulatedMuSample {
  const u = clamp(xi, 0, 1);
  const lo = phaseTableCdfInterval(table, u);
  const mass = table.cdf[lo + 1]! - table.cdf[lo]!;
  const r = mass > 0 ? clamp((u - table.cdf[lo]!) / mass, 0, 1) : 0;
  const a = table.pdf[lo]!;
  const b = table.pdf[lo + 1]!;
  const denominator = a + Math.sqrt(Math.max(0, a * a + (b - a) * (a + b) * r));
  const s = denominator > 0 ? clamp((r * (a + b)) / denominator, 0, 1) : r;
  const oneMinusMu =
    table.oneMinusMu[lo]! + s * (table.oneMinusMu[lo + 1]! - table.oneMinusMu[lo]!);
  const onePlusMu = table.onePlusMu[lo]! - s * (table.onePlusMu[lo]! - table.onePlusMu[lo + 1]!);
  const mu = oneMinusMu < onePlusMu ? 1 - oneMinusMu : onePlusMu - 1;
  return { mu, oneMinusMu, onePlusMu };
}

/** A tabulated-phase sample around the direction of travel −wo; pdf = the table at it. */
export function phaseTabulatedSample(
  table: PhaseTable,
  wo: Vec3,
  u: readonly [number, number],
): { wi: Vec3; pdf: number } {
  const { mu, oneMinusMu, onePlusMu } = phaseTabulatedSampleMu(table, u[0]);
  const sinTheta = Math.sqrt(Math.max(0, oneMinusMu * onePlusMu));
  return {
    wi: directionAroundAxis([-wo[0], -wo[1], -wo[2]], mu, sinTheta, u[1]),
    pdf: phaseTabulatedEvalTerms(table, oneMinusMu, onePlusMu),
  };
}
