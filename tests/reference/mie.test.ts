// The Lorenz–Mie twin (src/reference/mie.ts) against published values and the limits of
// the theory, and the tabulated phase function's sampler against its own density
// (chi-square, as HG's in tests/reference/phase.test.ts).
//
// Sources of the published numbers:
// - [MIEV0] Wiscombe's MIEV0 test cases (Wiscombe 1979, NCAR/TN-140+STR; the program's
//   test output), as transcribed into scottprahl/miepython tests/test_nojit.py. MIEV0
//   writes m = n − iκ; its S1, S2 are the complex conjugates of BH's (src/reference/mie.ts
//   header), so its S's are compared with conj(S) here, and Q's and g directly.
//   Tolerance: half a unit of the last printed digit (printed to 6 decimals: 5e-7),
//   one unit where a case was printed to fewer digits, and 1e-6 at x = 10⁴, where
//   MIEV0's single-precision sums of 10⁴ terms differ from float64 in the 7th digit
//   (case 16's Q_sca: 1.2365743 here, 1.236575 printed).
// - [BH] Bohren & Huffman 1983, Appendix A, the sample output of BHMIE for m = 1.55,
//   x = 5.213 (a sphere of radius 0.525 µm in light of 0.6328 µm): Q's, g and the
//   normalised S11, POL = −S12/S11, S33/S11, S34/S11 every 9°, as transcribed in
//   miepython's tests. BH print x = 5.213 but computed with x = 2π·0.525/0.6328 =
//   5.21282 (the table matches that x to all six printed digits, and x = 5.213 only to
//   2e-4); printed to 6 digits: tolerance 2e-6 (absolute, values ≤ 1).
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  complexAbs2,
  complexConj,
  complexMul,
  mieAmplitudes,
  mieCoefficients,
  mieEfficiencies,
  mieEfficienciesFromCoefficients,
  mieLogDerivative,
  miePhaseValues,
  mieSeriesCoefficients,
  mieSmallParticleCoefficients,
  mieTabulatePhase,
  mieTermCount,
  mieUsesSmallParticle,
  phaseTableFromValues,
  phaseTableAngles,
  phaseTabulatedEval,
  phaseTabulatedEvalTerms,
  phaseTabulatedSample,
  phaseTabulatedSampleMu,
  type Complex,
  type PhaseTable,
  type RefractiveIndex,
} from '../../src/reference/mie.ts';
import { rayleighEval } from '../../src/reference/phase.ts';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';
import { chiSquareSurvival } from '../../src/statistics/distributions.ts';
import { gaussLegendre } from '../support/hFunction.ts';

const index = (n: number, kappa = 0): RefractiveIndex => ({ n, kappa });

// ---------------------------------------------------------------------------
// Quadrature: Gauss–Legendre on pieces split geometrically toward the forward peak,
// whose width in 1 − μ is ≈ 1/x².
// ---------------------------------------------------------------------------
// The support's rule is on [0, 1]; on [−1, 1]: x = 2t − 1, w = 2w.
const GL = (({ nodes, weights }) => ({
  nodes: nodes.map((t) => 2 * t - 1),
  weights: weights.map((w) => 2 * w),
}))(gaussLegendre(32));

/**
 * ∫_{4π} f(μ) dω = 2π ∫_0^π f(cos θ) sin θ dθ by 32-point Gauss–Legendre on `pieces` equal
 * pieces in θ: the lobe's ripples have a period ≈ π/x and its forward peak a width ≈ 1/x,
 * so pieces ≈ 4x resolve both.
 */
function integrateSphere(f: (mu: number) => number, pieces: number): number {
  const width = Math.PI / pieces;
  let sum = 0;
  for (let j = 0; j < pieces; j++) {
    const mid = (j + 0.5) * width;
    GL.nodes.forEach((node, k) => {
      const theta = mid + (width / 2) * node;
      sum += GL.weights[k]! * f(Math.cos(theta)) * Math.sin(theta);
    });
  }
  return 2 * Math.PI * sum * (width / 2);
}

