// The float64 twin of shaders/chromatic.wesl against closed forms (chapter 12, colour in a
// medium): the density integral against quadrature, the hero weights and spectral-tracking
// probabilities against their definitions, and each estimator (one channel at a time, hero
// wavelength, spectral tracking with the average and the max scheme) unbiased for
//   - the transmittance and the first-scattering weight of a slab, per channel
//     (tests/support/chromaticWalks.ts: T_c = e^{−σt,c D(d)}, S_c = α_c(1 − T_c)),
//     homogeneous and with linear density;
//   - the reflectance and transmittance of a multiply scattering rod (two-stream closed form,
//     tests/support/chromaticRod.ts).
// Statistics: fixed seeds; each channel's mean passes when |mean − exact| < 5·sqrt(s²/N)
// (s² the sample variance). Each check has two-sided p ≈ 5.7e-7; the ~200 checks of this file
// stay below α = 1e-4 together (Bonferroni).
import { describe, expect, it } from 'vitest';
import {
  chromaticDensity,
  chromaticMajorantDensity,
  chromaticOpticalDepth,
  chromaticTransmittance,
  heroBalanceWeight,
  heroChannelWeights,
  spectralEventProbabilities,
  SPECTRAL_AVERAGE,
  SPECTRAL_MAX,
  type ChromaticMedium,
  type Rgb,
} from '../../src/reference/chromatic.ts';
import { rngSeed } from '../../src/reference/rng.ts';
import { simpson } from '../support/quadrature.ts';
import { moments } from '../support/statistics.ts';
import {
  CHROMATIC_ESTIMATORS,
  chromaticSlabExpectations,
  twinChromaticWalker,
} from '../support/chromaticWalks.ts';
import { rodClosedForm, rodWalk, type RodEstimator } from '../support/chromaticRod.ts';

const medium = (
  sigmaT: Rgb,
  albedo: Rgb = [0.9, 0.7, 0.5],
  densityBase = 1,
  densitySlope = 0,
): ChromaticMedium => ({ sigmaT, albedo, densityBase, densitySlope });

/** The book's default chromatic medium: σt = (0.5, 2, 8)/m, a 16× spread from red to blue. */
const DEFAULT = medium([0.5, 2, 8]);

/** |mean − exact| < 5·SE per channel; a channel whose samples are all equal must be exact. */
function expectUnbiased(samples: Rgb[], exact: Rgb, label: string): void {
  for (let c = 0; c < 3; c++) {
    const m = moments(samples.map((s) => s[c]!));
    const bound = 5 * Math.sqrt(m.variance / m.n) + 1e-12;
    expect(
      Math.abs(m.mean - exact[c]!),
      `${label} channel ${c}: mean ${m.mean} vs ${exact[c]} (bound ${bound})`,
    ).toBeLessThan(bound);
  }
}

describe('chromatic medium: density and optical depth', () => {
  const cases: [string, ChromaticMedium, number][] = [
    ['homogeneous', medium([1, 1, 1], [1, 1, 1], 0.7, 0), 2],
    ['increasing', medium([1, 1, 1], [1, 1, 1], 0.2, 1.6), 1.5],
    ['decreasing through 0 at s = 0.5', medium([1, 1, 1], [1, 1, 1], 1, -2), 1],
    ['increasing from 0 at s = 0.25', medium([1, 1, 1], [1, 1, 1], -0.5, 2), 1],
    ['zero everywhere', medium([1, 1, 1], [1, 1, 1], -1, -1), 3],
  ];
  for (const [name, m, d] of cases) {
    it(`${name}: D(s) equals the quadrature of ρ, and ρ̄ bounds ρ on [0, d]`, () => {
      for (const s of [0, 0.1, 0.25, 0.5, 0.9, d]) {
        // Split at the kink of max(·, 0) so that Simpson's rule sees smooth pieces.
        const kink = m.densitySlope !== 0 ? -m.densityBase / m.densitySlope : -1;
        const integral =
          kink > 0 && kink < s
            ? simpson((u) => chromaticDensity(m, u), 0, kink) +
              simpson((u) => chromaticDensity(m, u), kink, s)
            : simpson((u) => chromaticDensity(m, u), 0, s);
        expect(chromaticOpticalDepth(m, s)).toBeCloseTo(integral, 10);
        expect(chromaticDensity(m, s)).toBeLessThanOrEqual(chromaticMajorantDensity(m, d));
      }
    });
  }
  it('D(s) ≤ 0 for s ≤ 0 and T_c = exp(−σt,c D)', () => {
    expect(chromaticOpticalDepth(DEFAULT, -1)).toBe(0);
    const T = chromaticTransmittance(DEFAULT, 1);
    expect(T[0]).toBeCloseTo(Math.exp(-0.5), 14);
    expect(T[2]).toBeCloseTo(Math.exp(-8), 14);
  });
});

