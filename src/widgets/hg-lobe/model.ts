// What the hg-lobe widget computes, independent of the backend: its inputs, the
// closed-form bin probabilities of the HG cosine (physics.md §2.4), the chi-square
// test of a histogram against them, the normalisation integral of the float64
// twin, and the layout of the polar picture shared by the WGSL and 2D-canvas paths.
import { hgEval, phaseIsotropic, rayleighEval } from '../../reference/phase.ts';
import { chiSquareCritical, chiSquareSurvival, logGamma } from '../../statistics/distributions.ts';
import type { ParameterValues } from '../parameters.ts';

/** Equal-width bins of μ ∈ [−1, 1]; the kernel's histogram has the same count. */
export const BIN_COUNT = 64;
/** Threads per workgroup of the sampling kernel; one f32 partial sum each. */
export const WORKGROUP_SIZE = 256;
/** Largest N the CPU twin replays beside the GPU for the cost line (2^16). */
export const CPU_TIMING_CAP = 65536;

export type CompareLobe = 'none' | 'isotropic' | 'rayleigh';
export type RadiusScale = 'linear' | 'log';

export interface HgLobeInputs {
  /** Asymmetry as the GPU sees it: f32-rounded, so the twin replays the same number. */
  g: number;
  compare: CompareLobe;
  scale: RadiusScale;
  /** n of N = 2^n. */
  samplesExponent: number;
  sampleCount: number;
  seed: number;
}

export interface HgHistogram {
  /** Counts of μ in the 64 bins [−1 + kΔμ, −1 + (k+1)Δμ), Δμ = 1/32. */
  bins: Uint32Array;
  sampleCount: number;
  /** Σμ and Σμ² over the samples, reduced in float64. */
  sumMu: number;
  sumMuSquared: number;
  milliseconds: number;
  timing: 'gpu-timestamp' | 'gpu-wall' | 'cpu';
}

export function inputsFrom(values: ParameterValues): HgLobeInputs {
  const samplesExponent = Math.round(Number(values['samples']));
  return {
    g: Math.fround(Number(values['g'])),
    compare: values['compare'] as CompareLobe,
    scale: values['scale'] as RadiusScale,
    samplesExponent,
    sampleCount: 2 ** samplesExponent,
    seed: Math.round(Number(values['seed'])),
  };
}

/** Bin of a sample from 1 + μ (exact scaling by 32, a power of two), as the kernel does. */
export function binOf(onePlusMu: number): number {
  return Math.min(Math.floor(onePlusMu * (BIN_COUNT / 2)), BIN_COUNT - 1);
}

/** Lower edge of bin k in μ. */
export function binEdge(k: number): number {
  return -1 + (2 * k) / BIN_COUNT;
}

/**
 * Closed-form CDF of the HG cosine (physics.md §2.4),
 * F(μ) = (1 − g²)/(2g)·[(1 + g² − 2gμ)^{−1/2} − 1/(1 + g)].
 * With s = √(1 + g² − 2gμ), the bracket is (1 + g − s)/(s(1 + g)) and
 * 1 + g − s = ((1 + g)² − s²)/(1 + g + s) = 2g(1 + μ)/(1 + g + s), so the 1/(2g)
 * cancels exactly: F(μ) = (1 − g)(1 + μ)/(s(1 + g + s)). That form has no 0/0 at
 * g → 0 (it gives (1 + μ)/2, the isotropic CDF) and no cancellation anywhere; s² is
 * taken in the robust form of §2.5.
 */
export function hgCdf(g: number, mu: number): number {
  const m = Math.min(Math.max(mu, -1), 1);
  const sSquared = g >= 0 ? (1 - g) ** 2 + 2 * g * (1 - m) : (1 + g) ** 2 - 2 * g * (1 + m);
  const s = Math.sqrt(sSquared);
  return ((1 - g) * (1 + m)) / (s * (1 + g + s));
}