// ---------------------------------------------------------------------------
// Published values
// ---------------------------------------------------------------------------
interface PublishedCase {
  name: string;
  m: RefractiveIndex;
  x: number;
  qExt?: number;
  qSca?: number;
  g?: number;
  /** Q_back from |S1(180°)|: Q_back = 4|S1(π)|²/x². */
  qBack?: number;
  tolerance: number;
}

const PUBLISHED: readonly PublishedCase[] = [
  // [BH] Appendix A.
  {
    name: 'BH BHMIE m = 1.55, x = 5.213',
    m: index(1.55),
    x: (2 * Math.PI * 0.525) / 0.6328,
    qExt: 3.10543,
    qSca: 3.10543,
    qBack: 2.92534,
    g: 0.63314,
    tolerance: 5e-6,
  },
  // [MIEV0] test cases 5–8 (m = 0.75; 5 and 6 straddle the small-particle switch).
  {
    name: 'MIEV0 case 5, m = 0.75, x = 0.099 (small-particle branch)',
    m: index(0.75),
    x: 0.099,
    qSca: 7e-6,
    g: 0.001448,
    qBack: (4 * complexAbs2([1.81756e-8, 1.6481e-4])) / 0.099 ** 2,
    tolerance: 5e-7,
  },
  {
    name: 'MIEV0 case 6, m = 0.75, x = 0.101 (full series)',
    m: index(0.75),
    x: 0.101,
    qSca: 8e-6,
    g: 0.001507,
    qBack: (4 * complexAbs2([2.04875e-8, 1.74965e-4])) / 0.101 ** 2,
    tolerance: 5e-7,
  },
  {
    name: 'MIEV0 case 7, m = 0.75, x = 10',
    m: index(0.75),
    x: 10,
    qSca: 2.232265,
    g: 0.896473,
    qBack: (4 * complexAbs2([1.07857, 3.60881e-2])) / 100,
    tolerance: 5e-7,
  },
  {
    name: 'MIEV0 case 8, m = 0.75, x = 1000',
    m: index(0.75),
    x: 1000,
    qSca: 1.997908,
    g: 0.844944,
    qBack: (4 * complexAbs2([1.70578e1, 4.84251e2])) / 1e6,
    tolerance: 5e-7,
  },
  // [MIEV0] older test cases for m = 1.5 (printed to 4–5 digits).
  {
    name: 'MIEV0 (old) m = 1.5, x = 10',
    m: index(1.5),
    x: 10,
    qSca: 2.882,
    qExt: 2.882,
    qBack: (4 * complexAbs2([4.322, 4.868])) / 100,
    tolerance: 1e-4,
  },
  {
    name: 'MIEV0 (old) m = 1.5, x = 100',
    m: index(1.5),
    x: 100,
    qSca: 2.0944,
    qExt: 2.0944,
    tolerance: 1e-4,
  },
  {
    name: 'MIEV0 (old) m = 1.5, x = 1000',
    m: index(1.5),
    x: 1000,
    qSca: 2.0139,
    qExt: 2.0139,
    tolerance: 1e-4,
  },
  {
    name: 'MIEV0 (old) m = 1.5, x = 5000',
    m: index(1.5),
    x: 5000,
    qSca: 2.0086,
    qExt: 2.0086,
    tolerance: 1e-4,
  },
  // [MIEV0] test cases 9–11: water with a trace of absorption.
  {
    name: 'MIEV0 case 9, m = 1.33 + 1e-5i, x = 1',
    m: index(1.33, 1e-5),
    x: 1,
    qSca: 0.093923,
    g: 0.184517,
    tolerance: 5e-7,
  },
  {
    name: 'MIEV0 case 10, m = 1.33 + 1e-5i, x = 100',
    m: index(1.33, 1e-5),
    x: 100,
    qSca: 2.096594,
    g: 0.868959,
    tolerance: 5e-7,
  },
  {
    name: 'MIEV0 case 11, m = 1.33 + 1e-5i, x = 10000',
    m: index(1.33, 1e-5),
    x: 10000,
    qSca: 1.723857,
    g: 0.90784,
    tolerance: 1e-6,
  },
  // [MIEV0] test cases 12–16: m = 1.5 + i.
  {
    name: 'MIEV0 case 12, m = 1.5 + i, x = 0.055 (small-particle branch)',
    m: index(1.5, 1),
    x: 0.055,
    qExt: 0.101491,
    qSca: 1.1e-5,
    g: 0.000491,
    tolerance: 5e-7,
  },
  {
    name: 'MIEV0 case 13, m = 1.5 + i, x = 0.056 (full series)',
    m: index(1.5, 1),
    x: 0.056,
    qExt: 0.103347,
    qSca: 1.2e-5,
    g: 0.000509,
    tolerance: 5e-7,
  },
  {
    name: 'MIEV0 case 14, m = 1.5 + i, x = 1',
    m: index(1.5, 1),
    x: 1,
    qExt: 2.336321,
    qSca: 0.6634538,
    qBack: 0.573003,
    g: 0.192136,
    tolerance: 5e-7,
  },
  {
    name: 'MIEV0 case 15, m = 1.5 + i, x = 100',
    m: index(1.5, 1),
    x: 100,
    qExt: 2.097502,
    qSca: 1.283697,
    g: 0.850252,
    tolerance: 5e-7,
  },
  {
    name: 'MIEV0 case 16, m = 1.5 + i, x = 10000',
    m: index(1.5, 1),
    x: 10000,
    qExt: 2.004368,
    qSca: 1.236575,
    g: 0.846309,
    tolerance: 1e-6,
  },
  // [MIEV0] test cases 17–19: strongly absorbing m = 10 + 10i.
  {
    name: 'MIEV0 case 17, m = 10 + 10i, x = 1',
    m: index(10, 10),
    x: 1,
    qSca: 2.049405,
    g: -0.110664,
    tolerance: 5e-7,
  },
  {
    name: 'MIEV0 case 18, m = 10 + 10i, x = 100',
    m: index(10, 10),
    x: 100,
    qSca: 1.836785,
    g: 0.556215,
    tolerance: 5e-7,
  },
  {
    name: 'MIEV0 case 19, m = 10 + 10i, x = 10000',
    m: index(10, 10),
    x: 10000,
    qSca: 1.795393,
    g: 0.548194,
    tolerance: 1e-6,
  },
];