describe('hero weights and spectral-tracking probabilities (definitions)', () => {
  it('heroBalanceWeight is 3/Σp whichever channel was the hero, 0 when no channel could sample', () => {
    const pdfs: Rgb = [0.2, 1.5, 3];
    for (const hero of [0, 1, 2]) expect(heroBalanceWeight(pdfs, hero)).toBeCloseTo(3 / 4.7, 14);
    expect(heroBalanceWeight([0, 0, 0], 1)).toBe(0);
  });
  it('heroChannelWeights is 3p_c/Σp, sums to 3, and does not underflow for pdfs of e^-1000', () => {
    const w = heroChannelWeights([Math.log(0.2), Math.log(1.5), Math.log(3)], 0);
    expect(w[0]).toBeCloseTo((3 * 0.2) / 4.7, 14);
    expect(w[2]).toBeCloseTo((3 * 3) / 4.7, 14);
    const far = heroChannelWeights([-1000, -1001, -1e30], 1);
    expect(far[0] + far[1] + far[2]).toBeCloseTo(3, 12);
    expect(far[0] / far[1]).toBeCloseTo(Math.E, 10);
    expect(far[2]).toBe(0);
  });
  it('spectral probabilities: gray medium with w = 1 gives delta tracking (σa, σs, σn)/σ̄', () => {
    for (const scheme of [SPECTRAL_AVERAGE, SPECTRAL_MAX]) {
      const p = spectralEventProbabilities(
        [0.3, 0.3, 0.3],
        [0.5, 0.5, 0.5],
        [1.2, 1.2, 1.2],
        [1, 1, 1],
        scheme,
      );
      expect(p[0]).toBeCloseTo(0.3 / 2, 14);
      expect(p[1]).toBeCloseTo(0.5 / 2, 14);
      expect(p[2]).toBeCloseTo(1.2 / 2, 14);
    }
  });
  it('spectral probabilities: average and max schemes (Kutz et al. 2017 §5.1), w = 0 absorbs', () => {
    const a: Rgb = [0, 1, 2];
    const s: Rgb = [1, 1, 0];
    const n: Rgb = [3, 2, 2];
    const w: Rgb = [1, 2, 1];
    const avg = spectralEventProbabilities(a, s, n, w, SPECTRAL_AVERAGE);
    // avg: (0 + 2 + 2)/3, (1 + 2 + 0)/3, (3 + 4 + 2)/3 → 4 : 3 : 9
    expect(avg.map((x) => x * 16)).toEqual([4, 3, 9].map((x) => expect.closeTo(x, 12) as number));
    const max = spectralEventProbabilities(a, s, n, w, SPECTRAL_MAX);
    // max: 2, 2, 4 → 2 : 2 : 4
    expect(max.map((x) => x * 8)).toEqual([2, 2, 4].map((x) => expect.closeTo(x, 12) as number));
    expect(spectralEventProbabilities(a, s, n, [0, 0, 0], SPECTRAL_MAX)).toEqual([1, 0, 0]);
  });
});

