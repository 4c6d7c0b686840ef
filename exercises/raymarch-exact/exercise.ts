// Ray marching with exact transmittance (chapter 5): the public part of the exercise.
import type { ExerciseDefinition, Helpers } from '../../src/grading/exercise.ts';

/** Tolerance of every case, as the statement states it. */
export const TOLERANCE = { rtol: 1e-4, atol: 1e-7 } as const;

/** The medium σt(s) = σ0 (1 + a sin(3 s)) the statement describes, given to the student. */
export const MEDIUM_HELPERS: Helpers = {
  imports: [],
  wgsl: `fn extinction(sigma0: f32, amplitude: f32, s: f32) -> f32 {
  return sigma0 * (1.0 + amplitude * sin(3.0 * s));
}`,
};

export const EXERCISE: ExerciseDefinition = {
  id: 'raymarch-exact',
  chapter: '05-emission-absorption-and-ray-marching',
  title: 'Ray marching with exact transmittance',
  starter: `// Ray marching the transmittance of a heterogeneous medium, with the exact
// per-step update. extinction(sigma0, amplitude, s) is provided: σt(s) in 1/m at
// distance s (m) along the ray. Use \`steps\` equal steps over [0, d], sampling σt
// at the midpoint of each step.
fn marchTransmittance(sigma0: f32, amplitude: f32, d: f32, steps: u32) -> f32 {
  var transmittance = 1.0;
  // Your loop here.
  return transmittance;
}
`,
  signature: 'fn marchTransmittance(sigma0: f32, amplitude: f32, d: f32, steps: u32) -> f32',
  hints: [
    'h = d / f32(steps); the midpoint of step i is (f32(i) + 0.5) * h.',
    'for (var i = 0u; i < steps; i++) runs exactly `steps` times; i <= steps runs one too many.',
    'Multiply by exp(−σ h), not (1 − σ h): the exact factor never goes negative.',
  ],
  gradingNotes:
    "Each case passes when |T − T_ref| ≤ 1e-7 + 1e-4·|T_ref| against the book's midpoint marcher. " +
    'Public: 1 to 16 steps and a denser medium. Hidden checks draw their rays from the grading ' +
    'seed: any medium, length and step count, opaque media, no attenuation, long rays.',
  subject: {
    name: 'marchTransmittance',
    params: [
      { name: 'sigma0', type: 'f32' },
      { name: 'amplitude', type: 'f32' },
      { name: 'd', type: 'f32' },
      { name: 'steps', type: 'u32' },
    ],
    result: 'f32',
  },
  helpers: MEDIUM_HELPERS,
  reference: `import package::transmittance::transmittanceHomogeneous;
fn marchTransmittance(sigma0: f32, amplitude: f32, d: f32, steps: u32) -> f32 {
  let n = max(steps, 1u);
  let h = max(d, 0.0) / f32(n);
  var transmittance = 1.0;
  for (var i = 0u; i < n; i++) {
    transmittance *= transmittanceHomogeneous(extinction(sigma0, amplitude, (f32(i) + 0.5) * h), h);
  }
  return transmittance;
}`,
  loopBudget: 1024,
  checks: [
    {
      kind: 'cases',
      name: 'Step counts 1 to 16',
      points: 4,
      message:
        'Your marched transmittance differs from the exact per-step update T ← T·exp(−σ_i h) ' +
        'with σ_i at the step midpoints: check the update (not 1 − σh), the step length d/N ' +
        'and that the loop runs exactly N times.',
      ...TOLERANCE,
      cases: [1, 2, 3, 4, 6, 8, 12, 16].map((n) => ({
        label: `${n} steps`,
        args: [1, 0.5, 2, n],
      })),
      figure: { argIndex: 3, xLabel: 'steps N (σ0 = 1/m, a = 0.5, d = 2 m)' },
    },
    {
      kind: 'cases',
      name: 'A denser medium',
      points: 2,
      message:
        'In a denser medium (σ_i h up to 1.4) your transmittance is off: the linearised ' +
        'update 1 − σh is far from exp(−σh) there and can even go negative.',
      ...TOLERANCE,
      cases: [
        { label: 'σ0 = 3, 4 steps', args: [3, 0.9, 1, 4] },
        { label: 'σ0 = 3, 2 steps', args: [3, 0.9, 1, 2] },
      ],
    },
  ],
};
