// Henyey–Greenstein evaluation: hidden tests from physics.md §9 rows 1, 3, 4 and §2.5.
import type { CheckSpec } from '../../src/grading/exercise.ts';
import { TOLERANCE } from './exercise.ts';

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'cases',
    name: 'Far tail and sign convention',
    points: 2,
    message:
      'In the far tail (g = ±0.999, μ = ∓1) your value is wrong: p must be ≈ 1.99e-5 sr⁻¹ ' +
      'there; a mirrored convention (−μ) puts the peak on the wrong side.',
    ...TOLERANCE,
    cases: [
      { label: 'g = 0.999, μ = −1 (§9 row 3)', args: [0.999, -1] },
      { label: 'g = −0.999, μ = 1 (§9 row 3)', args: [-0.999, 1] },
      { label: 'g = −0.9, μ = −1', args: [-0.9, -1] },
    ],
  },
  {
    kind: 'cases',
    name: 'Isotropic scattering',
    points: 1,
    message: 'At g = 0 Henyey–Greenstein is isotropic: 1/(4π) = 0.0795775 sr⁻¹ for every μ.',
    ...TOLERANCE,
    cases: [-1, -0.3, 0.6, 1].map((mu) => ({
      label: `g = 0, μ = ${mu} (§9 row 4)`,
      args: [0, mu],
    })),
  },
  {
    kind: 'cases',
    name: 'Forward peak',
    points: 1,
    message:
      'At the forward peak your value is off: 1 + g² − 2gμ cancels in f32 when g and μ are ' +
      'near 1; compute it as (1 − g)² + 2g(1 − μ) (chapter 3, §2.5).',
    ...TOLERANCE,
    cases: [
      { label: 'g = 0.9, μ = 1', args: [0.9, 1] },
      { label: 'g = 0.999, μ = 1 (§9 row 1)', args: [0.999, 1] },
      { label: 'g = 0.99, μ = 0.999', args: [0.99, 0.999] },
    ],
  },
];