const WALKS = 20_000;

function slabWalks(
  estimator: (typeof CHROMATIC_ESTIMATORS)[number],
  m: ChromaticMedium,
  d: number,
) {
  const walk = twinChromaticWalker({ estimator, medium: m, d, maxSteps: 65536 });
  const T: Rgb[] = [];
  const S: Rgb[] = [];
  let capped = 0;
  for (let i = 0; i < WALKS; i++) {
    const w = walk({ value: rngSeed(i, 12) });
    T.push(w.T);
    S.push(w.S);
    capped += w.capped;
  }
  return { T, S, capped };
}

describe('each estimator is unbiased for a chromatic slab (transmittance and first scattering)', () => {
  const slabs: [string, ChromaticMedium, number][] = [
    ['homogeneous σt = (0.5, 2, 8), d = 1', DEFAULT, 1],
    [
      'linear density 0.2 + 1.6 s, σt = (0.5, 2, 8), d = 1',
      medium([0.5, 2, 8], [0.9, 0.7, 0.5], 0.2, 1.6),
      1,
    ],
    [
      'density 1 − 2s (zero beyond 0.5), σt = (1, 4, 16), d = 1',
      medium([1, 4, 16], [0.3, 0.95, 0.6], 1, -2),
      1,
    ],
    ['gray medium σt = (2, 2, 2)', medium([2, 2, 2], [0.8, 0.8, 0.8]), 1],
  ];
  for (const [name, m, d] of slabs) {
    const exact = chromaticSlabExpectations(m, d);
    for (const estimator of CHROMATIC_ESTIMATORS) {
      it(`${estimator}: ${name}`, () => {
        const run = slabWalks(estimator, m, d);
        expect(run.capped).toBe(0);
        expectUnbiased(run.T, exact.T, 'T');
        expectUnbiased(run.S, exact.S, 'S');
      });
    }
  }
});

describe('each estimator is unbiased for multiple scattering in a chromatic rod (two-stream closed form)', () => {
  const rods: [string, ChromaticMedium, number][] = [
    ['σt = (0.5, 2, 8), α = (0.9, 0.7, 0.5), L = 1', DEFAULT, 1],
    ['σt = (0.25, 1, 4), α = (0.99, 0.95, 0.8), L = 2', medium([0.25, 1, 4], [0.99, 0.95, 0.8]), 2],
  ];
  const estimators: RodEstimator[] = ['oneChannel', 'hero', 'spectralAverage', 'spectralMax'];
  for (const [name, m, length] of rods) {
    const exact = [0, 1, 2].map((c) => rodClosedForm(m.sigmaT[c]!, m.albedo[c]!, length));
    for (const estimator of estimators) {
      it(`${estimator}: ${name}`, () => {
        const R: Rgb[] = [];
        const T: Rgb[] = [];
        for (let i = 0; i < WALKS; i++) {
          const e = rodWalk(estimator, m, length, { value: rngSeed(i, 7) });
          R.push(e.R);
          T.push(e.T);
        }
        expectUnbiased(R, exact.map((e) => e.R) as Rgb, 'R');
        expectUnbiased(T, exact.map((e) => e.T) as Rgb, 'T');
      });
    }
  }
  it('the rod closed form: α = 0 is Beer, α = 1 is 1/(1 + τ/2), and R + T ≤ 1', () => {
    expect(rodClosedForm(2, 0, 1).T).toBeCloseTo(Math.exp(-2), 14);
    expect(rodClosedForm(2, 0, 1).R).toBeCloseTo(0, 14);
    expect(rodClosedForm(2, 1, 1).T).toBeCloseTo(0.5, 14);
    expect(rodClosedForm(2, 1 - 1e-12, 1).T).toBeCloseTo(0.5, 5);
    const { R, T } = rodClosedForm(3, 0.7, 1);
    expect(R + T).toBeLessThan(1);
  });
});
