// Delta tracking: hidden tests (physics.md §9 rows 13, 14; a thick segment).
import type { CheckSpec } from '../../src/grading/exercise.ts';
import { deltaTrackingCheck } from './exercise.ts';

const THICK = [3, 0.9, 1, 5.7] as const;

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  deltaTrackingCheck(
    'mean',
    THICK,
    'Mean in an optically thick segment',
    1,
    'In an optically thick segment (τ = 4.8) your average is not exp(−τ).',
  ),
  deltaTrackingCheck(
    'variance',
    THICK,
    'Variance in an optically thick segment',
    1,
    'In an optically thick segment your estimator is not binary with variance T(1 − T).',
  ),
  deltaTrackingCheck(
    'mean',
    [0, 0.5, 2, 1],
    'No medium, positive majorant',
    1,
    'With σt ≡ 0 every collision is null and the walk must always escape: T = 1 exactly ' +
      '(§9 row 13). A loop cap that returns "absorbed" biases T low.',
  ),
  deltaTrackingCheck(
    'mean',
    [0, 0.5, 2, 0],
    'Majorant of zero',
    1,
    'A majorant of 0 means no medium: return 1 before sampling a distance (−ln(1 − ξ)/0 is ' +
      'infinite or undefined in WGSL; §9 row 14).',
  ),
];
