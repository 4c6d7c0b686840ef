// Hard cases found by the fuzz at f32 extremes (tests/stability/fuzz-extremes.test.ts), in both
// implementations through the table harness (Dawn and wgpu against the float64 twin, each also
// against the exact value). Each name says what the WGSL gave before the fix.
//
// - L·f(kL) with f = oneMinusExpOverX is wrong once kL passes f's input clamp at 1e36 (f = 1e-36
//   instead of 1/(kL)); the truncated exponential, its pdf, the better dipole's
//   exponentialDifferenceOverRate and the emission integral now use oneMinusExpOverRate,
//   (1 − e^{−kL})/k, and x·f(x) = 1 − e^{−x} is formed directly above x = 1.
// - −ln(1 − ξ) in f32 is 0 for ξ < 2^-25 (1 − ξ rounds to 1): free flights of length 0.
// - Quotients and norms that overflowed f32: sunRadiance, photonKernel, slabRadius; and mix's
//   a + t(b − a) with b − a overflowing in lerpWithinEndpoints.
import { describeShaderFunction } from '../support/shaderHarness.ts';
import { exponentialDifferenceOverRate } from '../../src/reference/dipole.ts';
import {
  averageComponent,
  sampleTruncatedExponential,
  truncatedExponentialPdf,
} from '../../src/reference/integrator.ts';
import { compositeStep } from '../../src/reference/inverse.ts';
import { lerpWithinEndpoints } from '../../src/reference/medium.ts';
import { photonKernel, sunRadiance } from '../../src/reference/photons.ts';
import { oneMinusExpOverRate } from '../../src/reference/raymarch.ts';
import { slabRadius } from '../../src/reference/slab.ts';
import { sampleFreeFlight, transmittanceTrackLength } from '../../src/reference/tracking.ts';
import { F32_MAX, F32_MIN_NORMAL } from '../support/f32.ts';

/** 1 − e^{-1}. */
const ONE_MINUS_E_MINUS_1 = 0.6321205588285577;

const EXP = {
  relative: 2e-6,
  absolute: F32_MIN_NORMAL,
  reason: 'f32-rounded inputs (2^-24 each), WGSL exp and log (3 + 2|x| ULP) and one division',
};

describeShaderFunction({
  module: 'raymarch',
  fn: 'oneMinusExpOverRate',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: oneMinusExpOverRate,
  tolerance: EXP,
  cases: [
    { name: 'k = L = 1e20: (1 − e^{-1e40})/k = 1e-20', args: [1e20, 1e20], expected: 1e-20 },
    { name: 'k = L = 1: 1 − e^{-1}', args: [1, 1], expected: ONE_MINUS_E_MINUS_1 },
    {
      name: 'k = 1e-30, L = 1e30: the same medium, 0.632e30',
      args: [1e-30, 1e30],
      expected: ONE_MINUS_E_MINUS_1 * 1e30,
    },
    { name: 'k = 0: L', args: [0, 5], expected: 5 },
    {
      name: 'k = 1e-7, L = 1 (thin, no cancellation): 1 − 5e-8',
      args: [1e-7, 1],
      expected: 0.99999995,
    },
    { name: 'L = F32_MAX, k = 0: F32_MAX (finite)', args: [0, F32_MAX], expected: F32_MAX },
    { name: 'negative k and L count as 0', args: [-1, -1], expected: 0 },
  ],
});

describeShaderFunction({
  module: 'dipole',
  fn: 'exponentialDifferenceOverRate',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: exponentialDifferenceOverRate,
  tolerance: EXP,
  cases: [
    {
      name: 'σ = 1e20, a = 0, b = 1e20: 1e-20 (was 1e-16)',
      args: [1e20, 0, 1e20],
      expected: 1e-20,
    },
    { name: 'σ = 1e10, a = 0, b = 1e30: 1e-10 (was 1e-6)', args: [1e10, 0, 1e30], expected: 1e-10 },
    {
      name: 'σ = F32_MAX, a = 0, b = 1.5: 1/F32_MAX (was 1.5e-36)',
      args: [F32_MAX, 0, 1.5],
      expected: 1 / F32_MAX,
    },
    { name: 'σ = 1, a = 0, b = 1: 1 − e^{-1}', args: [1, 0, 1], expected: ONE_MINUS_E_MINUS_1 },
  ],
});

