// One ray of the irradiance in the room (chapter 12): the public part of the exercise. The
// student turns the radiance a cosine-weighted ray brings to a translucent sphere into that
// ray's estimate of the transmitted irradiance E of eq:room-irradiance, the number pass 1 of
// <sb-translucent-room> averages at each irradiance sample.
import type { ExerciseDefinition, Helpers } from '../../src/grading/exercise.ts';

/** The library's Fresnel reflectance, linked in front of the submission. */
export const FRESNEL_HELPERS: Helpers = {
  imports: ['import package::fresnel::fresnelDielectric;'],
  wgsl: `fn keepFresnelHelper() -> f32 {
  return fresnelDielectric(1.0, 1.5);
}`,
};

/** Tolerance of every case (irradiance in the radiance's units × sr). */
export const TOLERANCE = { rtol: 1e-5, atol: 1e-7 } as const;

export const EXERCISE: ExerciseDefinition = {
  id: 'room-irradiance',
  chapter: '12-beyond-the-lecture',
  title: 'One ray of the irradiance in the room',
  starter: `// One cosine-weighted ray's estimate of the irradiance transmitted into a translucent object
// (chapter 12, eq:room-irradiance): the ray arrives with radiance L at angle θ to the normal
// (cosTheta = cos θ ∈ [0, 1]) on a smooth boundary of relative index η, and was drawn with
// density cos θ / π. fresnelDielectric(cosThetaI, eta) (chapter 11's Fresnel reflectance) is provided.
fn irradianceRay(radiance: f32, cosTheta: f32, eta: f32) -> f32 {
  // Your code here.
  return 0.0;
}
`,
  signature: 'fn irradianceRay(radiance: f32, cosTheta: f32, eta: f32) -> f32',
  hints: [
    'The estimate of an integral is the integrand divided by the density the direction was drawn with.',
    'The integrand is L (1 − F_r(cos θ, η)) cos θ; the density is cos θ / π. What is left?',
    'At normal incidence with η = 1.3, F_r = 0.017, so one ray of radiance 1 gives π · 0.983 = 3.088.',
  ],
  gradingNotes:
    'Each case passes when |E − E_ref| ≤ 1e-7 + 1e-5·|E_ref|. Public: radiance 1 at η = 1.3 from ' +
    'normal to oblique incidence, and grazing and dark rays with a partner. Hidden checks draw ' +
    'radiances, angles and indices from the grading seed: any ray, grazing rays, and η = 1.',
  subject: {
    name: 'irradianceRay',
    params: [
      { name: 'radiance', type: 'f32' },
      { name: 'cosTheta', type: 'f32' },
      { name: 'eta', type: 'f32' },
    ],
    result: 'f32',
  },
  helpers: FRESNEL_HELPERS,
  reference: `fn irradianceRay(radiance: f32, cosTheta: f32, eta: f32) -> f32 {
  return 3.14159265358979 * (1.0 - fresnelDielectric(clamp(cosTheta, 0.0, 1.0), eta)) * radiance;
}`,
  checks: [
    {
      kind: 'cases',
      name: 'Normal to oblique incidence',
      points: 2,
      message:
        'Your estimate is wrong for a ray of radiance 1 at η = 1.3: divide L (1 − F) cos θ by the ' +
        'density cos θ / π, and transmit with 1 − F, not F.',
      ...TOLERANCE,
      cases: [1, 0.8, 0.5, 0.2].map((c) => ({
        label: `cos θ = ${c}`,
        args: [1, c, 1.3],
      })),
      figure: { argIndex: 1, xLabel: 'cos θ (radiance 1, η = 1.3)' },
    },
    {
      kind: 'cases',
      name: 'Grazing and dark rays',
      points: 1,
      message:
        'A grazing ray is wholly reflected (F = 1) and a dark ray brings nothing: both give 0, ' +
        'while an ordinary ray beside them does not.',
      ...TOLERANCE,
      cases: [
        { label: 'grazing, cos θ = 0', args: [2, 0, 1.3] },
        { label: 'dark, L = 0', args: [0, 0.7, 1.3] },
        { label: 'partner: L = 2.5, cos θ = 0.6, η = 1.5', args: [2.5, 0.6, 1.5] },
      ],
    },
  ],
};