describe('published efficiencies and asymmetry ([MIEV0], [BH])', () => {
  for (const c of PUBLISHED) {
    it(`${c.name}: ${['qExt', 'qSca', 'qBack', 'g'].filter((k) => k in c).join(', ')} within ${c.tolerance}`, () => {
      const e = mieEfficiencies(c.x, c.m);
      if (c.qExt !== undefined) expect(Math.abs(e.qExt - c.qExt)).toBeLessThanOrEqual(c.tolerance);
      if (c.qSca !== undefined) expect(Math.abs(e.qSca - c.qSca)).toBeLessThanOrEqual(c.tolerance);
      if (c.g !== undefined) expect(Math.abs(e.g - c.g)).toBeLessThanOrEqual(c.tolerance);
      // Q_back is derived from a printed S1(180°) with 6 significant digits: relative 2e-5.
      if (c.qBack !== undefined)
        expect(Math.abs(e.qBack - c.qBack)).toBeLessThanOrEqual(
          Math.max(c.tolerance, 2e-5 * c.qBack),
        );
    });
  }

  it('the switch between the small-particle branch and the series follows MIEV0 (|m|x ≤ 0.1, x ≤ 0.1)', () => {
    expect(mieUsesSmallParticle(0.099, index(0.75))).toBe(true);
    expect(mieUsesSmallParticle(0.101, index(0.75))).toBe(false);
    expect(mieUsesSmallParticle(0.055, index(1.5, 1))).toBe(true);
    expect(mieUsesSmallParticle(0.056, index(1.5, 1))).toBe(false);
  });

  it("Wiscombe's term count: x + 4x^{1/3} + 1 (x ≤ 8), x + 4.05x^{1/3} + 2 (8 < x < 4200), x + 4x^{1/3} + 2", () => {
    expect(mieTermCount(1)).toBe(6);
    expect(mieTermCount(10)).toBe(20);
    expect(mieTermCount(1000)).toBe(1042);
    expect(mieTermCount(10000)).toBe(10088);
  });

  it('[MIEV0] logarithmic derivative D_10(mx) at m = 1.28 + 1.37i, x = 62: 0.004087 − 1.000262i (conj of Wiscombe’s)', () => {
    const d = mieLogDerivative([62 * 1.28, 62 * 1.37], 10)[10]!;
    expect(d[0]).toBeCloseTo(0.004087, 5);
    expect(d[1]).toBeCloseTo(-1.000262, 5);
  });

  // [MIEV0] test case 14, S1 and S2 every 30° (Wiscombe's normalisation is BH's S).
  const CASE_14_ANGLES = [0, 30, 60, 90, 120, 150, 180];
  const CASE_14_S1: Complex[] = [
    [0.58408, 0.190515],
    [0.565702, 0.1872],
    [0.517525, 0.178443],
    [0.45634, 0.167167],
    [0.400212, 0.156643],
    [0.362157, 0.149391],
    [0.348844, 0.146829],
  ];
  const CASE_14_S2: Complex[] = [
    [0.58408, 0.190515],
    [0.500161, 0.145611],
    [0.287964, 0.041054],
    [0.0362285, -0.0618265],
    [-0.174875, -0.122959],
    [-0.305682, -0.143846],
    [-0.348844, -0.146829],
  ];
  it('[MIEV0] case 14 (m = 1.5 + i, x = 1): S1 and S2 every 30° within 1e-6 (conjugated)', () => {
    const c = mieCoefficients(1, index(1.5, 1));
    CASE_14_ANGLES.forEach((degrees, k) => {
      const { s1, s2 } = mieAmplitudes(c, Math.cos((degrees * Math.PI) / 180));
      const w1 = complexConj(s1);
      const w2 = complexConj(s2);
      expect(Math.abs(w1[0] - CASE_14_S1[k]![0])).toBeLessThan(1e-6);
      expect(Math.abs(w1[1] - CASE_14_S1[k]![1])).toBeLessThan(1e-6);
      expect(Math.abs(w2[0] - CASE_14_S2[k]![0])).toBeLessThan(1e-6);
      expect(Math.abs(w2[1] - CASE_14_S2[k]![1])).toBeLessThan(1e-6);
    });
  });

  // [BH] Appendix A: θ, S11/S11(0), POL = −S12/S11, S33/S11, S34/S11.
  const BH_TABLE: readonly (readonly [number, number, number, number, number])[] = [
    [0, 1, 0, 1, 0],
    [9, 0.78539, -0.00459811, 0.9994, 0.0343261],
    [18, 0.356897, -0.0458541, 0.986022, 0.160184],
    [27, 0.0766119, -0.364744, 0.843603, 0.394076],
    [36, 0.0355355, -0.534997, 0.686967, -0.491787],
    [45, 0.0701845, 0.00959953, 0.959825, -0.280434],
    [54, 0.0574313, 0.0477927, 0.985371, 0.163584],
    [63, 0.021966, -0.440604, 0.648043, 0.621216],
    [72, 0.0125959, -0.831996, 0.203255, -0.516208],
    [81, 0.017375, 0.034167, 0.795354, -0.605182],
    [90, 0.0124601, 0.230462, 0.937497, 0.260742],
    [99, 0.00679093, -0.713472, -0.00717397, 0.700647],
    [108, 0.00954239, -0.756255, -0.0394748, -0.653085],
    [117, 0.00863419, -0.281215, 0.536251, -0.795835],
    [126, 0.00227421, -0.239612, 0.967602, 0.0795798],
    [135, 0.00543998, -0.850804, 0.187531, -0.490882],
    [144, 0.0160243, -0.706334, 0.495254, -0.505781],
    [153, 0.0188852, -0.891081, 0.453277, -0.0226817],
    [162, 0.0195254, -0.783319, -0.391613, 0.482752],
    [171, 0.0301676, -0.196194, -0.962069, 0.189556],
    [180, 0.0383189, 0, -1, 0],
  ];
  it('[BH] m = 1.55, x = 5.213: the scattering matrix every 9° (S11 normalised, POL, S33, S34) within 2e-6', () => {
    const c = mieCoefficients((2 * Math.PI * 0.525) / 0.6328, index(1.55));
    const elements = (degrees: number): [number, number, number, number] => {
      const { s1, s2 } = mieAmplitudes(c, Math.cos((degrees * Math.PI) / 180));
      const s11 = 0.5 * (complexAbs2(s1) + complexAbs2(s2));
      const s12 = 0.5 * (complexAbs2(s2) - complexAbs2(s1));
      const s2s1 = complexMul(s2, complexConj(s1)); // BH 3.16: S33 = Re, S34 = Im of S2 S1*
      return [s11, s12, s2s1[0], s2s1[1]];
    };
    const forward = elements(0)[0];
    for (const [degrees, s11, pol, s33, s34] of BH_TABLE) {
      const [e11, e12, e33, e34] = elements(degrees);
      expect(Math.abs(e11 / forward - s11)).toBeLessThan(2e-6);
      expect(Math.abs(-e12 / e11 - pol)).toBeLessThan(2e-6);
      expect(Math.abs(e33 / e11 - s33)).toBeLessThan(2e-6);
      expect(Math.abs(e34 / e11 - s34)).toBeLessThan(2e-6);
    }
  });
});

