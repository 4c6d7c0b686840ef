// Hard cases of physics.md §9 for single scattering (row 18 in the slab formula,
// rows 10–11 in the shadow and view rays) and equiangular sampling (angles at
// ±π/2, a light on the ray, an empty segment), in both implementations; then a
// fuzz over f32 extremes: never NaN or Inf, radiance and pdf ≥ 0, T ∈ [0, 1].
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { gridMedium, homogeneousMedium, sineMedium } from '../../src/reference/medium.ts';
import { MARCH_MAX_STEPS, MARCH_MIDPOINT, marchStepCount } from '../../src/reference/raymarch.ts';
import {
  equiangularPdf,
  equiangularSample,
  singleScatterHomogeneousSlab,
} from '../../src/reference/scatter.ts';
import { describeShaderFunction, evaluateTable } from '../support/shaderHarness.ts';
import { singleScatterArgs, singleScatterTable } from '../support/marchTables.ts';
import { F32_MAX, F32_MIN_NORMAL, F32_MIN_SUBNORMAL } from '../support/f32.ts';

describeShaderFunction({
  module: 'scatter',
  fn: 'singleScatterHomogeneousSlab',
  args: ['f32', 'f32', 'f32', 'f32', 'f32', 'f32', 'f32'],
  result: 'f32',
  twin: singleScatterHomogeneousSlab,
  tolerance: { relative: 2e-6, absolute: F32_MIN_NORMAL, reason: '≤ 20 ULP of f32 operations' },
  cases: [
    {
      name: '§9 row 18: thin slab, σt(1 + b)L = 1e-7 → σs·p·E·L·(1 − 5e-8) (naive f32: −40%)',
      args: [1e-7, 0, 1, 1, 0, 0, 1],
      expected: 1e-7 * (1 - 5e-8),
    },
    {
      name: '§9 row 18: σt(1 + b)L = 1e-9 → σs·p·E·L (naive f32: 0)',
      args: [1e-9, 0, 1, 1, 0, 0, 1],
      expected: 1e-9,
    },
    { name: '§9 row 10: σt = 1e6, a = 1 → exactly 0', args: [1e6, 0, 1, 1, 1, 0, 1], expected: 0 },
    {
      name: '§9 row 11: σt = 1e6, a = 1e-6, L = 1e-6, b = 0 → e^{-1}(1 − e^{-1})/σt·σs',
      args: [1e6, 0, 1, 1, 1e-6, 0, 1e-6],
      expected: Math.exp(-1) * (1 - Math.exp(-1)),
    },
    { name: 'σt = 0 (no medium): 0, no division', args: [0, 0, 1, 1, 1, 1, 1], expected: 0 },
    { name: 'subnormal σs: finite, ≥ 0', args: [F32_MIN_SUBNORMAL, 0, 1, 1, 0, 0, 1] },
  ],
});

describeShaderFunction({
  module: 'scatter',
  fn: 'equiangularSample',
  args: ['f32', 'f32', 'f32', 'f32'],
  result: 'vec2f',
  twin: equiangularSample,
  // Near θ = ±π/2 tan is ill-conditioned (f32 θ and WGSL's sin/cos errors of 2^-11
  // against cos θ ≈ 1e-7 move t by ~20% and the pdf ∝ 1/t² by ~50%): the harness
  // checks finiteness here, and the test below the sign and size of t.
  tolerance: {
    relative: 1,
    reason: 'tan at its pole: only finiteness, sign and magnitude are meaningful',
  },
  cases: [
    {
      name: 'θb = f32(π/2) = 1.5707964 (past π/2) is clamped below it: t > 0, finite',
      args: [1, 0, 1.5707964, 1],
    },
    { name: 'θa = −f32(π/2) is clamped: t < 0, finite', args: [1, -1.5707964, 0, 0] },
    { name: 'θ beyond ±π/2 (3, −3) is clamped', args: [2, -3, 3, 0.999] },
    {
      name: 'h = 0 (light on the ray): pdf 0, t = 0',
      args: [0, -1, 1, 0.5],
      expected: [0, 0],
    },
    { name: 'h = f32 max: finite', args: [F32_MAX, -1, 1, 0.75] },
  ],
});

