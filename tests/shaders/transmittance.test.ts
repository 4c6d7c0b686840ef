// WGSL transmittance module vs its float64 twin (physics.md §1), over tables
// that include the hard cases: σt = 0, thickness 0, σt·d up to 1e6, results in
// the subnormal range.
import { describeShaderFunction, type Tolerance } from '../support/shaderHarness.ts';
import {
  opticalThicknessGrid1D,
  opticalThicknessHomogeneous,
  opticalThicknessSine,
  transmittanceFromOpticalThickness,
  transmittanceHomogeneous,
} from '../../src/reference/transmittance.ts';
import { F32_MAX, F32_MIN_NORMAL } from '../support/f32.ts';

// exp(x) is accurate to 3 + 2|x| ULP in WGSL (spec, "Floating Point Accuracy"):
// 2e-5 relative covers |x| ≤ 100 (≈ 200 ULP ≈ 1.2e-5) plus the half-ULP rounding of
// τ = σt·d amplified by τ. Below the smallest normal the GPU may flush to zero,
// hence the absolute 2^-126.
const EXP_TOLERANCE: Tolerance = {
  relative: 2e-5,
  absolute: F32_MIN_NORMAL,
  reason: 'WGSL exp: 3+2|x| ULP; subnormals may flush to 0',
};

describeShaderFunction({
  module: 'transmittance',
  fn: 'transmittanceFromOpticalThickness',
  args: ['f32'],
  result: 'f32',
  twin: transmittanceFromOpticalThickness,
  tolerance: EXP_TOLERANCE,
  cases: [
    { name: 'τ = 0 is fully transparent', args: [0], expected: 1 },
    { name: 'τ = 1 gives 1/e', args: [1], expected: 0.36787944117144233 },
    { name: 'τ = 1e-7 (thin)', args: [1e-7] },
    { name: 'τ = 10', args: [10] },
    { name: 'τ = 50', args: [50] },
    { name: 'τ = 87 (just above the smallest normal)', args: [87] },
    { name: 'τ = 95: result is subnormal, may flush to 0', args: [95] },
    { name: 'τ = 103.9 (last subnormals)', args: [103.9] },
    { name: 'τ = 104 rounds to 0 (physics.md §1.2)', args: [104], expected: 0 },
    { name: 'τ = 1e6 (hard case 10)', args: [1e6], expected: 0 },
    { name: 'τ = 3.4e38 (largest f32)', args: [3.4e38], expected: 0 },
    { name: 'negative τ is clamped to 0: T = 1, never > 1', args: [-5], expected: 1 },
  ],
});

describeShaderFunction({
  module: 'transmittance',
  fn: 'opticalThicknessHomogeneous',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: opticalThicknessHomogeneous,
  tolerance: { ulps: 1, reason: 'one f32 multiplication: 0.5 ULP' },
  cases: [
    { name: 'σt = 0', args: [0, 5], expected: 0 },
    { name: 'd = 0', args: [3, 0], expected: 0 },
    { name: 'σt = 1e6, d = 1e-6 (hard case 11)', args: [1e6, 1e-6] },
    { name: 'σt = 0.7, d = 3.3', args: [0.7, 3.3] },
    { name: 'negative σt is clamped', args: [-1, 2], expected: 0 },
    { name: 'negative d is clamped', args: [1, -2], expected: 0 },
    {
      name: 'f32 max × f32 max stays finite: each factor is clamped to 1e18',
      args: [F32_MAX, F32_MAX],
      tolerance: { relative: 1e-6, reason: 'f32(1e18)² vs the float64 1e36: 2 roundings' },
    },
  ],
});

describeShaderFunction({
  module: 'transmittance',
  fn: 'transmittanceHomogeneous',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: transmittanceHomogeneous,
  tolerance: EXP_TOLERANCE,
  cases: [
    { name: 'σt = 0: T = 1', args: [0, 10], expected: 1 },
    { name: 'thickness 0: T = 1', args: [5, 0], expected: 1 },
    { name: "Beer's law σt = 1, d = 1", args: [1, 1], expected: 0.36787944117144233 },
    { name: 'σt = 0.5, d = 2', args: [0.5, 2], expected: 0.36787944117144233 },
    {
      name: 'σt = 3, d = 1 (linearized step would give −2)',
      args: [3, 1],
      expected: 0.049787068367863944,
    },
    { name: 'σt = 10, d = 1', args: [10, 1], expected: 4.5399929762484854e-5 },
    { name: 'σt = 1e6, d = 1e-6 (hard case 11)', args: [1e6, 1e-6], expected: 0.36787944117144233 },
    {
      name: 'σt = 1e6, d = 1: underflows to exactly 0 (hard case 10)',
      args: [1e6, 1],
      expected: 0,
    },
    { name: 'σt·d = 90: subnormal result', args: [9, 10] },
    { name: 'σt = 1e-6, d = 1e-3 (almost transparent)', args: [1e-6, 1e-3] },
    { name: 'σt = 1e30, d = 1e30 (product overflows f32)', args: [1e30, 1e30], expected: 0 },
  ],
});

