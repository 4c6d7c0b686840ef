// Hard cases of physics.md §9 that concern ray marching (rows 10, 11, 17, 18, 27),
// each run in both implementations, and a fuzz over media up to σt = 1e6, steps up
// to and beyond the cap, and f32 extremes: never NaN or Inf, T ∈ [0, 1], radiance ≥ 0
// (emission ≥ 0), and the reported step count is marchStepCount(steps).
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { gridMedium, homogeneousMedium, sineMedium } from '../../src/reference/medium.ts';
import {
  MARCH_JITTERED_RAY,
  MARCH_LEFT,
  MARCH_MAX_STEPS,
  MARCH_MIDPOINT,
  marchStepCount,
  oneMinusExpOverX,
  raymarchEmissionAbsorption,
  raymarchEmissionRiemann,
  raymarchLinearized,
} from '../../src/reference/raymarch.ts';
import { rngSeed } from '../../src/reference/rng.ts';
import {
  describeShaderFunction,
  evaluateTable,
  type ShaderCase,
} from '../support/shaderHarness.ts';
import {
  marchArgs,
  marchTable,
  type March,
  opticalDepthArgs,
  opticalDepthTable,
} from '../support/marchTables.ts';
import { F32_MAX, F32_MIN_NORMAL, F32_MIN_SUBNORMAL } from '../support/f32.ts';

// Homogeneous media only below: the f32 budget is n steps of a few ULP (no sin).
const STEP_BUDGET = {
  relative: 2e-5,
  absolute: F32_MIN_NORMAL,
  reason: '≤ 64 f32 steps: (4n + 2τ + 16)·2^-24; exp 3 + 2|x| ULP',
};

describeShaderFunction(
  marchTable(
    'raymarchLinearized',
    raymarchLinearized,
    [
      {
        name: '§9 row 17: σΔs = 1.5, linear factor −0.5 → clamped: T = 0, one clamp counted',
        args: marchArgs(homogeneousMedium(1.5), 0, 0, 0, 0, 1, 1, MARCH_LEFT),
        expected: [0, 0, 1, 1],
      },
      {
        name: '§9 row 17: σΔs = 2.5, |factor| > 1 (would grow): T = 0, one clamp',
        args: marchArgs(homogeneousMedium(2.5), 0, 0, 0, 0, 1, 1, MARCH_LEFT),
        expected: [0, 0, 1, 1],
      },
      {
        name: '§9 row 10: σt = 1e6, 64 steps (unclamped product 2.5e268): T = 0, 64 clamps',
        args: marchArgs(homogeneousMedium(1e6), 1, 0, 0, 1, 1, 64, MARCH_MIDPOINT),
        expected: [1, 0, 64, 64],
      },
    ],
    STEP_BUDGET,
  ),
);

describeShaderFunction(
  marchTable(
    'raymarchEmissionAbsorption',
    raymarchEmissionAbsorption,
    [
      {
        name: '§9 row 17: σΔs = 1.5, the exact step gives e^{−1.5} = 0.22313',
        args: marchArgs(homogeneousMedium(1.5), 0, 0, 0, 0, 1, 1, MARCH_LEFT),
        expected: [0, 0.22313016014842982, 1, 0],
      },
      {
        name: '§9 row 10: σt = 1e6, d = 1 → T = 0 exactly, L = Le of the first sample',
        args: marchArgs(homogeneousMedium(1e6), 1, 0, 0, 5, 1, 64, MARCH_MIDPOINT),
        expected: [1, 0, 64, 0],
      },
      {
        name: '§9 row 11: σt = 1e6, d = 1e-6 → T = e^{-1}',
        args: marchArgs(homogeneousMedium(1e6), 0, 0, 0, 0, 1e-6, 7, MARCH_LEFT),
        expected: [0, Math.exp(-1), 7, 0],
      },
      {
        name: '§9 row 18 inside a march: σt·h = 1e-9, L = σt·d·Le = 1e-8 (naive opacity: 0)',
        args: marchArgs(homogeneousMedium(1e-9), 1, 0, 0, 0, 10, 1, MARCH_LEFT),
        expected: [1e-8, 1, 1, 0],
      },
      {
        name: 'steps = 2^32 − 1 is capped at 4096 and reported',
        args: marchArgs(homogeneousMedium(1), 1, 0, 0, 0, 1, 0xffffffff, MARCH_LEFT),
        expected: [1 - Math.exp(-1), Math.exp(-1), MARCH_MAX_STEPS, 0],
        tolerance: {
          relative: 4e-4,
          reason: '4096 f32 steps: (4n + 2τ + 16)·2^-24 ≈ 1e-3 worst case, observed ≪',
        },
      },
    ],
    STEP_BUDGET,
  ),
);

