// The phase functions against the analytic facts of physics.md §2: published
// values, normalisation and mean cosine by quadrature, reciprocity, the sampled
// density against the ANALYTIC density (chi-square on the float64 twin and on
// samples drawn on the GPU), ⟨μ⟩ = g and the median g(3 − g²)/2, and fast-check
// properties for all g ∈ (−1, 1) and ξ ∈ [0, 1). Direction convention: the one at
// the top of shaders/phase.wesl (wo, wi both point away; μ = −wo·wi).
import fc from 'fast-check';
import { beforeAll, describe, expect, it } from 'vitest';
import {
  cbrtReal,
  HG_MAX_ABS_G,
  hgEval,
  hgEvalDirections,
  hgEvalTerms,
  hgSample,
  hgSampleMu,
  phaseIsotropic,
  rayleighEval,
  rayleighSample,
  rayleighSampleMu,
  type Vec3,
} from '../../src/reference/phase.ts';
import { sampleUniformSphere } from '../../src/reference/directions.ts';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';
import { linkKernel } from '../../src/gpu/link.ts';
import { runCompute } from '../../src/gpu/compute.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';
import { f32ToBits } from '../support/f32.ts';
import { chiSquareSurvival } from '../../src/statistics/distributions.ts';

// ---------------------------------------------------------------------------
// Numerical tools written for this file: Gauss–Legendre quadrature and the
// chi-square tail probability (regularised upper incomplete gamma function).
// ---------------------------------------------------------------------------

/** Nodes and weights of n-point Gauss–Legendre on [−1, 1] (Newton on P_n). */
function gaussLegendre(n: number): { nodes: number[]; weights: number[] } {
  const nodes: number[] = [];
  const weights: number[] = [];
  for (let i = 1; i <= n; i++) {
    let x = Math.cos((Math.PI * (i - 0.25)) / (n + 0.5));
    let derivative = 1;
    for (let iteration = 0; iteration < 100; iteration++) {
      let p0 = 1;
      let p1 = x;
      for (let k = 2; k <= n; k++) [p0, p1] = [p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k];
      derivative = (n * (x * p1 - p0)) / (x * x - 1);
      const step = p1 / derivative;
      x -= step;
      if (Math.abs(step) < 1e-16) break;
    }
    nodes.push(x);
    weights.push(2 / ((1 - x * x) * derivative * derivative));
  }
  return { nodes, weights };
}
const GL = gaussLegendre(24);

/** ∫ f over [a, b] with 24-point Gauss–Legendre. */
function integrate(f: (x: number) => number, a: number, b: number): number {
  const half = (b - a) / 2;
  const mid = (a + b) / 2;
  return GL.nodes.reduce((sum, x, k) => sum + (GL.weights[k] ?? 0) * f(mid + half * x), 0) * half;
}

/**
 * ∫_0^2 f(t) dt split at 2·10^-k, k = 1 … 18: log-spaced pieces, so that a peak of
 * width (1 − |g|)² at t = 0 (t = distance in μ from the HG peak) is resolved.
 */
function integrateFromPeak(f: (t: number) => number, upper = 2): number {
  const breaks = [0];
  for (let k = 18; k >= 1; k--) if (2 * 10 ** -k < upper) breaks.push(2 * 10 ** -k);
  breaks.push(upper);
  let sum = 0;
  for (let i = 0; i + 1 < breaks.length; i++)
    sum += integrate(f, breaks[i] as number, breaks[i + 1] as number);
  return sum;
}

/** HG at distance t from its peak (t = 1 − μ for g ≥ 0, 1 + μ for g < 0). */
const hgFromPeak = (g: number, t: number): number =>
  g >= 0 ? hgEvalTerms(g, t, 2 - t) : hgEvalTerms(g, 2 - t, t);

/** Pearson's statistic of counts against equal expected counts. */
function chiSquareUniform(bins: readonly number[]): number {
  const total = bins.reduce((a, b) => a + b, 0);
  const expected = total / bins.length;
  return bins.reduce((sum, count) => sum + (count - expected) ** 2 / expected, 0);
}

// ---------------------------------------------------------------------------
// Analytic distributions (physics.md §2.4, §2.6): the CDFs the samples are binned by.
// ---------------------------------------------------------------------------

