// The dipole: hidden tests (physics.md §9 rows 19–21, §6.1).
import type { CheckSpec } from '../../src/grading/exercise.ts';
import { TOLERANCE } from './exercise.ts';

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'cases',
    name: 'No scattering',
    points: 1,
    message: "With σs' = 0 (α' = 0) nothing scatters back: R_d must be exactly 0 (§9 row 20).",
    ...TOLERANCE,
    cases: [{ label: "α' = 0", args: [0, 0.5, 1.3, 1] }],
  },
  {
    kind: 'cases',
    name: 'No absorption',
    points: 1,
    message:
      "With σa = 0 (α' = 1, σtr = 0) the profile is a finite power law; yours is wrong there (§9 row 21).",
    ...TOLERANCE,
    cases: [
      { label: 'σa = 0, r = 0', args: [1, 0, 1.3, 0] },
      { label: 'σa = 0, r = 2', args: [1, 0, 1.3, 2] },
    ],
  },
  {
    kind: 'cases',
    name: 'No medium',
    points: 1,
    message: "With σs' = σa = 0 there is no medium: return 0 instead of dividing by σt' = 0 (NaN).",
    ...TOLERANCE,
    cases: [{ label: "σs' = σa = 0", args: [0, 0, 1.3, 1] }],
  },
  {
    kind: 'cases',
    name: 'Far from the source',
    points: 1,
    message: 'Far from the entry point (r = 30 mm) your profile is off.',
    ...TOLERANCE,
    cases: [{ label: 'skim milk, r = 30 mm', args: [0.7, 0.0014, 1.3, 30] }],
  },
];
