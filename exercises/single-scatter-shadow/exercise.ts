// The single-scattering shadow-ray loop (chapter 9): the public part of the exercise.
import type { ExerciseDefinition } from '../../src/grading/exercise.ts';

/** Tolerance of every case, as the statement states it. */
export const TOLERANCE = { rtol: 1e-4, atol: 1e-7 } as const;

export const EXERCISE: ExerciseDefinition = {
  id: 'single-scatter-shadow',
  chapter: '09-single-scattering',
  title: 'The single-scattering shadow-ray loop',
  starter: `// Single scattering along a view ray of length len through a homogeneous medium
// (σs, σa in 1/m), lit by a distant light whose shadow ray from the point at
// distance t crosses a + b·t metres of the medium. Phase function × irradiance = 1.
// March \`steps\` equal steps, one shadow ray at each step's midpoint.
fn singleScatter(sigmaS: f32, sigmaA: f32, a: f32, b: f32, len: f32, steps: u32) -> f32 {
  var radiance = 0.0;
  // Your loop here.
  return radiance;
}
`,
  signature:
    'fn singleScatter(sigmaS: f32, sigmaA: f32, a: f32, b: f32, len: f32, steps: u32) -> f32',
  hints: [
    'h = len / f32(steps); t = (f32(i) + 0.5) * h for i in 0..steps−1.',
    'Each sample: sigmaS * exp(−σt t) * exp(−σt (a + b t)); σt = σs + σa attenuates both rays.',
    'Multiply the sum by h: a sample without its 1/pdf weight is off by the ray length.',
  ],
  gradingNotes:
    'Each case passes when |L − L_ref| ≤ 1e-7 + 1e-4·|L_ref|. Public: 1 to 16 steps, several ' +
    'media. Hidden checks draw their rays from the grading seed: any medium, light and step ' +
    'count, no scattering, opaque media and occluded lights, thin media with many steps.',
  subject: {
    name: 'singleScatter',
    params: [
      { name: 'sigmaS', type: 'f32' },
      { name: 'sigmaA', type: 'f32' },
      { name: 'a', type: 'f32' },
      { name: 'b', type: 'f32' },
      { name: 'len', type: 'f32' },
      { name: 'steps', type: 'u32' },
    ],
    result: 'f32',
  },
  reference: `import package::transmittance::transmittanceHomogeneous;
import package::scatter::shadowTransmittanceExact;
fn singleScatter(sigmaS: f32, sigmaA: f32, a: f32, b: f32, len: f32, steps: u32) -> f32 {
  let n = max(steps, 1u);
  let sigmaT = sigmaS + sigmaA;
  let h = max(len, 0.0) / f32(n);
  var radiance = 0.0;
  for (var i = 0u; i < n; i++) {
    let t = (f32(i) + 0.5) * h;
    radiance += sigmaS * transmittanceHomogeneous(sigmaT, t) * shadowTransmittanceExact(sigmaT, a, b, t);
  }
  return radiance * h;
}`,
  loopBudget: 1024,
  checks: [
    {
      kind: 'cases',
      name: 'Step counts 1 to 16',
      points: 4,
      message:
        'Your single-scattering estimate differs from the midpoint shadow-ray loop: each sample ' +
        'is σs·T_view(t)·T_shadow(t), weighted by h = len/N (its 1/pdf), with exactly N samples.',
      ...TOLERANCE,
      cases: [1, 2, 4, 8, 16].map((n) => ({
        label: `${n} steps`,
        args: [0.8, 0.2, 0.5, 1, 2, n],
      })),
      figure: { argIndex: 5, xLabel: 'steps N (σs = 0.8, σa = 0.2, a = 0.5, b = 1, len = 2)' },
    },
    {
      kind: 'cases',
      name: 'Other media and lights',
      points: 2,
      message:
        'For some media or light directions your estimate is off: both the view ray and the ' +
        'shadow ray are attenuated by σt = σs + σa, the shadow ray over a + b·t.',
      ...TOLERANCE,
      cases: [
        { label: 'absorbing, overhead light', args: [0.3, 1.5, 0, 0, 1.5, 8] },
        { label: 'bright haze, grazing light', args: [0.5, 0.01, 2, 3, 4, 8] },
      ],
    },
  ],
};