/**
 * HG CDF in μ, F(μ) = (1 − g²)/(2g)·[(1 + g² − 2gμ)^(−1/2) − 1/(1 + g)] (§2.4),
 * from the distance t to the peak so that near-peak samples keep their digits:
 * 1 + g² − 2gμ = (1 − g)² + 2gt for g > 0 (t = 1 − μ) and (1 + g)² − 2gt for
 * g < 0 (t = 1 + μ). g = 0 is the uniform F = (1 + μ)/2.
 */
function hgCdfFromPeak(g: number, t: number): number {
  if (g === 0) return 1 - t / 2;
  const d = g > 0 ? (1 - g) ** 2 + 2 * g * t : (1 + g) ** 2 - 2 * g * t;
  return ((1 - g * g) / (2 * g)) * (1 / Math.sqrt(d) - 1 / (1 + g));
}

/** F(μ) = (μ³ + 3μ + 4)/8 (§2.6). */
const rayleighCdf = (mu: number): number => (mu ** 3 + 3 * mu + 4) / 8;

const BINS = 100;
const binOf = (u: number): number => Math.min(BINS - 1, Math.max(0, Math.floor(u * BINS)));

/** Chi-square tests in this file, for the Bonferroni correction. */
const HG_CHI_G = [0, 0.3, -0.5, 0.9, -0.95, 0.999] as const;
const CHI_SQUARE_TESTS = 2 * (HG_CHI_G.length + 2); // HG, Rayleigh, sphere × twin, GPU
const ALPHA = 0.01 / CHI_SQUARE_TESTS;

/** A unit wo off every axis, rounded to f32 (what the GPU sees). */
const OBLIQUE_WO: Vec3 = [0.3, -0.5, 0.81].map((c) =>
  Math.fround(c / Math.hypot(0.3, 0.5, 0.81)),
) as [number, number, number];