/** Probability of each μ bin under HG with asymmetry g: F(upper edge) − F(lower edge). */
export function hgBinProbabilities(g: number): Float64Array {
  const edges = Array.from({ length: BIN_COUNT + 1 }, (_, k) => hgCdf(g, binEdge(k)));
  return Float64Array.from({ length: BIN_COUNT }, (_, k) => edges[k + 1]! - edges[k]!);
}

/** Smallest expected count a cell may have; sparser cells are pooled (as pbrt-v4's chi2test does). */
export const MIN_EXPECTED = 5;
/** Significance of the widget's test (one test per frame). */
export const ALPHA = 0.01;

export interface ChiSquareResult {
  statistic: number;
  /** Degrees of freedom: cells after pooling, minus one. */
  df: number;
  pValue: number;
  /** Critical value at ALPHA for df (92.01 for the unpooled 64 bins, df = 63). */
  critical: number;
  passes: boolean;
  /** Number of bins pooled into one cell because their expected count was below MIN_EXPECTED. */
  pooled: number;
}

/**
 * Pearson's χ² = Σ (O − E)²/E of observed counts against bin probabilities, with
 * E = N·P. Bins whose E < 5 are pooled into one cell, because the χ² distribution
 * of the statistic only holds where every E is large enough; df = cells − 1.
 */
export function chiSquareTest(
  counts: ArrayLike<number>,
  probabilities: ArrayLike<number>,
  sampleCount: number,
  alpha = ALPHA,
): ChiSquareResult {
  let statistic = 0;
  let cells = 0;
  let pooledObserved = 0;
  let pooledExpected = 0;
  let pooled = 0;
  for (let k = 0; k < probabilities.length; k++) {
    const expected = sampleCount * (probabilities[k] ?? 0);
    const observed = counts[k] ?? 0;
    if (expected < MIN_EXPECTED) {
      pooledObserved += observed;
      pooledExpected += expected;
      pooled += 1;
      continue;
    }
    statistic += (observed - expected) ** 2 / expected;
    cells += 1;
  }
  if (pooled > 0 && pooledExpected > 0) {
    statistic += (pooledObserved - pooledExpected) ** 2 / pooledExpected;
    cells += 1;
  }
  const df = Math.max(cells - 1, 1);
  const pValue = chiSquareSurvival(statistic, df);
  return {
    statistic,
    df,
    pValue,
    critical: chiSquareCritical(alpha, df),
    passes: pValue > alpha,
    pooled,
  };
}

export interface MeanCosine {
  mean: number;
  /** Standard error √(s²/N) from the unbiased sample variance s². */
  standardError: number;
  /** (mean − g)/SE. */
  zScore: number;
}

export function meanCosine(histogram: HgHistogram, g: number): MeanCosine {
  const n = histogram.sampleCount;
  const mean = histogram.sumMu / n;
  const variance = Math.max(histogram.sumMuSquared - n * mean * mean, 0) / (n - 1);
  const standardError = Math.sqrt(variance / n);
  return { mean, standardError, zScore: standardError > 0 ? (mean - g) / standardError : 0 };
}

/**
 * Gauss–Legendre nodes and weights on [−1, 1]: the roots of P_n by Newton's method
 * from the Chebyshev guess cos(π(i + 3/4)/(n + 1/2)), and w = 2/((1 − x²)P_n'(x)²)
 * (Numerical Recipes §4.6). Computed rather than typed, so no digit can be wrong.
 */
function gaussLegendre(n: number): { nodes: number[]; weights: number[] } {
  const nodes: number[] = [];
  const weights: number[] = [];
  for (let i = 0; i < n; i++) {
    let x = Math.cos((Math.PI * (i + 0.75)) / (n + 0.5));
    let derivative = 1;
    for (let iteration = 0; iteration < 100; iteration++) {
      let p0 = 1;
      let p1 = x;
      for (let k = 2; k <= n; k++) [p0, p1] = [p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k];
      derivative = (n * (x * p1 - p0)) / (x * x - 1);
      const dx = p1 / derivative;
      x -= dx;
      if (Math.abs(dx) < 1e-16) break;
    }
    nodes.push(x);
    weights.push(2 / ((1 - x * x) * derivative * derivative));
  }
  return { nodes, weights };
}

