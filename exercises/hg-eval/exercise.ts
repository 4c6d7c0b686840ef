// Henyey–Greenstein evaluation (chapter 3): the public part of the exercise.
import type { ExerciseDefinition } from '../../src/grading/exercise.ts';

/** Tolerance of every case, as the statement states it. */
export const TOLERANCE = { rtol: 1e-4, atol: 1e-7 } as const;

const MUS = [-1, -0.75, -0.5, -0.25, 0, 0.25, 0.5, 0.75, 0.9, 1];

export const EXERCISE: ExerciseDefinition = {
  id: 'hg-eval',
  chapter: '03-phase-functions-and-in-scattering',
  title: 'Evaluating the Henyey–Greenstein phase function',
  starter: `// The Henyey–Greenstein phase function p(μ; g) in sr⁻¹, where μ is the cosine of the
// angle between the incoming direction of travel and the scattered one and g ∈ (−1, 1)
// is the mean cosine (g > 0 scatters forward).
fn hgPhase(g: f32, mu: f32) -> f32 {
  // Your code here.
  return 0.0;
}
`,
  signature: 'fn hgPhase(g: f32, mu: f32) -> f32',
  hints: [
    'p = (1 − g²) / (4π (1 + g² − 2gμ)^{3/2}); 1/(4π) = 0.0795774715.',
    'x^{3/2} is x * sqrt(x); WGSL pow(x, 1.5) works too but is less accurate.',
    'Near the forward peak, 1 + g² − 2gμ cancels: write it (1 − g)² + 2g(1 − μ).',
  ],
  gradingNotes:
    'Each case passes when |p − p_ref| ≤ 1e-7 + 1e-4·|p_ref|. Public: g ∈ {0, 0.3, 0.7, −0.5}, ' +
    'μ ∈ [−1, 1]. Hidden checks draw g and μ from the grading seed: arbitrary lobes, the far ' +
    'tail of strong lobes, isotropy, and forward peaks.',
  subject: {
    name: 'hgPhase',
    params: [
      { name: 'g', type: 'f32' },
      { name: 'mu', type: 'f32' },
    ],
    result: 'f32',
  },
  reference: `import package::phase::hgEval;
fn hgPhase(g: f32, mu: f32) -> f32 {
  return hgEval(g, mu);
}`,
  checks: [
    {
      kind: 'cases',
      name: 'Forward lobe g = 0.7',
      points: 3,
      message:
        'Your phase function does not match Henyey–Greenstein for a forward lobe: with g > 0 ' +
        'it must peak at μ = 1; check the sign of 2gμ and the 3/2 power.',
      ...TOLERANCE,
      cases: MUS.map((mu) => ({ label: `g = 0.7, μ = ${mu}`, args: [0.7, mu] })),
      figure: { argIndex: 1, xLabel: 'μ = cos θ at g = 0.7' },
    },
    {
      kind: 'cases',
      name: 'Other asymmetries',
      points: 3,
      message:
        'Your phase function is wrong for some g: check the normalisation 1/(4π) (at g = 0 it ' +
        'is 1/(4π) everywhere) and that a negative g peaks backwards.',
      ...TOLERANCE,
      cases: [0, 0.3, -0.5].flatMap((g) =>
        [-1, -0.5, 0, 0.5, 1].map((mu) => ({ label: `g = ${g}, μ = ${mu}`, args: [g, mu] })),
      ),
    },
  ],
};