// ---------------------------------------------------------------------------
// Published values (float64, exact decimal inputs)
// ---------------------------------------------------------------------------
describe('published values (physics.md §2.2, §2.4, §2.6)', () => {
  const table: readonly (readonly [number, readonly number[]])[] = [
    [
      0.3,
      [
        0.211123904101494, 0.103131394790625, 0.0636343747723979, 0.0441885069637756,
        0.0329610828888541,
      ],
    ],
    [
      0.5,
      [
        0.477464829275686, 0.0918881492369653, 0.0427057526050306, 0.0257806775110893,
        0.0176838825657661,
      ],
    ],
    [
      0.76,
      [
        2.43153385279285, 0.0454676723086372, 0.0169636263976477, 0.00940499886809252,
        0.0061656098821757,
      ],
    ],
    [
      0.9,
      [
        15.1197195937301, 0.0174173327314225, 0.00620906025796582, 0.00338914227398196,
        0.00220436209268553,
      ],
    ],
    [
      0.99,
      [
        1583.59168376436, 0.00160740243399954, 0.000568345632183467, 0.000309375989072885,
        0.000200948136526723,
      ],
    ],
    [
      0.999,
      [
        159075.365620349, 1.59314038073132e-4, 5.63260606166466e-5, 3.06600316130896e-5,
        1.99142771851027e-5,
      ],
    ],
    [
      0.9999,
      [
        15914698.5344741, 1.59170857989095e-5, 5.62753969477927e-6, 3.06324462087376e-6,
        1.98963574724933e-6,
      ],
    ],
  ];
  const mus = [1, 0.5, 0, -0.5, -1];

  // The published values have 15 digits; a decimal g such as 0.9999 is itself
  // rounded in float64, which moves 1 − g by up to 2^-53/(1 − g) ≈ 5.5e-13
  // relative and p(μ = 1) ∝ (1 − g)^-2 by twice that.
  const TABLE_TOLERANCE = 3e-12;

  it('HG equals the §2.2 table for g and −g (mirror p(−g, −μ) = p(g, μ)) to 3e-12', () => {
    for (const [g, values] of table)
      mus.forEach((mu, k) => {
        const expected = values[k] as number;
        expect(Math.abs(hgEval(g, mu) / expected - 1), `g = ${g}, μ = ${mu}`).toBeLessThan(
          TABLE_TOLERANCE,
        );
        expect(Math.abs(hgEval(-g, -mu) / expected - 1), `g = ${-g}, μ = ${-mu}`).toBeLessThan(
          TABLE_TOLERANCE,
        );
      });
    for (const mu of mus) expect(hgEval(0, mu)).toBeCloseTo(0.0795774715459477, 16);
    // §2.1: 0.079577471545947668, here rounded to the nearest double.
    expect(phaseIsotropic()).toBeCloseTo(0.07957747154594767, 17);
  });

  it('HG at the f32-rounded g = f32(0.999), f32(0.9999) gives the §2.2 f32-g peaks', () => {
    // f32 values are exact in float64: only the 15-digit rounding of the table remains.
    expect(Math.abs(hgEval(Math.fround(0.999), 1) / 159079.462788454 - 1)).toBeLessThan(1e-14);
    expect(Math.abs(hgEval(Math.fround(0.9999), 1) / 15909417.9679941 - 1)).toBeLessThan(1e-14);
  });

  it('the robust form beats the textbook one in float64 (§2.5: 1.3e-10 at g = 0.999, μ = 1)', () => {
    const exact = 159075.365620349;
    const textbook = (1 - 0.999 ** 2) / (4 * Math.PI * (1 + 0.999 ** 2 - 2 * 0.999) ** 1.5);
    expect(Math.abs(textbook / exact - 1)).toBeGreaterThan(1e-11);
    expect(Math.abs(hgEval(0.999, 1) / exact - 1)).toBeLessThan(TABLE_TOLERANCE);
  });

  it('§2.3 conformance vector: wo = (0,0,1), wi = (0,0,−1) is the forward peak (g = 0.5 → 0.477464829275686)', () => {
    expect(hgEvalDirections(0.5, [0, 0, 1], [0, 0, -1])).toBeCloseTo(0.477464829275686, 14);
    // A sign error in the convention would give the backward value instead.
    expect(hgEvalDirections(0.5, [0, 0, 1], [0, 0, 1])).toBeCloseTo(0.0176838825657661, 15);
  });

  it('HG samples μ(ξ) equal the §2.4 table (textbook mapping ξ = 0 → μ = −1)', () => {
    const xis = [0, 0.1, 0.25, 0.5, 0.75, 0.9, 1];
    const samples: readonly (readonly [number, readonly number[]])[] = [
      [
        0.3,
        [
          -1, -0.572818559556787, -0.093598615916955, 0.4365, 0.773062381852552, 0.919055671175858,
          1,
        ],
      ],
      [
        -0.3,
        [
          -1, -0.919055671175858, -0.773062381852552, -0.4365, 0.093598615916955, 0.572818559556787,
          1,
        ],
      ],
      [
        0.9,
        [-1, 0.749744897959184, 0.939256198347107, 0.9855, 0.996016646848989, 0.998776365603029, 1],
      ],
      [
        0.999,
        [
          -1, 0.999950898100824, 0.999992516474534, 0.9999985005, 0.9999996110185,
          0.999999882667332, 1,
        ],
      ],
      [
        1e-7,
        [
          -1, -0.799999945999994, -0.499999887499992, 1.5e-7, 0.500000112499993, 0.800000053999994,
          1,
        ],
      ],
    ];
    for (const [g, values] of samples)
      xis.forEach((xi, k) => {
        const mu = hgSampleMu(g, xi, 1 - xi).mu;
        expect(Math.abs(mu - (values[k] as number)), `g = ${g}, ξ = ${xi}`).toBeLessThan(1e-13);
      });
  });

  it('Rayleigh equals §2.6: p(0) = 0.0596831036594608, p(±1) = 0.119366207318922', () => {
    expect(rayleighEval(0)).toBeCloseTo(0.0596831036594608, 16);
    expect(rayleighEval(1)).toBeCloseTo(0.119366207318922, 15);
    expect(rayleighEval(-1)).toBeCloseTo(0.119366207318922, 15);
  });
});