// ---------------------------------------------------------------------------
// Limits and identities
// ---------------------------------------------------------------------------
describe('limits and identities', () => {
  const rayleighQsca = (x: number, m: RefractiveIndex): number => {
    const m2: Complex = [m.n * m.n - m.kappa * m.kappa, 2 * m.n * m.kappa];
    const ratio = complexMul([m2[0] - 1, m2[1]], complexConj([m2[0] + 2, m2[1]]));
    const k = complexAbs2(ratio) / complexAbs2([m2[0] + 2, m2[1]]) ** 2;
    return (8 / 3) * x ** 4 * k;
  };
  for (const m of [index(1.33), index(1.5, 1), index(1.75, 0.44), index(0.75)]) {
    for (const x of [0.001, 0.01, 0.05]) {
      it(`x = ${x}, m = ${m.n} + ${m.kappa}i: Q_sca = (8/3)x⁴|(m²−1)/(m²+2)|² and p = 3(1 + μ²)/(16π) to O(x²)`, () => {
        const c = mieCoefficients(x, m);
        const e = mieEfficienciesFromCoefficients(c);
        // The first corrections are of relative order x²|m|² (BH 5.7–5.8 and the a_2, b_1 terms).
        const bound = 10 * x * x * (m.n ** 2 + m.kappa ** 2) + 1e-12;
        expect(Math.abs(e.qSca / rayleighQsca(x, m) - 1)).toBeLessThan(bound);
        const mus = [1, 0.6, 0, -0.3, -1];
        miePhaseValues(c, e.qSca, mus).forEach((p, k) => {
          expect(Math.abs(p / rayleighEval(mus[k]!) - 1)).toBeLessThan(bound);
        });
      });
    }
  }

  for (const m of [index(1.33), index(0.75), index(1.5, 1), index(1.75, 0.44)]) {
    it(`small-particle expansion and full series agree to 1e-6 where the switch can use either (m = ${m.n} + ${m.kappa}i)`, () => {
      for (const x of [0.01, 0.03, 0.05]) {
        if (!mieUsesSmallParticle(x, m)) continue;
        const small = mieEfficienciesFromCoefficients(mieSmallParticleCoefficients(x, m));
        const series = mieEfficienciesFromCoefficients(mieSeriesCoefficients(x, m));
        for (const key of ['qSca', 'qExt', 'qBack', 'g'] as const)
          expect(Math.abs(small[key] / series[key] - 1)).toBeLessThan(1e-6);
      }
    });
  }

  it('extinction paradox: Q_ext → 2 at x = 10⁴ (within 0.01) for dielectric, absorbing and metallic spheres', () => {
    for (const m of [index(1.33), index(1.5, 1), index(10, 10), index(1.75, 0.44)]) {
      expect(Math.abs(mieEfficiencies(1e4, m).qExt - 2)).toBeLessThan(0.01);
    }
  });

  it('κ = 0 ⇒ Q_abs = 0 (to 1e-11 of Q_ext) over x from 0.2 to 10⁴; κ > 0 ⇒ Q_abs > 0', () => {
    for (const x of [0.2, 1, 5.213, 30, 300, 3000, 10000]) {
      for (const n of [0.75, 1.33, 1.5, 2.5]) {
        const e = mieEfficiencies(x, index(n));
        expect(Math.abs(e.qAbs)).toBeLessThan(1e-11 * e.qExt);
      }
      expect(mieEfficiencies(x, index(1.33, 1e-3)).qAbs).toBeGreaterThan(0);
    }
  });

  it('optical theorem: Q_ext = (4/x²) Re S(0), and S1(0) = S2(0), S1(π) = −S2(π) (BH 4.76–4.77)', () => {
    for (const [x, m] of [
      [0.5, index(1.33)],
      [5.213, index(1.55)],
      [40, index(1.5, 1)],
      [300, index(1.33, 1e-5)],
    ] as const) {
      const c = mieCoefficients(x, m);
      const e = mieEfficienciesFromCoefficients(c);
      const forward = mieAmplitudes(c, 1);
      const back = mieAmplitudes(c, -1);
      expect(Math.abs((4 / x ** 2) * forward.s1[0] - e.qExt)).toBeLessThan(1e-10 * e.qExt);
      expect(Math.hypot(forward.s1[0] - forward.s2[0], forward.s1[1] - forward.s2[1])).toBeLessThan(
        1e-10 * Math.hypot(...forward.s1),
      );
      expect(Math.hypot(back.s1[0] + back.s2[0], back.s1[1] + back.s2[1])).toBeLessThan(
        1e-9 * (Math.hypot(...back.s1) + 1e-300),
      );
      // Q_back from the coefficients equals 4|S1(π)|²/x².
      expect(Math.abs(e.qBack - (4 * complexAbs2(back.s1)) / x ** 2)).toBeLessThan(1e-9 * e.qBack);
    }
  });

  for (const [x, m] of [
    [0.05, index(1.33)],
    [1, index(1.5, 1)],
    [5.213, index(1.55)],
    [30, index(1.33)],
    [200, index(1.75, 0.44)],
  ] as const) {
    it(`x = ${x}, m = ${m.n} + ${m.kappa}i: ∫p dω = 1 and ∫μ p dω = g (quadrature, 1e-9)`, () => {
      const c = mieCoefficients(x, m);
      const e = mieEfficienciesFromCoefficients(c);
      const p = (mu: number): number => miePhaseValues(c, e.qSca, [mu])[0]!;
      const pieces = Math.max(16, Math.ceil(4 * x));
      expect(Math.abs(integrateSphere(p, pieces) - 1)).toBeLessThan(1e-9);
      expect(Math.abs(integrateSphere((mu) => mu * p(mu), pieces) - e.g)).toBeLessThan(1e-9);
    });
  }

  it('fast-check: finite, 0 ≤ Q_sca ≤ Q_ext, |g| ≤ 1 and 0 ≤ ϖ ≤ 1 over x ∈ [0.01, 300], n ∈ [1.01, 3], κ ∈ [0, 10]', () => {
    fc.assert(
      fc.property(
        fc.double({ min: -2, max: Math.log10(300), noNaN: true }),
        fc.double({ min: 1.01, max: 3, noNaN: true }),
        fc.double({ min: 0, max: 10, noNaN: true }),
        (logX, n, kappa) => {
          const e = mieEfficiencies(10 ** logX, index(n, kappa));
          return (
            [e.qExt, e.qSca, e.qBack, e.g].every(Number.isFinite) &&
            e.qSca >= 0 &&
            e.qSca <= e.qExt * (1 + 1e-9) &&
            Math.abs(e.g) <= 1 &&
            e.albedo >= 0 &&
            e.albedo <= 1 + 1e-9
          );
        },
      ),
      { numRuns: 200 },
    );
  });
});

