// Ray marching: hidden tests (physics.md §9 rows 10, 17; §1.1 table).
import type { CheckSpec } from '../../src/grading/exercise.ts';
import { TOLERANCE } from './exercise.ts';

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'cases',
    name: 'Opaque medium',
    points: 1,
    message:
      'For σ0 = 1e6 the ray is opaque and T must be exactly 0; the linearised update gives ' +
      'huge values or NaN here (§9 row 10).',
    ...TOLERANCE,
    cases: [{ label: 'σ0 = 1e6, 64 steps', args: [1e6, 0.5, 1, 64] }],
  },
  {
    kind: 'cases',
    name: 'No attenuation',
    points: 1,
    message: 'With no medium or a ray of zero length nothing is attenuated: T must be 1.',
    ...TOLERANCE,
    cases: [
      { label: 'σ0 = 0', args: [0, 0.5, 3, 8] },
      { label: 'd = 0', args: [2, 0.5, 0, 8] },
    ],
  },
  {
    kind: 'cases',
    name: 'Many steps over a long ray',
    points: 1,
    message: 'With 64 steps over 10 m your result drifts from the exact per-step product.',
    ...TOLERANCE,
    cases: [{ label: '64 steps over 10 m', args: [0.4, 0.8, 10, 64] }],
  },
];