// ---------------------------------------------------------------------------
// Normalisation, mean cosine, CDF
// ---------------------------------------------------------------------------
describe('normalisation and moments by quadrature (physics.md §2.2)', () => {
  const gs = [0, 0.3, -0.3, 0.76, 0.9, -0.9, 0.99, 0.999, -0.999, 0.9999, HG_MAX_ABS_G];

  it('∫ p_HG dω = 1 for g up to the clamp (log-spaced split near the peak)', () => {
    for (const g of gs) {
      const total = 2 * Math.PI * integrateFromPeak((t) => hgFromPeak(g, t));
      expect(Math.abs(total - 1), `g = ${g}`).toBeLessThan(1e-12);
    }
  });

  it('mean cosine ⟨μ⟩ = ∫ μ p_HG dω = g (a sign error in the convention gives −g)', () => {
    for (const g of gs) {
      // μ = 1 − t on the forward side, t − 1 on the backward side.
      const mean =
        2 * Math.PI * integrateFromPeak((t) => (g >= 0 ? 1 - t : t - 1) * hgFromPeak(g, t));
      expect(Math.abs(mean - g), `g = ${g}`).toBeLessThan(1e-12);
    }
  });

  it('second moment ⟨μ²⟩ = (1 + 2g²)/3 (HG Legendre moments are g^l), the variance the mean tests use', () => {
    for (const g of [0, 0.5, -0.9, 0.999]) {
      const second = 2 * Math.PI * integrateFromPeak((t) => (1 - t) ** 2 * hgFromPeak(g, t));
      expect(Math.abs(second - (1 + 2 * g * g) / 3), `g = ${g}`).toBeLessThan(1e-12);
    }
  });

  it('the §2.4 CDF used for binning equals the integral of the density', () => {
    for (const g of [0.3, -0.5, 0.9, -0.95, 0.999])
      for (const t of [1e-8, 1e-4, 0.01, 0.3, 1, 1.9]) {
        const mass = 2 * Math.PI * integrateFromPeak((s) => hgFromPeak(g, s), t);
        // For g > 0 the mass within t of the peak is 1 − F(μ); for g < 0 it is F(μ).
        const fromCdf = g > 0 ? 1 - hgCdfFromPeak(g, t) : hgCdfFromPeak(g, t);
        expect(Math.abs(mass - fromCdf), `g = ${g}, t = ${t}`).toBeLessThan(1e-12);
      }
  });

  it('Rayleigh: ∫ p dω = 1, ⟨μ⟩ = 0, ⟨μ²⟩ = 2/5, and its CDF is (μ³ + 3μ + 4)/8', () => {
    expect(2 * Math.PI * integrate(rayleighEval, -1, 1)).toBeCloseTo(1, 14);
    expect(2 * Math.PI * integrate((mu) => mu * rayleighEval(mu), -1, 1)).toBeCloseTo(0, 14);
    expect(2 * Math.PI * integrate((mu) => mu * mu * rayleighEval(mu), -1, 1)).toBeCloseTo(0.4, 14);
    for (const mu of [-0.7, 0, 0.2, 0.95])
      expect(2 * Math.PI * integrate(rayleighEval, -1, mu)).toBeCloseTo(rayleighCdf(mu), 14);
  });

  it('isotropic: 4π · 1/(4π) = 1', () => {
    expect(4 * Math.PI * phaseIsotropic()).toBeCloseTo(1, 15);
  });
});

// ---------------------------------------------------------------------------
// Reciprocity and the direction convention
// ---------------------------------------------------------------------------
const unitVector = fc
  .tuple(
    fc.double({ min: -1, max: 1, noNaN: true }),
    fc.double({ min: -1, max: 1, noNaN: true }),
    fc.double({ min: -1, max: 1, noNaN: true }),
  )
  .filter(([x, y, z]) => Math.hypot(x, y, z) > 1e-3)
  .map(([x, y, z]): Vec3 => {
    const n = Math.hypot(x, y, z);
    return [x / n, y / n, z / n];
  });
const anyG = fc.double({ min: -1, max: 1, minExcluded: true, maxExcluded: true, noNaN: true });
const anyXi = fc.double({ min: 0, max: 1, maxExcluded: true, noNaN: true });
const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

describe('reciprocity and convention', () => {
  it('p(wo, wi) = p(wi, wo) exactly, for all g and unit directions', () => {
    fc.assert(
      fc.property(anyG, unitVector, unitVector, (g, wo, wi) => {
        return hgEvalDirections(g, wo, wi) === hgEvalDirections(g, wi, wo);
      }),
    );
  });

  it('p(wo, wi) depends only on μ = −wo·wi: equals hgEval(g, −wo·wi)', () => {
    fc.assert(
      fc.property(anyG, unitVector, unitVector, (g, wo, wi) => {
        const byVectors = hgEvalDirections(g, wo, wi);
        const byCosine = hgEval(g, -dot(wo, wi));
        // Away from the peak (|1 ∓ μ| ≥ 1e-6) the cosine form is as accurate.
        if (Math.min(1 + dot(wo, wi), 1 - dot(wo, wi)) < 1e-6) return true;
        return Math.abs(byVectors / byCosine - 1) < 1e-8;
      }),
    );
  });
});