describeShaderFunction({
  module: 'transmittance',
  fn: 'opticalThicknessSine',
  args: ['f32', 'f32', 'f32', 'f32', 'f32', 'f32'],
  result: 'f32',
  twin: opticalThicknessSine,
  // WGSL allows sin an absolute error of 2^-11 ≈ 4.9e-4 on [-π, π] (spec, "Floating
  // Point Accuracy"), and SwiftShader uses it: the oscillating term 2a·sin·sin/k
  // then carries up to ≈ 2·2^-11·a/k·σ0 absolute, i.e. a few 1e-4 of τ.
  tolerance: { relative: 5e-4, absolute: 1e-6, reason: 'WGSL sin: absolute error up to 2^-11' },
  cases: [
    { name: 'amplitude 0 reduces to σ0·L', args: [2, 0, 3, 0, 0, 1.5], expected: 3 },
    {
      name: 'chapter 2 profile, σ̄ = 1, [0, 1]',
      args: [1, 0.8, 3, 0, 0, 1],
      expected: 1.5306637290758394,
    },
    { name: 'chapter 2 profile, σ̄ = 1, [1, 2]', args: [1, 0.8, 3, 0, 1, 2] },
    { name: 'short segment [1, 1 + 1e-4] does not cancel', args: [1, 0.8, 3, 0, 1, 1.0001] },
    { name: 'empty segment s1 = s0', args: [1, 0.8, 3, 0, 1, 1], expected: 0 },
    { name: 'reversed segment gives 0', args: [1, 0.8, 3, 0, 2, 1], expected: 0 },
    { name: 'frequency 0 is constant σ0(1 + a sin φ)', args: [1, 0.5, 0, 1, 0, 2] },
    {
      name: 'amplitude 1: σt touches 0 but τ ≥ 0',
      args: [1, 1, 3, -1.5707964, 0, 0.01],
      // τ ≈ 1.5e-6 is far below the sin error: bound it by σ0·a·L·2·2^-11 ≈ 1e-5 absolute.
      tolerance: {
        absolute: 1e-5,
        reason: 'σ0·a·L·2^-10: WGSL sin error on a nearly empty segment',
      },
    },
    { name: 'amplitude > 1 is clamped to 1', args: [1, 3, 3, 0, 0, 2] },
    { name: 'large σ0 = 1e6', args: [1e6, 0.8, 3, 0, 0, 1] },
  ],
});

const LAYERS = [0.5, 1.5, 0.8, 1.2, 2, 0.2, 1, 0.8, 0, 0, 0, 0, 0, 0, 0, 0];
const ZERO_GRID = new Array<number>(16).fill(0);

describeShaderFunction({
  module: 'transmittance',
  fn: 'opticalThicknessGrid1D',
  args: ['f32[16]', 'u32', 'f32', 'f32', 'f32'],
  result: 'f32',
  twin: opticalThicknessGrid1D,
  tolerance: { relative: 1e-6, absolute: 1e-7, reason: 'a sum of ≤ 16 f32 products: ≤ 16 ULP' },
  cases: [
    { name: 'whole grid: Σ σ_i h', args: [LAYERS, 8, 0.25, 0, 2], expected: 2 },
    { name: 'inside one cell', args: [LAYERS, 8, 0.25, 0.3, 0.4], expected: 0.15 },
    { name: 'across cell edges', args: [LAYERS, 8, 0.25, 0.1, 1.3] },
    { name: 'beyond the last cell σt = 0', args: [LAYERS, 8, 0.25, 1.9, 5], expected: 0.08 },
    { name: 'all-zero grid', args: [ZERO_GRID, 16, 1, 0, 16], expected: 0 },
    { name: 'cell size 0 gives 0, no division', args: [LAYERS, 8, 0, 0, 1], expected: 0 },
    { name: 'cell count above the maximum is clamped', args: [LAYERS, 99, 0.25, 0, 4] },
    { name: 'empty segment', args: [LAYERS, 8, 0.25, 1, 1], expected: 0 },
  ],
});