describeShaderFunction({
  module: 'raymarch',
  fn: 'oneMinusExpOverX',
  args: ['f32'],
  result: 'f32',
  twin: oneMinusExpOverX,
  tolerance: { relative: 5e-7, reason: 'series ≤ 3 ULP; direct form ≤ 8 ULP at the x = 1 switch' },
  cases: [
    {
      name: '§9 row 18: x = 1e-7 → 0.99999995 (naive f32 0.596)',
      args: [1e-7],
      expected: 0.99999995,
    },
    {
      name: '§9 row 18: x = 1e-9 → 0.9999999995 (naive f32 0)',
      args: [1e-9],
      expected: 0.9999999995,
    },
    { name: 'smallest subnormal x → 1', args: [F32_MIN_SUBNORMAL], expected: 1 },
    { name: 'x = 87.34 (e^{-x} subnormal)', args: [87.34] },
  ],
});

describe('§9 row 27: jittered ray-marched transmittance with 1 sample is biased high, in both implementations', () => {
  // Exact E[exp(−τ̂)] = ∫₀¹ exp(−2σt(2ξ)) dξ = 0.172054 (quadrature; §3 prints the
  // Monte Carlo value 0.171730) against the true T = 0.134440.
  const exact = 0.17205423982172965;
  const trueT = Math.exp(-(2 - (0.5 / 3) * (Math.cos(6) - 1)));

  it('mean of exp(−τ̂) over 20 000 seeds = 0.172054 (5 SE + f32 budget) on the GPU and the twin, above T by more than that', async () => {
    const rays = 20_000;
    const medium = sineMedium(1, 0.5, 3);
    const outcomes = await evaluateTable(
      opticalDepthTable(
        Array.from({ length: rays }, (_, i) => ({
          name: `ray ${i}`,
          args: opticalDepthArgs(medium, 2, 1, MARCH_JITTERED_RAY, rngSeed(i, 27)),
        })),
        { relative: 1e-3, reason: 'unused here' },
        'transmittance',
      ),
    );
    for (const side of ['gpu', 'twin'] as const) {
      const values = outcomes.map((o) => o[side][0] ?? NaN);
      const mean = values.reduce((a, b) => a + b, 0) / rays;
      const se = Math.sqrt(values.reduce((a, v) => a + (v - mean) ** 2, 0) / (rays - 1) / rays);
      // The GPU's τ̂ carries σ0·a·2^-11·d ≈ 4.9e-4 from WGSL sin: T moves by ≤ 4.9e-4·T.
      const bound = 5 * se + (side === 'gpu' ? 4.9e-4 * exact : 0);
      expect(Math.abs(mean - exact), side).toBeLessThan(bound);
      expect(mean - trueT, side).toBeGreaterThan(bound);
    }
  });
});