const GAUSS_LEGENDRE_16 = gaussLegendre(16);

/**
 * ∫_{4π} p dω = 2π ∫_{−1}^{1} p(μ) dμ for the float64 twin hgEval, by 16-point
 * Gauss–Legendre on panels that shrink geometrically (factor 4) toward both ends,
 * where an HG lobe with |g| → 1 has a peak of width ~(1 − |g|)². Independent of
 * the CDF, so it checks the normalisation rather than restating it.
 */
export function sphereIntegral(p: (mu: number) => number): number {
  const breaks = [0];
  for (let k = 1; k <= 14; k++) breaks.push(1 - 4 ** -k);
  breaks.push(1);
  const edges = [...breaks.map((b) => -b).reverse(), ...breaks.slice(1)];
  let sum = 0;
  for (let i = 0; i + 1 < edges.length; i++) {
    const a = edges[i]!;
    const b = edges[i + 1]!;
    const half = 0.5 * (b - a);
    const mid = 0.5 * (a + b);
    const { nodes, weights } = GAUSS_LEGENDRE_16;
    for (let j = 0; j < nodes.length; j++) sum += weights[j]! * half * p(mid + half * nodes[j]!);
  }
  return 2 * Math.PI * sum;
}

/** The comparison phase function, or null. */
export function comparePhase(compare: CompareLobe): ((mu: number) => number) | null {
  if (compare === 'isotropic') return () => phaseIsotropic();
  if (compare === 'rayleigh') return rayleighEval;
  return null;
}

/**
 * Where the polar picture puts things: the scattering point at the centre, the
 * forward direction (θ = 0) to the right. Radius in pixels is k·p (linear) or
 * k·(log₁₀ p − logFloor), clamped at 0 (log). k is chosen so that the lobe and the
 * comparison lobe fit; ring values are the labelled circles.
 */
export interface PolarLayout {
  width: number;
  height: number;
  centreX: number;
  centreY: number;
  /** Pixels per sr⁻¹ (linear) or per decade (log). */
  pixelsPerUnit: number;
  /** log₁₀ of the value at radius 0 (log scale only). */
  logFloor: number;
  /** Distance between rings in the scale's units (sr⁻¹ or decades). */
  ringStep: number;
  /** Ring values in sr⁻¹ with their radius in pixels, for the labels. */
  rings: { value: number; radius: number }[];
}

export function radiusFor(p: number, scale: RadiusScale, layout: PolarLayout): number {
  if (scale === 'linear') return layout.pixelsPerUnit * p;
  return layout.pixelsPerUnit * Math.max(0, Math.log10(Math.max(p, 1e-30)) - layout.logFloor);
}

/** A "nice" step (1, 2 or 5 × 10^k) near x. */
function niceStep(x: number): number {
  const power = 10 ** Math.floor(Math.log10(x));
  const m = x / power;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * power;
}

export function polarLayout(inputs: HgLobeInputs, width: number, height: number): PolarLayout {
  const other = comparePhase(inputs.compare);
  const lobes = [(mu: number) => hgEval(inputs.g, mu), ...(other ? [other] : [])];
  const angles = Array.from({ length: 721 }, (_, i) => (Math.PI * i) / 720);
  let pMin = Infinity;
  let pMax = 0;
  for (const p of lobes)
    for (const theta of angles) {
      const value = p(Math.cos(theta));
      pMin = Math.min(pMin, value);
      pMax = Math.max(pMax, value);
    }
  const top = Math.ceil(Math.log10(pMax) + 1e-9);
  const logFloor = Math.max(Math.floor(Math.log10(pMin) - 1e-9), top - 7);
  const base: PolarLayout = {
    width,
    height,
    centreX: width / 2,
    centreY: height / 2,
    pixelsPerUnit: 1,
    logFloor,
    ringStep: 1,
    rings: [],
  };
  // Extents of both lobes at k = 1, then the k that fits them with a margin for labels.
  let extentX = 0;
  let extentY = 0;
  for (const p of lobes)
    for (const theta of angles) {
      const r = radiusFor(p(Math.cos(theta)), inputs.scale, base);
      extentX = Math.max(extentX, Math.abs(r * Math.cos(theta)));
      extentY = Math.max(extentY, r * Math.sin(theta));
    }
  const pixelsPerUnit = Math.min(
    (0.45 * width) / Math.max(extentX, 1e-12),
    (0.42 * height) / Math.max(extentY, 1e-12),
  );
  const layout = { ...base, pixelsPerUnit };
  const visible = Math.hypot(width / 2, height / 2) / pixelsPerUnit;
  if (inputs.scale === 'linear') {
    layout.ringStep = niceStep(pMax / 3);
    for (let j = 1; j * layout.ringStep <= visible && j <= 40; j++) {
      const value = j * layout.ringStep;
      layout.rings.push({ value, radius: pixelsPerUnit * value });
    }
  } else {
    layout.ringStep = 1;
    for (let j = 1; j <= visible && j <= 12; j++) {
      layout.rings.push({ value: 10 ** (logFloor + j), radius: pixelsPerUnit * j });
    }
  }
  return layout;
}