// ---------------------------------------------------------------------------
// The tabulated phase function
// ---------------------------------------------------------------------------

/** The table's own CDF at 1 − μ = t, from its nodes and pdf only (not its cdf column). */
function tableCdf(table: PhaseTable, t: number): number {
  let sum = 0;
  for (let k = 0; k + 1 < table.oneMinusMu.length; k++) {
    const t0 = table.oneMinusMu[k]!;
    const t1 = table.oneMinusMu[k + 1]!;
    if (t <= t0) break;
    const upper = Math.min(t, t1);
    const slope = t1 > t0 ? (table.pdf[k + 1]! - table.pdf[k]!) / (t1 - t0) : 0;
    const dt = upper - t0;
    sum += 2 * Math.PI * (table.pdf[k]! * dt + 0.5 * slope * dt * dt);
  }
  return sum;
}

const BINS = 100;
const TABLE_CASES = [
  { name: 'fog droplet x = 10, m = 1.33', x: 10, m: index(1.33) },
  { name: 'soot x = 3, m = 1.75 + 0.44i', x: 3, m: index(1.75, 0.44) },
  { name: 'cloud droplet x = 500, m = 1.33', x: 500, m: index(1.33) },
] as const;
const ALPHA = 0.01 / TABLE_CASES.length;