describe('fuzz: every march stays finite with T ∈ [0, 1] and radiance ≥ 0, on the GPU and the twin', () => {
  const sigma = fc.oneof(
    fc.constantFrom(0, 1e-9, 1, 1e3, 1e6),
    fc.double({ min: 0, max: 1e6, noNaN: true }),
  );
  const medium = fc.oneof(
    sigma.map(homogeneousMedium),
    fc
      .tuple(
        sigma,
        fc.double({ min: 0, max: 1, noNaN: true }),
        fc.double({ min: 0, max: 50, noNaN: true }),
      )
      .map(([s, a, k]) => sineMedium(s, a, k, 0.3)),
    fc
      .tuple(
        fc.array(sigma, { minLength: 1, maxLength: 16 }),
        fc.double({ min: 1e-3, max: 10, noNaN: true }),
      )
      .map(([cells, size]) => gridMedium(cells, size)),
  );
  const marchCase = fc.tuple(
    medium,
    fc.double({ min: 0, max: 1e3, noNaN: true }), // emission0 ≥ 0
    fc.double({ min: 0, max: 10, noNaN: true }), // slope ≥ 0 so that Le ≥ 0
    fc.double({ min: 0, max: 1, noNaN: true }), // albedo
    fc.double({ min: 0, max: 1e3, noNaN: true }), // background
    fc.oneof(fc.constantFrom(0, 1e-6, 1, 100), fc.double({ min: 0, max: 1e3, noNaN: true })),
    fc.oneof(
      fc.constantFrom(0, 1, MARCH_MAX_STEPS, MARCH_MAX_STEPS + 1),
      fc.integer({ min: 0, max: 5000 }),
    ),
    fc.integer({ min: 0, max: 5 }), // scheme, including unknown values
    fc.integer({ min: 0, max: 0xffffffff }),
  );
  const samples = fc.sample(marchCase, { numRuns: 96, seed: 20261124 });

  const marches: [string, March][] = [
    ['raymarchEmissionAbsorption', raymarchEmissionAbsorption],
    ['raymarchLinearized', raymarchLinearized],
    ['raymarchEmissionRiemann', raymarchEmissionRiemann],
  ];
  for (const [fn, twin] of marches) {
    it(`${fn}: 96 fuzzed media, steps up to and beyond the cap`, async () => {
      const outcomes = await evaluateTable(
        marchTable(
          fn,
          twin,
          samples.map(([m, e0, slope, albedo, bg, d, steps, scheme, seed], i) => ({
            name: `fuzz ${i}`,
            args: marchArgs(m, e0, slope, albedo, bg, d, steps, scheme, seed),
          })),
          { relative: 1, reason: 'invariants only' },
        ),
      );
      outcomes.forEach((outcome, i) => {
        const steps = samples[i]?.[6] ?? 0;
        for (const [side, [radiance, transmittance, taken]] of [
          ['gpu', outcome.gpu],
          ['twin', outcome.twin],
        ] as const) {
          const label = `${side} case ${i}: ${JSON.stringify(samples[i])}`;
          expect(Number.isFinite(radiance) && Number.isFinite(transmittance), label).toBe(true);
          expect(radiance, label).toBeGreaterThanOrEqual(0);
          expect(transmittance, label).toBeGreaterThanOrEqual(0);
          expect(transmittance, label).toBeLessThanOrEqual(1);
          expect(taken, label).toBe(marchStepCount(steps));
        }
      });
    });
  }

  it('raymarchOpticalDepth: fuzzed media, τ̂ finite and ≥ 0', async () => {
    const outcomes = await evaluateTable(
      opticalDepthTable(
        samples.map(([m, , , , , d, steps, scheme, seed], i) => ({
          name: `fuzz ${i}`,
          args: opticalDepthArgs(m, d, steps, scheme, seed),
        })),
        { relative: 1, reason: 'invariants only' },
      ),
    );
    for (const outcome of outcomes) {
      for (const value of [outcome.gpu[0] ?? NaN, outcome.twin[0] ?? NaN]) {
        expect(Number.isFinite(value)).toBe(true);
        expect(value).toBeGreaterThanOrEqual(0);
      }
    }
  });

  it('f32 extremes (σ0, d, emission, background up to the largest f32) stay finite', async () => {
    const extremes = [0, F32_MIN_SUBNORMAL, 1, 1e6, 1e30, F32_MAX];
    const cases: ShaderCase[] = [];
    for (const sigma0 of extremes)
      for (const d of extremes)
        for (const e0 of [0, 1, F32_MAX])
          cases.push({
            name: `σ0 ${sigma0}, d ${d}, Le ${e0}`,
            args: marchArgs(
              homogeneousMedium(sigma0),
              e0,
              F32_MAX,
              0,
              F32_MAX,
              d,
              64,
              MARCH_MIDPOINT,
            ),
          });
    for (const [fn, twin] of marches) {
      const outcomes = await evaluateTable(
        marchTable(fn, twin, cases, { relative: 1, reason: 'invariants only' }),
      );
      outcomes.forEach((outcome, i) => {
        for (const [radiance, transmittance] of [outcome.gpu, outcome.twin]) {
          const label = `${fn} ${cases[i]?.name}: GPU ${outcome.gpu.join(', ')}; twin ${outcome.twin.join(', ')}`;
          expect(Number.isFinite(radiance) && Number.isFinite(transmittance), label).toBe(true);
          expect(radiance, label).toBeGreaterThanOrEqual(0);
          expect(transmittance, label).toBeGreaterThanOrEqual(0);
          expect(transmittance, label).toBeLessThanOrEqual(1);
        }
      });
    }
  });
});
