// Hard cases of physics.md §9 that concern transmittance and random numbers, run
// against both implementations, plus a fuzz over f32 extremes: never NaN, never
// Inf, never T < 0 or T > 1.
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { describeShaderFunction, evaluateTable } from '../support/shaderHarness.ts';
import {
  opticalThicknessSine,
  transmittanceFromOpticalThickness,
  transmittanceHomogeneous,
} from '../../src/reference/transmittance.ts';
import { u32ToUnitFloat } from '../../src/reference/rng.ts';
import {
  F32_MAX,
  F32_MIN_NORMAL,
  F32_MIN_SUBNORMAL,
  ONE_MINUS_EPSILON_F32,
} from '../support/f32.ts';

const EXP = {
  relative: 2e-5,
  absolute: F32_MIN_NORMAL,
  reason: 'WGSL exp: 3+2|x| ULP; subnormals may flush to 0',
};

describeShaderFunction({
  module: 'transmittance',
  fn: 'transmittanceHomogeneous',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: transmittanceHomogeneous,
  tolerance: EXP,
  cases: [
    { name: '§9 row 10: σt = 1e6, d = 1 → T = 0 exactly', args: [1e6, 1], expected: 0 },
    {
      name: '§9 row 11: σt = 1e6, d = 1e-6 → e^-1',
      args: [1e6, 1e-6],
      expected: 0.36787944117144233,
    },
    {
      name: '§9 row 17: σΔs = 1.5 → exact factor e^-1.5 (the linear one is −0.5)',
      args: [1.5, 1],
      expected: 0.22313016014842982,
    },
    { name: 'σt = 0 → T = 1 (no medium)', args: [0, 1e30], expected: 1 },
    { name: 'd = 0 → T = 1', args: [F32_MAX, 0], expected: 1 },
    { name: 'τ just below underflow (103.9) stays ≥ 0', args: [103.9, 1] },
    { name: 'subnormal σt', args: [F32_MIN_SUBNORMAL, 1], expected: 1 },
    {
      name: 'largest f32 σt and d (τ overflows to Inf in f32)',
      args: [F32_MAX, F32_MAX],
      expected: 0,
    },
  ],
});

describeShaderFunction({
  module: 'rng',
  fn: 'u32ToUnitFloat',
  args: ['u32'],
  result: 'f32',
  twin: u32ToUnitFloat,
  tolerance: { ulps: 0, reason: 'exact: 24 bits times a power of two' },
  cases: [
    {
      name: '§9 row 16: ξ from 0xFFFFFFFF is 1 − 2^-24, so −ln(1 − ξ) = 16.64 is finite',
      args: [0xffffffff],
      expected: ONE_MINUS_EPSILON_F32,
    },
  ],
});

describe('fuzz: WGSL transmittance over f32 extremes never leaves [0, 1]', () => {
  const extremes = fc.oneof(
    fc.constantFrom(
      0,
      F32_MIN_SUBNORMAL,
      F32_MIN_NORMAL,
      1 - 2 ** -24,
      1,
      87.3365,
      103.9721,
      1e6,
      F32_MAX,
      -0,
      -1,
      -F32_MAX,
    ),
    fc.float({ noNaN: true, noDefaultInfinity: true }),
  );
  const samples = fc.sample(fc.tuple(extremes, extremes), { numRuns: 512, seed: 20261123 });

  it('transmittanceHomogeneous: 512 fuzzed (σt, d) pairs', async () => {
    const outcomes = await evaluateTable({
      module: 'transmittance',
      fn: 'transmittanceHomogeneous',
      args: ['f32', 'f32'],
      result: 'f32',
      twin: transmittanceHomogeneous,
      tolerance: EXP,
      cases: samples.map(([s, d], i) => ({ name: `fuzz ${i}`, args: [s, d] })),
    });
    for (const [i, outcome] of outcomes.entries()) {
      const gpu = outcome.gpu[0] ?? NaN;
      expect(Number.isFinite(gpu), `case ${i}: ${samples[i]?.join(', ')} → ${gpu}`).toBe(true);
      expect(gpu).toBeGreaterThanOrEqual(0);
      expect(gpu).toBeLessThanOrEqual(1);
    }
  });

  it('transmittanceFromOpticalThickness and opticalThicknessSine: fuzzed inputs stay finite and in range', async () => {
    const taus = fc.sample(extremes, { numRuns: 256, seed: 7 });
    const outcomes = await evaluateTable({
      module: 'transmittance',
      fn: 'transmittanceFromOpticalThickness',
      args: ['f32'],
      result: 'f32',
      twin: transmittanceFromOpticalThickness,
      tolerance: EXP,
      cases: taus.map((tau, i) => ({ name: `fuzz ${i}`, args: [tau] })),
    });
    for (const outcome of outcomes) {
      const gpu = outcome.gpu[0] ?? NaN;
      expect(gpu >= 0 && gpu <= 1).toBe(true);
    }
    const sines = fc.sample(fc.tuple(extremes, extremes, extremes), { numRuns: 256, seed: 11 });
    const sineOutcomes = await evaluateTable({
      module: 'transmittance',
      fn: 'opticalThicknessSine',
      args: ['f32', 'f32', 'f32', 'f32', 'f32', 'f32'],
      result: 'f32',
      twin: opticalThicknessSine,
      tolerance: EXP,
      // Bounded frequency and segment so that the f32 result is representable.
      cases: sines.map(([sigma, amplitude, s], i) => ({
        name: `fuzz ${i}`,
        args: [
          Math.min(Math.abs(sigma), 1e6),
          amplitude,
          3,
          0,
          Math.min(Math.abs(s), 1e3),
          Math.min(Math.abs(s), 1e3) + 1,
        ],
      })),
    });
    for (const outcome of sineOutcomes) {
      const gpu = outcome.gpu[0] ?? NaN;
      expect(Number.isFinite(gpu) && gpu >= 0).toBe(true);
    }
  });
});
