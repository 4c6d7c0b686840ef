// WGSL moments module vs its float64 twin: the standard error of a pixel's mean from its
// M2 (shaders/moments.wesl; the accumulation itself is tested end to end in
// tests/shaders/scene-accumulation.test.ts).
import { describeShaderFunction } from '../support/shaderHarness.ts';
import { momentsStandardError } from '../../src/reference/moments.ts';

describeShaderFunction({
  module: 'moments',
  fn: 'momentsStandardError',
  args: ['f32[3]', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['momentsStandardError', 'PixelMoments'],
    wgsl: `fn caseUnderTest(m2: array<f32, 3>, samples: f32) -> vec3f {
  return momentsStandardError(PixelMoments(vec3f(0.5), 0u, vec3f(m2[0], m2[1], m2[2]), 0u), samples);
}`,
  },
  twin: (m2: readonly number[], samples: number) =>
    momentsStandardError(
      { mean: [0.5, 0.5, 0.5], lookups: 0, m2: [m2[0] ?? 0, m2[1] ?? 0, m2[2] ?? 0], capped: 0 },
      samples,
    ),
  tolerance: {
    relative: 2e-6,
    reason: 'one multiplication, one division (2.5 ULP) and a square root (2.5 ULP) in f32',
  },
  cases: [
    {
      name: 'M2 = n − 1 (unit variance) over n = 100 gives 1/√n = 0.1',
      args: [[99, 99, 99], 100],
      expected: [0.1, 0.1, 0.1],
    },
    {
      name: 'channels are independent',
      args: [[0, 4, 36], 2],
      expected: [0, Math.sqrt(2), Math.sqrt(18)],
    },
    { name: 'a rounding-negative M2 counts as 0', args: [[-1e-7, 0, 1e-7], 10] },
    { name: 'a million samples with small spread', args: [[3e-3, 1.5e-2, 2.2e-1], 1048576] },
  ],
});