describeShaderFunction({
  module: 'integrator',
  fn: 'truncatedExponentialPdf',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: truncatedExponentialPdf,
  tolerance: EXP,
  cases: [
    { name: 'k = L = 1e20, s = 0: k = 1e20 (was 1e16)', args: [1e20, 1e20, 0], expected: 1e20 },
    {
      name: 'k = 1e10, L = 1e30, s = 1e-10: k e^{-1} (was 1e6 e^{-1})',
      args: [1e10, 1e30, 1e-10],
      expected: 1e10 * Math.exp(-1),
    },
  ],
});

describeShaderFunction({
  module: 'integrator',
  fn: 'sampleTruncatedExponential',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: sampleTruncatedExponential,
  tolerance: { ...EXP, relative: 1e-5 },
  cases: [
    {
      name: 'k = 1e10, L = 1e30, u = 1e-4: −ln(1 − u)/k = 1.00005e-14 (was 1e-10)',
      args: [1e10, 1e30, 1e-4],
      expected: -Math.log1p(-Math.fround(1e-4)) / Math.fround(1e10),
    },
  ],
});

describeShaderFunction({
  module: 'inverse',
  fn: 'compositeStep',
  args: ['f32', 'f32'],
  result: 'vec4f',
  wrapper: {
    wgsl: 'fn caseUnderTest(sigma: f32, step: f32) -> vec4f {\n  return compositeStep(vec4f(0.0, 0.0, 0.0, 1.0), vec4f(sigma, 1.0, 1.0, 1.0), step);\n}',
    imports: ['compositeStep'],
  },
  twin: (sigma: number, step: number) => compositeStep([0, 0, 0, 1], [sigma, 1, 1, 1], step),
  tolerance: EXP,
  cases: [
    { name: 'σ = 1e37, h = 1: α = 1 (was 10)', args: [1e37, 1], expected: [1, 1, 1, 0] },
    { name: 'σ = 1, h = 1e37: α = 1 (was 10)', args: [1, 1e37], expected: [1, 1, 1, 0] },
    {
      name: 'σ = h = 1: α = 1 − e^{-1}',
      args: [1, 1],
      expected: [ONE_MINUS_E_MINUS_1, ONE_MINUS_E_MINUS_1, ONE_MINUS_E_MINUS_1, Math.exp(-1)],
    },
  ],
});

describeShaderFunction({
  module: 'tracking',
  fn: 'sampleFreeFlight',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: sampleFreeFlight,
  tolerance: { relative: 1e-6, reason: 'the series below ξ = 1/32, WGSL log above it' },
  cases: [
    {
      name: 'σ̄ = 1e-30, ξ = 1e-20: 1e10 (was 0)',
      args: [1e-30, 1e-20],
      expected: Math.fround(1e-20) / Math.fround(1e-30),
    },
    { name: 'σ̄ = 1, ξ = 1e-10: 1e-10 (was 0)', args: [1, 1e-10], expected: Math.fround(1e-10) },
    {
      name: 'σ̄ = 1, ξ = 0.01: −ln(0.99)',
      args: [1, 0.01],
      expected: -Math.log1p(-Math.fround(0.01)),
    },
    { name: 'σ̄ = 1, ξ = 0.5: ln 2 (the log branch)', args: [1, 0.5], expected: Math.LN2 },
    { name: 'ξ = 0: 0', args: [1, 0], expected: 0 },
  ],
});

describeShaderFunction({
  module: 'tracking',
  fn: 'transmittanceTrackLength',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: transmittanceTrackLength,
  tolerance: { absolute: 0, reason: 'an indicator, exactly 0 or 1' },
  cases: [
    {
      name: 'σt = 1, d = 1e-38, ξ = 1e-10: the path 1e-10 passes d, 1 (was 0)',
      args: [1, 1e-38, 1e-10],
      expected: 1,
    },
    { name: 'σt = 1, d = 1e-9, ξ = 1e-10: stops before d, 0', args: [1, 1e-9, 1e-10], expected: 0 },
  ],
});