describe('equiangular samples at θ = ±π/2 keep their sign (f32(π/2) lies past the pole, where tan < 0)', () => {
  it('t ≫ 0 for θ → +π/2 and t ≪ 0 for θ → −π/2, on the GPU and the twin', async () => {
    const outcomes = await evaluateTable({
      module: 'scatter',
      fn: 'equiangularSample',
      args: ['f32', 'f32', 'f32', 'f32'],
      result: 'vec2f',
      twin: equiangularSample,
      tolerance: { relative: 1, reason: 'sign and magnitude only' },
      cases: [
        { name: '+π/2', args: [1, 0, 1.5707964, 1] },
        { name: '−π/2', args: [1, -1.5707964, 0, 0] },
      ],
    });
    const [up, down] = outcomes;
    for (const values of [up?.gpu, up?.twin]) expect(values?.[0]).toBeGreaterThan(1e6);
    for (const values of [down?.gpu, down?.twin]) expect(values?.[0]).toBeLessThan(-1e6);
  });
});

describeShaderFunction({
  module: 'scatter',
  fn: 'equiangularPdf',
  args: ['f32', 'f32', 'f32', 'f32'],
  result: 'f32',
  twin: equiangularPdf,
  tolerance: {
    relative: 1e-6,
    absolute: F32_MIN_NORMAL,
    reason: '≤ 12 ULP of divisions and products',
  },
  cases: [
    { name: 'light on the ray (h = 0): 0, not Inf', args: [0, -1, 1, 0], expected: 0 },
    { name: 'empty segment θa = θb: 0, not Inf', args: [1, 0.2, 0.2, 0], expected: 0 },
    {
      name: 'h·Δθ = 1e-39 < 2^-126 (pdf past f32): degenerate, 0',
      args: [1e-39, -1, 0, 0],
      expected: 0,
    },
    {
      name: 'h = 1e-31, Δθ = 1, t = 0: 1e31 (no length threshold, issue 20)',
      args: [1e-31, -1, 0, 0],
      expected: 1e31,
    },
    { name: 'h = 1e-20, t = 0: 1/(h·Δθ) = 3.2e19, finite', args: [1e-20, -1.5, 1.5, 0] },
    { name: 't = f32 max: clamped to 1e36, tiny but finite', args: [1, -1, 1, F32_MAX] },
    { name: 'negative h is 0: pdf 0', args: [-1, -1, 1, 0], expected: 0 },
  ],
});

