// Beer's-law transmittance (chapter 2): the public part of the exercise.
import type { ExerciseDefinition } from '../../src/grading/exercise.ts';

/** Tolerance of every case, as the statement states it. */
export const TOLERANCE = { rtol: 1e-5, atol: 1e-6 } as const;

export const EXERCISE: ExerciseDefinition = {
  id: 'beer-law',
  chapter: '02-extinction-and-transmittance',
  title: "Beer's law",
  starter: `// Beer's law: the fraction of light that crosses a homogeneous slab of thickness d
// (m) with extinction coefficient sigmaT (1/m) without being absorbed or scattered.
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  // Your code here: T = exp(−σt d). Think about what a negative σt or d should give.
  return 1.0;
}
`,
  signature: 'fn transmittance(sigmaT: f32, d: f32) -> f32',
  hints: [
    'The optical thickness is τ = σt·d; the transmittance is exp(−τ).',
    'Clamp τ to be non-negative first: max(sigmaT * d, 0.0). Transmittance never exceeds 1.',
    'For τ = 1e6, exp(−τ) is exactly 0 in f32; no special case is needed once τ ≥ 0.',
  ],
  gradingNotes:
    'Each case passes when |T − T_ref| ≤ 1e-6 + 1e-5·|T_ref|. Public: τ from 0 to 10 at σt = 1/m ' +
    'and three media. Hidden checks draw their cases from the grading seed: media of any ' +
    'thickness and the hard cases of the chapter, each with ordinary partners.',
  subject: {
    name: 'transmittance',
    params: [
      { name: 'sigmaT', type: 'f32' },
      { name: 'd', type: 'f32' },
    ],
    result: 'f32',
  },
  reference: `import package::transmittance::transmittanceHomogeneous;
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  return transmittanceHomogeneous(sigmaT, d);
}`,
  checks: [
    {
      kind: 'cases',
      name: 'Transmittance over typical thicknesses',
      points: 4,
      message:
        'Your transmittance does not follow Beer’s law T = exp(−σt d) for an ordinary slab; ' +
        'check the sign of the exponent and that you multiply σt by d.',
      ...TOLERANCE,
      cases: [0, 0.1, 0.25, 0.5, 1, 1.5, 2, 3, 5, 7.5, 10].map((d) => ({
        label: `σt = 1/m, d = ${d} m`,
        args: [1, d],
      })),
      figure: { argIndex: 1, xLabel: 'distance d (m) at σt = 1/m' },
    },
    {
      kind: 'cases',
      name: 'Different extinction coefficients',
      points: 2,
      message:
        'Your transmittance is right for one σt but not for others: T depends on the product σt d.',
      ...TOLERANCE,
      cases: [
        { label: 'thin fog', args: [0.02, 30] },
        { label: 'dense smoke', args: [8, 0.3] },
        { label: 'milk over 1 mm', args: [700, 0.001] },
      ],
    },
  ],
};
