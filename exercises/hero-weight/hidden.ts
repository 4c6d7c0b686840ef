// Hero-wavelength weight: hidden checks. Cases are drawn from the grading seed
// (src/grading/checks/generated.ts): pdfs over many decades (the pdf of a long path is a
// product of many factors), a channel that cannot produce the path (its σt is 0 at a
// collision, p = 0) and a path no channel could produce (all 0, where the factor is 0 and a
// division without a guard gives Inf or NaN).
import type { CheckSpec } from '../../src/grading/exercise.ts';
import { caseSampler } from '../../src/grading/checks/generated.ts';
import { TOLERANCE, WEIGHT_MESSAGE } from './exercise.ts';

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'generated-cases',
    name: 'Arbitrary pdfs and heroes',
    points: 2,
    message: WEIGHT_MESSAGE,
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hero-weight arbitrary');
      return Array.from({ length: 24 }, (_, k) => ({
        label: `case ${k + 1}`,
        args: [
          r.logUniform(0.01, 100),
          r.logUniform(0.01, 100),
          r.logUniform(0.01, 100),
          r.integer(0, 2),
        ],
      }));
    },
  },
  {
    kind: 'generated-cases',
    name: 'Pdfs over many decades',
    points: 1,
    message:
      'For pdfs far from 1 (a long path’s pdf is a product of many factors) your factor is wrong: ' +
      'compute 3/(p0 + p1 + p2) directly; squares of pdfs (the power heuristic) overflow or ' +
      'underflow in f32 long before the sum does.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hero-weight decades');
      return Array.from({ length: 8 }, (_, k) => {
        const scale = r.logUniform(1e-20, 1e20);
        return {
          label: `pdfs near ${scale.toExponential(1)}`,
          args: [
            scale * r.uniform(0.2, 5),
            scale * r.uniform(0.2, 5),
            scale * r.uniform(0.2, 5),
            k % 3,
          ],
        };
      });
    },
  },
  {
    kind: 'generated-cases',
    name: 'A channel that cannot produce the path',
    points: 1,
    message:
      'A channel with p = 0 (σt = 0 where the path collided) simply drops out of the sum: the factor is ' +
      '3/(sum of the other two), still with the 3 of choosing the hero among all three channels.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hero-weight zero');
      return Array.from({ length: 6 }, (_, k) => {
        const p = [r.logUniform(0.1, 10), r.logUniform(0.1, 10), r.logUniform(0.1, 10)];
        p[k % 3] = 0;
        return { label: `p${k % 3} = 0, hero ${(k + 1) % 3}`, args: [...p, (k + 1) % 3] };
      });
    },
  },
  {
    kind: 'generated-cases',
    name: 'No channel can produce the path',
    points: 1,
    message:
      'With p0 = p1 = p2 = 0 the path has no density in any channel; return 0 (guard the sum: ' +
      '3/0 is Inf, and WGSL may assume neither Inf nor NaN). The check also has ordinary cases.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hero-weight none');
      // One all-zero case (its hero from the seed, so at most this case repeats between
      // seeds) among ordinary ones.
      const hero = r.integer(0, 2);
      return [
        { label: `all pdfs 0, hero ${hero}`, args: [0, 0, 0, hero] },
        ...[0, 2].map((h) => ({
          label: `ordinary, hero ${h}`,
          args: [r.logUniform(0.1, 10), r.logUniform(0.1, 10), r.logUniform(0.1, 10), h],
        })),
      ];
    },
  },
];