describe('fuzz: single scattering and equiangular sampling stay finite and non-negative', () => {
  const extremes = fc.oneof(
    fc.constantFrom(
      0,
      F32_MIN_SUBNORMAL,
      F32_MIN_NORMAL,
      1e-9,
      1,
      1e6,
      1e30,
      F32_MAX,
      -1,
      -F32_MAX,
    ),
    fc.float({ noNaN: true, noDefaultInfinity: true }),
  );

  it('singleScatterHomogeneousSlab: 256 fuzzed 7-tuples of f32 extremes', async () => {
    const samples = fc.sample(fc.array(extremes, { minLength: 7, maxLength: 7 }), {
      numRuns: 256,
      seed: 5,
    });
    const outcomes = await evaluateTable({
      module: 'scatter',
      fn: 'singleScatterHomogeneousSlab',
      args: ['f32', 'f32', 'f32', 'f32', 'f32', 'f32', 'f32'],
      result: 'f32',
      twin: singleScatterHomogeneousSlab,
      tolerance: { relative: 1, reason: 'invariants only' },
      cases: samples.map((args, i) => ({ name: `fuzz ${i}`, args })),
    });
    outcomes.forEach((outcome, i) => {
      for (const value of [outcome.gpu[0] ?? NaN, outcome.twin[0] ?? NaN]) {
        expect(Number.isFinite(value), `case ${i}: ${samples[i]?.join(', ')} → ${value}`).toBe(
          true,
        );
        expect(value).toBeGreaterThanOrEqual(0);
      }
    });
  });

  it('equiangularSample and equiangularPdf: 256 fuzzed (h, θa, θb, ξ/t), t finite, pdf finite ≥ 0', async () => {
    const samples = fc.sample(
      fc.tuple(
        extremes,
        extremes,
        extremes,
        fc.oneof(fc.double({ min: 0, max: 1, noNaN: true }), extremes),
      ),
      { numRuns: 256, seed: 6 },
    );
    for (const [fn, twin] of [
      ['equiangularSample', equiangularSample],
      ['equiangularPdf', equiangularPdf],
    ] as const) {
      const outcomes = await evaluateTable({
        module: 'scatter',
        fn,
        args: ['f32', 'f32', 'f32', 'f32'],
        result: fn === 'equiangularSample' ? 'vec2f' : 'f32',
        twin,
        tolerance: { relative: 1, reason: 'invariants only' },
        cases: samples.map((args, i) => ({ name: `fuzz ${i}`, args })),
      });
      outcomes.forEach((outcome, i) => {
        for (const values of [outcome.gpu, outcome.twin]) {
          const label = `${fn} case ${i}: ${samples[i]?.join(', ')} → ${values.join(', ')}`;
          expect(values.every(Number.isFinite), label).toBe(true);
          expect(values[values.length - 1], label).toBeGreaterThanOrEqual(0);
        }
      });
    }
  });

  it('singleScatterMarched: 96 fuzzed media (σt ≤ 1e6), steps up to and beyond the cap', async () => {
    const sigma = fc.oneof(
      fc.constantFrom(0, 1e-9, 1, 1e6),
      fc.double({ min: 0, max: 1e6, noNaN: true }),
    );
    const medium = fc.oneof(
      sigma.map(homogeneousMedium),
      fc
        .tuple(sigma, fc.double({ min: 0, max: 1, noNaN: true }))
        .map(([s, a]) => sineMedium(s, a, 3)),
      fc.array(sigma, { minLength: 1, maxLength: 16 }).map((cells) => gridMedium(cells, 0.25)),
    );
    const samples = fc.sample(
      fc.tuple(
        medium,
        fc.double({ min: 0, max: 1, noNaN: true }), // albedo
        fc.double({ min: 0, max: 100, noNaN: true }), // phase
        fc.double({ min: 0, max: 1e3, noNaN: true }), // irradiance
        fc.double({ min: 0, max: 1e3, noNaN: true }), // a
        fc.double({ min: 0, max: 1e3, noNaN: true }), // b
        fc.oneof(fc.constantFrom(0, 1e-6, 1), fc.double({ min: 0, max: 1e3, noNaN: true })), // length
        fc.oneof(
          fc.constantFrom(0, MARCH_MAX_STEPS, MARCH_MAX_STEPS + 1),
          fc.integer({ min: 0, max: 5000 }),
        ),
        fc.integer({ min: 0, max: 5 }),
        fc.integer({ min: 0, max: 0xffffffff }),
      ),
      { numRuns: 96, seed: 7 },
    );
    // f32 extremes: σt, a and b from 0 to the largest f32; phase, E and L at the largest.
    const extremeCases = [0, 1, 1e30, F32_MAX].map((value): (typeof samples)[number] => [
      homogeneousMedium(value),
      1,
      F32_MAX,
      F32_MAX,
      value,
      value,
      F32_MAX,
      64,
      MARCH_MIDPOINT,
      0,
    ]);
    const all = [...samples, ...extremeCases];
    const outcomes = await evaluateTable(
      singleScatterTable(
        all.map((args, i) => ({ name: `fuzz ${i}`, args: singleScatterArgs(...args) })),
        { relative: 1, reason: 'invariants only' },
      ),
    );
    outcomes.forEach((outcome, i) => {
      const steps = all[i]?.[7] ?? 0;
      for (const [radiance, transmittance, taken] of [outcome.gpu, outcome.twin]) {
        const label = `case ${i}: GPU ${outcome.gpu.join(', ')}; twin ${outcome.twin.join(', ')}`;
        expect(Number.isFinite(radiance) && Number.isFinite(transmittance), label).toBe(true);
        expect(radiance, label).toBeGreaterThanOrEqual(0);
        expect(transmittance, label).toBeGreaterThanOrEqual(0);
        expect(transmittance, label).toBeLessThanOrEqual(1);
        expect(taken, label).toBe(marchStepCount(steps));
      }
    });
  });
});
