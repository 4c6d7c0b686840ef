// Single scattering: hidden tests (physics.md §9 rows 10, 18; §5).
import type { CheckSpec } from '../../src/grading/exercise.ts';
import { TOLERANCE } from './exercise.ts';

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'cases',
    name: 'No scattering',
    points: 1,
    message: 'Without scattering (σs = 0) nothing is scattered towards the eye: L must be 0.',
    ...TOLERANCE,
    cases: [{ label: 'σs = 0', args: [0, 1, 0.5, 1, 2, 8] }],
  },
  {
    kind: 'cases',
    name: 'Opaque medium and occluded light',
    points: 1,
    message:
      'For an opaque medium or a light behind 200 m of it your result is wrong: the shadow ' +
      'transmittance underflows to 0, never NaN (§9 row 10).',
    ...TOLERANCE,
    cases: [
      { label: 'σt = 1e6', args: [5e5, 5e5, 1, 1, 1, 16] },
      { label: 'a = 200', args: [0.5, 0.5, 200, 1, 2, 8] },
    ],
  },
  {
    kind: 'cases',
    name: 'Thin medium, many steps',
    points: 1,
    message: 'Through a thin medium with 64 steps your sum drifts from the reference.',
    ...TOLERANCE,
    cases: [{ label: 'σt = 1e-3, 64 steps', args: [8e-4, 2e-4, 1, 0.5, 10, 64] }],
  },
];