describe('tabulated phase function (twins of shaders/mie.wesl)', () => {
  it('the table interpolates the series at its nodes and is within 1e-3 of it between them (x = 10)', () => {
    const m = index(1.33);
    const table = mieTabulatePhase(10, m);
    const c = mieCoefficients(10, m);
    const e = mieEfficienciesFromCoefficients(c);
    expect(Math.abs(table.normalization - 1)).toBeLessThan(1e-4);
    const angles = phaseTableAngles();
    for (const k of [0, 5, 100, 300, 511]) {
      const mu = Math.cos(angles[k]!);
      expect(phaseTabulatedEval(table, mu)).toBeCloseTo(table.pdf[k]!, 12);
      const midAngle = (angles[k]! + angles[k + 1]!) / 2;
      const exact = miePhaseValues(c, e.qSca, [Math.cos(midAngle)])[0]!;
      expect(Math.abs(phaseTabulatedEval(table, Math.cos(midAngle)) / exact - 1)).toBeLessThan(
        1e-3,
      );
    }
  });

  it('its mean cosine is g of the series within the tabulation error (x = 10: 1e-4; x = 500: 1e-3, cell averages)', () => {
    for (const [x, bound] of [
      [10, 1e-4],
      [500, 2e-3],
    ] as const) {
      const table = mieTabulatePhase(x, index(1.33));
      const meanCosine = integrateSphere((mu) => mu * phaseTabulatedEval(table, mu), 4096);
      expect(Math.abs(meanCosine - mieEfficiencies(x, index(1.33)).g)).toBeLessThan(bound);
    }
  });

  it('ξ = 0 samples μ = 1 and ξ = 1 samples μ = −1 exactly; a zero-density stretch is never sampled', () => {
    const table = mieTabulatePhase(10, index(1.33));
    expect(phaseTabulatedSampleMu(table, 0).mu).toBe(1);
    expect(phaseTabulatedSampleMu(table, 1).mu).toBe(-1);
    // A table with no density between 60° and 120°.
    const angles = phaseTableAngles(64);
    const values = Array.from(angles, (theta) =>
      theta > Math.PI / 3 && theta < (2 * Math.PI) / 3 ? 0 : 1,
    );
    const gapped = phaseTableFromValues(angles, values);
    const zeroNodes = [...angles.keys()].filter((k) => values[k] === 0);
    const gapStart = Math.cos(angles[zeroNodes[0]!]!);
    const gapEnd = Math.cos(angles[zeroNodes[zeroNodes.length - 1]!]!);
    for (let i = 0; i <= 1000; i++) {
      const { mu } = phaseTabulatedSampleMu(gapped, i / 1000);
      expect(mu < gapStart && mu > gapEnd).toBe(false);
    }
  });

  it('fast-check: μ ∈ [−1, 1], the complements add to 2, and the sample’s pdf is the table at it', () => {
    const table = mieTabulatePhase(30, index(1.33));
    fc.assert(
      fc.property(
        fc.double({ min: 0, max: 1, noNaN: true }),
        fc.double({ min: 0, max: 1, maxExcluded: true, noNaN: true }),
        (u0, u1) => {
          const s = phaseTabulatedSampleMu(table, u0);
          const direction = phaseTabulatedSample(table, [0, 0, 1], [u0, u1]);
          return (
            s.mu >= -1 &&
            s.mu <= 1 &&
            Math.abs(s.oneMinusMu + s.onePlusMu - 2) < 1e-12 &&
            Math.abs(direction.pdf - phaseTabulatedEvalTerms(table, s.oneMinusMu, s.onePlusMu)) ===
              0 &&
            Math.abs(-direction.wi[2] - s.mu) < 1e-12
          );
        },
      ),
    );
  });

  const SAMPLES = 100_000;
  for (const c of TABLE_CASES) {
    it(`${c.name}: ${SAMPLES} samples match the table's density (chi-square, ${BINS} equiprobable bins, α = 0.01/${TABLE_CASES.length})`, () => {
      const table = mieTabulatePhase(c.x, c.m);
      const bins = new Array<number>(BINS).fill(0);
      for (let i = 0; i < SAMPLES; i++) {
        const state = { value: rngSeed(i, 21) };
        const s = phaseTabulatedSampleMu(table, rngNextFloat(state));
        const bin = Math.min(BINS - 1, Math.floor(tableCdf(table, s.oneMinusMu) * BINS));
        bins[bin] = (bins[bin] ?? 0) + 1;
      }
      const expected = SAMPLES / BINS;
      const statistic = bins.reduce((sum, count) => sum + (count - expected) ** 2 / expected, 0);
      expect(chiSquareSurvival(statistic, BINS - 1)).toBeGreaterThan(ALPHA);
    });
  }

  it('the chi-square test fails a sampler of the wrong table (HG-like x = 10 samples binned by x = 30)', () => {
    const drawn = mieTabulatePhase(10, index(1.33));
    const binned = mieTabulatePhase(30, index(1.33));
    const bins = new Array<number>(BINS).fill(0);
    for (let i = 0; i < 20_000; i++) {
      const state = { value: rngSeed(i, 22) };
      const s = phaseTabulatedSampleMu(drawn, rngNextFloat(state));
      const bin = Math.min(BINS - 1, Math.floor(tableCdf(binned, s.oneMinusMu) * BINS));
      bins[bin] = (bins[bin] ?? 0) + 1;
    }
    const expected = 20_000 / BINS;
    const statistic = bins.reduce((sum, count) => sum + (count - expected) ** 2 / expected, 0);
    expect(chiSquareSurvival(statistic, BINS - 1)).toBeLessThan(1e-6);
  });
});
