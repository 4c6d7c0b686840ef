// Beer's law: hidden tests, the hard cases of physics.md §9 (rows 10, 11) and §1.
import type { CheckSpec } from '../../src/grading/exercise.ts';
import { TOLERANCE } from './exercise.ts';

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'cases',
    name: 'Zero thickness',
    points: 1,
    message: 'With no distance or no medium nothing is attenuated: T must be exactly 1.',
    ...TOLERANCE,
    cases: [
      { label: 'd = 0', args: [5, 0] },
      { label: 'σt = 0', args: [0, 100] },
    ],
  },
  {
    kind: 'cases',
    name: 'Optically thick media',
    points: 1,
    message:
      'For an optically thick medium (τ = 1e6) the transmittance is 0; yours is not (NaN or ' +
      'infinity means the exponent overflowed: keep τ ≥ 0 and let exp underflow to 0).',
    ...TOLERANCE,
    cases: [
      { label: 'σt = 1e6 over 1 m (§9 row 10)', args: [1e6, 1] },
      { label: 'σt = 200 over 1 m', args: [200, 1] },
      { label: 'σt = 1e6 over 1e-6 m (§9 row 11)', args: [1e6, 1e-6] },
    ],
  },
  {
    kind: 'cases',
    name: 'Negative inputs stay physical',
    points: 2,
    message:
      'Your transmittance must be exactly 1 for negative σt or d (treat τ < 0 as no medium): ' +
      'clamp the optical thickness to τ ≥ 0 (neither exp(−τ) nor exp(−|τ|) is right for τ < 0).',
    ...TOLERANCE,
    cases: [
      { label: 'negative σt', args: [-2, 1] },
      { label: 'negative d', args: [3, -0.5] },
    ],
  },
];