// ---------------------------------------------------------------------------
// Sampling on the twin: properties for all g and ξ, density by chi-square
// ---------------------------------------------------------------------------
describe('HG and Rayleigh sampling on the float64 twin', () => {
  it('fast-check: μ ∈ [−1, 1], the complements sum to 2, for all g ∈ (−1, 1), ξ ∈ [0, 1)', () => {
    fc.assert(
      fc.property(anyG, anyXi, (g, xi) => {
        const s = hgSampleMu(g, xi, 1 - xi);
        return (
          s.mu >= -1 &&
          s.mu <= 1 &&
          s.oneMinusMu >= 0 &&
          s.onePlusMu >= 0 &&
          Math.abs(s.oneMinusMu + s.onePlusMu - 2) < 1e-14 &&
          // μ comes from the smaller complement; the larger one carries the rounding of its
          // quotient, a few ulps of a number up to 2 (ulp(2) = 4.4e-16): g = −0.0835, ξ = 0
          // gives 1 − μ = 2 − 5 ulps. Eight ulps bound it.
          Math.abs(1 - s.oneMinusMu - s.mu) < 8 * 4.45e-16
        );
      }),
      { numRuns: 2000 },
    );
  });

  it('fast-check: the sample is monotone in ξ (an inverse CDF)', () => {
    fc.assert(
      fc.property(anyG, anyXi, anyXi, (g, a, b) => {
        const [lo, hi] = a < b ? [a, b] : [b, a];
        return hgSampleMu(g, lo, 1 - lo).mu <= hgSampleMu(g, hi, 1 - hi).mu;
      }),
    );
  });

  it('fast-check: F(μ(ξ)) = ξ, the sampler inverts the §2.4 CDF (|g| ≥ 1e-3 where F is well conditioned)', () => {
    const g = anyG.filter((x) => Math.abs(x) >= 1e-3 && Math.abs(x) <= HG_MAX_ABS_G);
    fc.assert(
      fc.property(g, anyXi, (gValue, xi) => {
        const s = hgSampleMu(gValue, xi, 1 - xi);
        const cdf = hgCdfFromPeak(gValue, gValue >= 0 ? s.oneMinusMu : s.onePlusMu);
        return Math.abs(cdf - xi) < 1e-9;
      }),
    );
  });

  it('fast-check: wi is unit length and pdf = p(wo, wi) = hgEval at the sample, for all g, ξ and wo', () => {
    fc.assert(
      fc.property(anyG, anyXi, anyXi, unitVector, (g, u0, u1, wo) => {
        const { wi, pdf } = hgSample(g, wo, [u0, u1]);
        const evaluated = hgEvalDirections(g, wo, wi);
        return (
          Math.abs(Math.hypot(...wi) - 1) < 1e-14 &&
          Math.abs(pdf / evaluated - 1) < 1e-9 &&
          pdf > 0 &&
          Number.isFinite(pdf)
        );
      }),
      { numRuns: 2000 },
    );
  });

  it('fast-check: the median μ(½) = g(3 − g²)/2 (§2.4)', () => {
    fc.assert(
      fc.property(
        anyG.filter((g) => Math.abs(g) <= HG_MAX_ABS_G),
        (g) => {
          return Math.abs(hgSampleMu(g, 0.5, 0.5).mu - (g * (3 - g * g)) / 2) < 2e-15;
        },
      ),
    );
  });

  it('fast-check: Rayleigh μ(ξ) solves F(μ) = ξ and equals Cardano’s ∛(z + √(z²+1)) + ∛(z − √(z²+1))', () => {
    fc.assert(
      fc.property(anyXi, fc.double({ min: -10, max: 10, noNaN: true }), (xi, x) => {
        const mu = rayleighSampleMu(xi);
        const z = 2 * (2 * xi - 1);
        const cardano = cbrtReal(z + Math.sqrt(z * z + 1)) + cbrtReal(z - Math.sqrt(z * z + 1));
        return (
          Math.abs(rayleighCdf(mu) - xi) < 1e-14 &&
          Math.abs(mu - cardano) < 1e-14 &&
          Math.abs(cbrtReal(x) ** 3 - x) <= 1e-14 * (1 + Math.abs(x)) &&
          cbrtReal(-x) === -cbrtReal(x)
        );
      }),
    );
  });

  it('fast-check: Rayleigh wi is unit length and pdf = 3/(16π)(1 + μ²) at μ = −wo·wi', () => {
    fc.assert(
      fc.property(anyXi, anyXi, unitVector, (u0, u1, wo) => {
        const { wi, pdf } = rayleighSample(wo, [u0, u1]);
        return (
          Math.abs(Math.hypot(...wi) - 1) < 1e-14 &&
          Math.abs(pdf - rayleighEval(-dot(wo, wi))) < 1e-14
        );
      }),
    );
  });

  it(`chi-square self-check: P(χ²₆₃ ≥ 92.01) = 0.01 (the critical value tests/reference/rng.test.ts uses)`, () => {
    expect(chiSquareSurvival(92.01, 63)).toBeCloseTo(0.01, 4);
    expect(chiSquareSurvival(0, 99)).toBe(1);
    expect(chiSquareSurvival(99, 99)).toBeGreaterThan(0.4);
  });

  const TWIN_SAMPLES = 100_000;
  for (const g of HG_CHI_G) {
    it(`HG g = ${g}: ${TWIN_SAMPLES} samples match the analytic density (chi-square, ${BINS} equiprobable bins in μ, α = 0.01/${CHI_SQUARE_TESTS})`, () => {
      const bins = new Array<number>(BINS).fill(0);
      for (let i = 0; i < TWIN_SAMPLES; i++) {
        const state = { value: rngSeed(i, 1) };
        const xi = rngNextFloat(state);
        const s = hgSampleMu(g, xi, 1 - xi);
        const bin = binOf(hgCdfFromPeak(g, g >= 0 ? s.oneMinusMu : s.onePlusMu));
        bins[bin] = (bins[bin] ?? 0) + 1;
      }
      expect(chiSquareSurvival(chiSquareUniform(bins), BINS - 1)).toBeGreaterThan(ALPHA);
    });
  }

  it(`Rayleigh: ${TWIN_SAMPLES} directions match the analytic density (chi-square on F(−wo·wi))`, () => {
    const bins = new Array<number>(BINS).fill(0);
    for (let i = 0; i < TWIN_SAMPLES; i++) {
      const state = { value: rngSeed(i, 2) };
      const { wi } = rayleighSample(OBLIQUE_WO, [rngNextFloat(state), rngNextFloat(state)]);
      const bin = binOf(rayleighCdf(-dot(OBLIQUE_WO, wi)));
      bins[bin] = (bins[bin] ?? 0) + 1;
    }
    expect(chiSquareSurvival(chiSquareUniform(bins), BINS - 1)).toBeGreaterThan(ALPHA);
  });

  it(`uniform sphere: ${TWIN_SAMPLES} directions are uniform in (z, φ) (chi-square, 10 × 10 bins)`, () => {
    const bins = new Array<number>(BINS).fill(0);
    for (let i = 0; i < TWIN_SAMPLES; i++) {
      const state = { value: rngSeed(i, 3) };
      const w = sampleUniformSphere([rngNextFloat(state), rngNextFloat(state)]);
      bins[sphereBin(w)] = (bins[sphereBin(w)] ?? 0) + 1;
    }
    expect(chiSquareSurvival(chiSquareUniform(bins), BINS - 1)).toBeGreaterThan(ALPHA);
  });
});