/** The error-versus-time sweep: N = 2^n for n = 10 … 20, the range of the samples slider. */
export const SWEEP_EXPONENTS = [10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20] as const;
/** Repetitions per point: the time is their median, the error their mean (seeds s, s + 1, …). */
export const SWEEP_REPETITIONS = 3;

/**
 * L1 distance between the histogram's bin frequencies and the analytic bin
 * probabilities, Σ_k |O_k/N − P_k| (twice the total-variation distance): the
 * sampler's error as a density estimate on the 64 bins.
 */
export function histogramL1(
  counts: ArrayLike<number>,
  probabilities: ArrayLike<number>,
  sampleCount: number,
): number {
  let sum = 0;
  for (let k = 0; k < probabilities.length; k++)
    sum += Math.abs((counts[k] ?? 0) / sampleCount - (probabilities[k] ?? 0));
  return sum;
}

/** ln C(n, k) through ln Γ. */
function logBinomial(n: number, k: number): number {
  return logGamma(n + 1) - logGamma(k + 1) - logGamma(n - k + 1);
}

/**
 * E|X − Np| for X ~ Binomial(N, p), exactly, by de Moivre's formula
 * E|X − Np| = 2ν·C(N, ν)·p^ν·(1 − p)^{N−ν+1} with ν = ⌊Np⌋ + 1
 * (Diaconis and Zabell 1991, "Closed form summation for classical distributions").
 * Evaluated in logarithms, so N up to 2^20 neither overflows nor underflows early.
 */
export function binomialMeanAbsoluteDeviation(sampleCount: number, p: number): number {
  if (p <= 0 || p >= 1) return 0;
  const nu = Math.floor(sampleCount * p) + 1;
  if (nu > sampleCount) return 0;
  return Math.exp(
    Math.log(2 * nu) +
      logBinomial(sampleCount, nu) +
      nu * Math.log(p) +
      (sampleCount - nu + 1) * Math.log1p(-p),
  );
}

/**
 * The expected L1 error of a histogram of N independent samples: each count O_k is
 * Binomial(N, P_k), so E Σ|O_k/N − P_k| = Σ E|O_k − N·P_k|/N, exactly. When every
 * N·P_k is large this is ≈ √(2/(πN))·Σ√(P_k(1 − P_k)), the N^{−1/2} law of Monte Carlo.
 */
export function expectedHistogramL1(probabilities: ArrayLike<number>, sampleCount: number): number {
  let sum = 0;
  for (let k = 0; k < probabilities.length; k++)
    sum += binomialMeanAbsoluteDeviation(sampleCount, probabilities[k] ?? 0);
  return sum / sampleCount;
}

/** The median of a non-empty list. */
export function median(values: readonly number[]): number {
  const sorted = [...values].sort((a, b) => a - b);
  const middle = Math.floor(sorted.length / 2);
  return sorted.length % 2 === 1 ? sorted[middle]! : 0.5 * (sorted[middle - 1]! + sorted[middle]!);
}
