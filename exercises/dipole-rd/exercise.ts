// The dipole R_d(r) (chapter 11): the public part of the exercise.
import type { ExerciseDefinition } from '../../src/grading/exercise.ts';

/** Tolerance of every case, as the statement states it (values in mm⁻²). */
export const TOLERANCE = { rtol: 1e-4, atol: 1e-9 } as const;

export const EXERCISE: ExerciseDefinition = {
  id: 'dipole-rd',
  chapter: '11-subsurface-scattering',
  title: 'The dipole diffuse reflectance R_d(r)',
  starter: `// The classic dipole diffuse reflectance profile R_d(r) (Jensen et al. 2001) in 1/L²,
// from the reduced scattering σs' and absorption σa (1/L), the relative index η and
// the distance r (L) between where light enters and where it leaves.
fn dipoleRd(sigmaSPrime: f32, sigmaA: f32, eta: f32, r: f32) -> f32 {
  // Your code here.
  return 0.0;
}
`,
  signature: 'fn dipoleRd(sigmaSPrime: f32, sigmaA: f32, eta: f32, r: f32) -> f32',
  hints: [
    "Compute σt', α', σtr, z_r, A and z_v first; skim milk gives z_r = 1.42572 mm, z_v = 6.37214 mm.",
    'Each source term is z (1 + σtr d) exp(−σtr d) / d³ with its own z and d = sqrt(r² + z²).',
    'The two source terms add: the virtual source is a negative source above the surface, and z_v > 0 is its distance.',
  ],
  gradingNotes:
    'Each public case passes when |R − R_ref| ≤ 1e-9 + 1e-4·|R_ref| (mm⁻²). Public: skim milk over ' +
    'r = 0 … 10 mm and a material at η = 1.5. Hidden checks draw materials and distances from ' +
    "the grading seed (relative tolerance 1e-4): any material, α' = 0, σa = 0, no medium, far " +
    'from the source.',
  subject: {
    name: 'dipoleRd',
    params: [
      { name: 'sigmaSPrime', type: 'f32' },
      { name: 'sigmaA', type: 'f32' },
      { name: 'eta', type: 'f32' },
      { name: 'r', type: 'f32' },
    ],
    result: 'f32',
  },
  reference: `import package::dipole::dipoleProfile;
import package::dipole::dipoleParameters;
fn dipoleRd(sigmaSPrime: f32, sigmaA: f32, eta: f32, r: f32) -> f32 {
  return dipoleProfile(dipoleParameters(sigmaSPrime, sigmaA, eta), r);
}`,
  checks: [
    {
      kind: 'cases',
      name: 'Skim milk profile',
      points: 4,
      message:
        'Your profile does not match the dipole for skim milk: check z_v = z_r(1 + 4A/3), ' +
        "σtr = sqrt(3 σa σt'), that both source terms are added, and the factor α'/(4π).",
      ...TOLERANCE,
      cases: [0, 0.25, 0.5, 1, 2, 4, 7, 10].map((r) => ({
        label: `skim milk, r = ${r} mm`,
        args: [0.7, 0.0014, 1.3, r],
      })),
      figure: { argIndex: 3, xLabel: 'r (mm), skim milk' },
    },
    {
      kind: 'cases',
      name: 'Another material at η = 1.5',
      points: 2,
      message:
        'Your profile is wrong at η = 1.5: the boundary term A = (1 + F_dr)/(1 − F_dr) depends on η ' +
        'through the F_dr fit.',
      ...TOLERANCE,
      cases: [0, 1, 3].map((r) => ({
        label: `marble-like, r = ${r} mm`,
        args: [2.19, 0.0021, 1.5, r],
      })),
    },
  ],
};