/** 10 bins in z (uniform for a uniform sphere, Archimedes) × 10 in φ. */
function sphereBin(w: readonly number[]): number {
  const z = Math.min(9, Math.floor(((1 + (w[2] ?? 0)) / 2) * 10));
  const phi = Math.atan2(w[1] ?? 0, w[0] ?? 0);
  const azimuth = Math.min(9, Math.floor(((phi + Math.PI) / (2 * Math.PI)) * 10));
  return Math.max(0, z) * 10 + Math.max(0, azimuth);
}

// ---------------------------------------------------------------------------
// Sampling on the GPU: a kernel draws N samples per configuration with the PCG
// stream (rngSeed per sample, rngNextFloat), and writes four floats each.
// ---------------------------------------------------------------------------
const MODE_HG = 0;
const MODE_RAYLEIGH = 1;
const MODE_SPHERE = 2;
const GPU_SAMPLES = 1 << 20;

const SAMPLING_KERNEL = `import package::rng::{rngNextFloat, rngSeed};
import package::directions::sampleUniformSphere;
import package::phase::{hgSample, hgSampleMu, rayleighSample};

// params: mode, frame, count, bits of g, bits of wo.x, wo.y, wo.z.
@group(0) @binding(0) var<storage, read> params: array<u32, 7>;
@group(0) @binding(1) var<storage, read_write> outputs: array<f32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= params[2]) {
    return;
  }
  var state = rngSeed(i, params[1]);
  let u = vec2f(rngNextFloat(&state), rngNextFloat(&state));
  let g = bitcast<f32>(params[3]);
  let wo = vec3f(bitcast<f32>(params[4]), bitcast<f32>(params[5]), bitcast<f32>(params[6]));
  var result = vec4f(0.0);
  if (params[0] == ${MODE_HG}u) {
    let s = hgSample(g, wo, u);
    let m = hgSampleMu(g, u.x, 1.0 - u.x);
    result = vec4f(-dot(wo, s.wi), m.oneMinusMu, m.onePlusMu, s.pdf);
  } else if (params[0] == ${MODE_RAYLEIGH}u) {
    let s = rayleighSample(wo, u);
    result = vec4f(-dot(wo, s.wi), dot(s.wi, s.wi), s.pdf, 0.0);
  } else {
    result = vec4f(sampleUniformSphere(u), 0.0);
  }
  for (var k = 0u; k < 4u; k++) {
    outputs[4u * i + k] = result[k];
  }
}
`;