describeShaderFunction({
  module: 'medium',
  fn: 'lerpWithinEndpoints',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: lerpWithinEndpoints,
  tolerance: { relative: 1e-6, absolute: 1e-30, reason: 'two products and a sum' },
  cases: [
    {
      name: 'a = −F32_MAX, b = 1e37, t = 1e-30: ≈ −F32_MAX (was 1e37)',
      args: [-F32_MAX, 1e37, 1e-30],
      expected: -F32_MAX,
    },
    { name: 'a = −F32_MAX, b = 1, t = 1: b', args: [-F32_MAX, 1, 1], expected: 1 },
    { name: 'a = F32_MAX, b = −F32_MAX, t = ½: 0', args: [F32_MAX, -F32_MAX, 0.5], expected: 0 },
    { name: 'a = 2, b = 4, t = ¼: 2.5', args: [2, 4, 0.25], expected: 2.5 },
  ],
});

describeShaderFunction({
  module: 'slab',
  fn: 'slabRadius',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: slabRadius,
  tolerance: { relative: 1e-6, reason: 'a division, a square root and two products' },
  cases: [
    {
      name: 'x = y = F32_MAX: saturates at F32_MAX (was Inf)',
      args: [F32_MAX, F32_MAX],
      expected: F32_MAX,
    },
    {
      name: 'x = 3e38, y = 1e38: √10·1e38, finite',
      args: [3e38, 1e38],
      expected: Math.hypot(Math.fround(3e38), Math.fround(1e38)),
    },
    { name: 'x = 3, y = −4: 5', args: [3, -4], expected: 5 },
  ],
});

describeShaderFunction({
  module: 'photons',
  fn: 'sunRadiance',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: sunRadiance,
  tolerance: { relative: 1e-6, reason: 'one product and one division' },
  cases: [
    {
      name: 'E = 1e30, sin θ = 1e-30 (clamped to 1e-6): F32_MAX (was Inf)',
      args: [1e30, 1e-30],
      expected: F32_MAX,
    },
    { name: 'E = 1, sin θ = ½: 4/π', args: [1, 0.5], expected: 4 / Math.PI },
  ],
});

describeShaderFunction({
  module: 'photons',
  fn: 'photonKernel',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: photonKernel,
  tolerance: { relative: 1e-6, reason: 'three products and one division' },
  cases: [
    {
      name: 'd² = 0, r = 1e-14: 3/(4πr³) past f32, F32_MAX (was Inf)',
      args: [0, 1e-14],
      expected: F32_MAX,
    },
    { name: 'd² = 0, r = 1e-20: r² below the normal range, 0', args: [0, 1e-20], expected: 0 },
    { name: 'd² = ½, r = 1: 3/(4π)', args: [0.5, 1], expected: 3 / (4 * Math.PI) },
  ],
});

describeShaderFunction({
  module: 'integrator',
  fn: 'averageComponent',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  wrapper: {
    wgsl: 'fn caseUnderTest(x: f32, y: f32, z: f32) -> f32 {\n  return averageComponent(vec3f(x, y, z));\n}',
    imports: ['averageComponent'],
  },
  twin: (x: number, y: number, z: number) => averageComponent([x, y, z]),
  tolerance: { relative: 2e-6, reason: 'quarters, a sum of three and 4/3 (a few ULP)' },
  cases: [
    {
      name: 'all channels F32_MAX: finite, ≈ F32_MAX (was Inf)',
      args: [F32_MAX, F32_MAX, F32_MAX],
      expected: F32_MAX,
    },
    {
      name: '−F32_MAX thrice: ≈ −F32_MAX (was −Inf)',
      args: [-F32_MAX, -F32_MAX, -F32_MAX],
      expected: -F32_MAX,
    },
    { name: '(1, 2, 3): 2', args: [1, 2, 3], expected: 2 },
    { name: '(F32_MAX, −F32_MAX, 3): 1', args: [F32_MAX, -F32_MAX, 3], expected: 1 },
  ],
});
