// Henyey–Greenstein sampling: hidden tests (physics.md §9 rows 6–8).
import type { CheckSpec } from '../../src/grading/exercise.ts';
import { hgChiSquare } from './exercise.ts';

const POINT_TOLERANCE = { rtol: 1e-4, atol: 1e-5 } as const;

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  hgChiSquare(
    0.95,
    'Distribution of μ for a strongly forward lobe, g = 0.95',
    1,
    'Your samples are not distributed like Henyey–Greenstein at g = 0.95.',
  ),
  {
    kind: 'cases',
    name: 'End points and median',
    points: 1,
    message:
      'Your sampler does not map ξ = 0 to μ = −1, or ξ = ½ to the median g(3 − g²)/2: keep μ ' +
      'increasing with ξ as the statement says.',
    ...POINT_TOLERANCE,
    cases: [
      { label: 'ξ = 0 (§9 row 7)', args: [0.7, 0] },
      { label: 'median, g = 0.9 (§9 row 8)', args: [0.9, 0.5] },
      { label: 'median, g = −0.4', args: [-0.4, 0.5] },
    ],
  },
  {
    kind: 'cases',
    name: 'Nearly isotropic g',
    points: 1,
    message:
      'For g = 1e-7 the inverse CDF divides two tiny numbers and leaves [−1, 1] in f32 ' +
      '(the textbook form gives −1.19): use μ = 2ξ − 1 for very small |g| (§9 row 6). ' +
      'If you already do, check the orientation: μ must increase with ξ.',
    ...POINT_TOLERANCE,
    cases: [{ label: 'g = 1e-7, ξ = 0.25 (§9 row 6)', args: [1e-7, 0.25] }],
  },
];