async function gpuSamples(mode: number, g: number, frame: number): Promise<Float32Array> {
  const device = await nodeDevice();
  const code = await linkKernel(SHADER_LIBRARY, SAMPLING_KERNEL);
  const params = new Uint32Array([
    mode,
    frame,
    GPU_SAMPLES,
    f32ToBits(g),
    ...OBLIQUE_WO.map((c) => f32ToBits(c)),
  ]);
  const { output } = await runCompute(device, {
    code,
    inputs: [params],
    outputWords: 4 * GPU_SAMPLES,
    workgroups: [Math.ceil(GPU_SAMPLES / 64)],
  });
  return new Float32Array(output.buffer, output.byteOffset, output.length);
}

describe(`HG, Rayleigh and uniform-sphere sampling on the GPU (${GPU_SAMPLES} samples each)`, () => {
  const hg = new Map<number, Float32Array>();
  let rayleigh: Float32Array = new Float32Array(0);
  let sphere: Float32Array = new Float32Array(0);
  beforeAll(async () => {
    for (const [k, g] of HG_CHI_G.entries()) hg.set(g, await gpuSamples(MODE_HG, g, 100 + k));
    rayleigh = await gpuSamples(MODE_RAYLEIGH, 0, 200);
    sphere = await gpuSamples(MODE_SPHERE, 0, 300);
  }, 60_000);

  for (const g of HG_CHI_G) {
    const gf = Math.fround(g);
    it(`HG g = ${g}: GPU samples match the analytic density (chi-square, ${BINS} equiprobable bins in μ, α = 0.01/${CHI_SQUARE_TESTS})`, () => {
      const samples = hg.get(g) as Float32Array;
      const bins = new Array<number>(BINS).fill(0);
      for (let i = 0; i < GPU_SAMPLES; i++) {
        // Bin by the complement on the peak side: it keeps its digits where μ does not.
        const t = g >= 0 ? (samples[4 * i + 1] as number) : (samples[4 * i + 2] as number);
        const bin = binOf(hgCdfFromPeak(gf, t));
        bins[bin] = (bins[bin] ?? 0) + 1;
      }
      expect(chiSquareSurvival(chiSquareUniform(bins), BINS - 1)).toBeGreaterThan(ALPHA);
    });

    it(`HG g = ${g}: ⟨−wo·wi⟩ = g within 5σ, σ² = (1 − g²)/(3N); median within 5σ of g(3 − g²)/2`, () => {
      const samples = hg.get(g) as Float32Array;
      let sum = 0;
      for (let i = 0; i < GPU_SAMPLES; i++) sum += samples[4 * i] as number;
      // Var μ = ⟨μ²⟩ − g² = (1 − g²)/3 (quadrature test above). The f32 directions
      // add a bias of a few 1e-8 to μ, far below σ ≥ 2.5e-5.
      const sigma = Math.sqrt((1 - gf * gf) / 3 / GPU_SAMPLES);
      expect(Math.abs(sum / GPU_SAMPLES - gf)).toBeLessThan(5 * sigma);
      // The median from the complement on the peak side, which keeps its digits
      // near μ = ±1. Sample median: asymptotically normal, sd 1/(2 f(m) √N) with
      // f = 2π p_HG(m); plus the complements' 4e-6 relative GPU budget.
      const distances = new Float64Array(GPU_SAMPLES);
      for (let i = 0; i < GPU_SAMPLES; i++)
        distances[i] = samples[4 * i + (g >= 0 ? 1 : 2)] as number;
      distances.sort();
      const halfway =
        ((distances[GPU_SAMPLES / 2 - 1] as number) + (distances[GPU_SAMPLES / 2] as number)) / 2;
      const sampleMedian = g >= 0 ? 1 - halfway : halfway - 1;
      const median = (gf * (3 - gf * gf)) / 2;
      const sd = 1 / (2 * 2 * Math.PI * hgEval(gf, median) * Math.sqrt(GPU_SAMPLES));
      expect(Math.abs(sampleMedian - median)).toBeLessThan(5 * sd + 4e-6 * halfway);
    });

    it(`HG g = ${g}: every GPU sample has μ ∈ [−1, 1], finite complements and pdf = p at the sample`, () => {
      const samples = hg.get(g) as Float32Array;
      let worst = 0;
      for (let i = 0; i < GPU_SAMPLES; i++) {
        const mu = samples[4 * i] as number;
        const oneMinusMu = samples[4 * i + 1] as number;
        const onePlusMu = samples[4 * i + 2] as number;
        const pdf = samples[4 * i + 3] as number;
        if (!(mu >= -1 && mu <= 1 && oneMinusMu >= 0 && onePlusMu >= 0 && pdf > 0))
          expect.fail(
            `sample ${i}: μ = ${mu}, 1 − μ = ${oneMinusMu}, 1 + μ = ${onePlusMu}, pdf = ${pdf}`,
          );
        worst = Math.max(worst, Math.abs(pdf / hgEvalTerms(gf, oneMinusMu, onePlusMu) - 1));
      }
      // The GPU evaluation budget of tests/shaders/phase.test.ts (≈ 13 ULP ⇒ 4e-6).
      expect(worst).toBeLessThan(4e-6);
    });
  }

  it('Rayleigh: GPU samples match the analytic density (chi-square on F(−wo·wi)); ⟨μ⟩ = 0 within 5σ; pdf = p(μ)', () => {
    const bins = new Array<number>(BINS).fill(0);
    let sum = 0;
    for (let i = 0; i < GPU_SAMPLES; i++) {
      const mu = rayleigh[4 * i] as number;
      if (!(Math.abs(mu) <= 1 + 2e-6)) expect.fail(`sample ${i}: μ = ${mu}`);
      bins[binOf(rayleighCdf(mu))] = (bins[binOf(rayleighCdf(mu))] ?? 0) + 1;
      sum += mu;
      const pdf = rayleigh[4 * i + 2] as number;
      // pdf from the sampled μ; −wo·wi carries 2e-6 of f32 direction rounding, ×|p'| ≤ 0.12.
      if (Math.abs(pdf - rayleighEval(mu)) > 1e-6)
        expect.fail(`sample ${i}: pdf ${pdf} vs p(${mu})`);
      if (Math.abs((rayleigh[4 * i + 1] as number) - 1) > 4e-6)
        expect.fail(`sample ${i}: |wi|² = ${rayleigh[4 * i + 1]}`);
    }
    expect(chiSquareSurvival(chiSquareUniform(bins), BINS - 1)).toBeGreaterThan(ALPHA);
    // ⟨μ²⟩ = 2/5 for Rayleigh ⇒ σ = √(0.4/N).
    expect(Math.abs(sum / GPU_SAMPLES)).toBeLessThan(5 * Math.sqrt(0.4 / GPU_SAMPLES));
  });

  it('uniform sphere: GPU directions are uniform in (z, φ) (chi-square, 10 × 10 bins) and unit length', () => {
    const bins = new Array<number>(BINS).fill(0);
    for (let i = 0; i < GPU_SAMPLES; i++) {
      const w = [sphere[4 * i] as number, sphere[4 * i + 1] as number, sphere[4 * i + 2] as number];
      if (Math.abs(Math.hypot(...w) - 1) > 2e-6)
        expect.fail(`sample ${i}: |w| = ${Math.hypot(...w)}`);
      bins[sphereBin(w)] = (bins[sphereBin(w)] ?? 0) + 1;
    }
    expect(chiSquareSurvival(chiSquareUniform(bins), BINS - 1)).toBeGreaterThan(ALPHA);
  });
});
