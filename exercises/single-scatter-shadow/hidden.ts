// Single scattering: hidden tests (physics.md §9 rows 10, 18; §5). Cases are drawn from
// the grading seed (src/grading/checks/generated.ts), and each check pairs its edge
// cases (no scattering, opaque, occluded light) with ordinary partners, so neither a
// table of inputs nor a constant guess (0) passes it.
import type { CaseSpec, CheckSpec } from '../../src/grading/exercise.ts';
import { caseSampler, type CaseSampler } from '../../src/grading/checks/generated.ts';
import { TOLERANCE } from './exercise.ts';

const f = Math.fround;

/**
 * An ordinary view ray: σs, σa log-uniform, a light behind a ∈ [0, 3] m plus b ∈ [0, 3]
 * per metre, a ray of optical depth σt·len ∈ [0.05, 8] and 1 to 64 steps.
 */
function ordinary(r: CaseSampler, label: string): CaseSpec {
  const sigmaS = r.logUniform(0.01, 5);
  const sigmaA = r.logUniform(0.001, 5);
  const len = f(r.logUniform(0.05, 8) / (sigmaS + sigmaA));
  return { label, args: [sigmaS, sigmaA, r.uniform(0, 3), r.uniform(0, 3), len, r.integer(1, 64)] };
}

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'generated-cases',
    name: 'Media, lights and step counts',
    points: 2,
    message:
      'For some media, light geometries or step counts your estimate differs from the midpoint ' +
      'shadow-ray loop: each sample is σs·T_view(t)·T_shadow(t)·h.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'single-scatter ordinary');
      // Many ordinary cases: deterministic cases cost one dispatch, and a submission right
      // only in part of the domain (the public region) fails a check of k uniform draws unless
      // all miss the wrong part: (1 − q)^k, 0.001 for q = 25 % at k = 24 (red team, issue 15).
      return Array.from({ length: 24 }, (_, k) => ordinary(r, `ray ${k + 1}`));
    },
  },
  {
    kind: 'generated-cases',
    name: 'No scattering',
    points: 1,
    message:
      'Without scattering (σs = 0) nothing is scattered towards the eye: L must be 0; a weakly ' +
      'scattering medium still scatters.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'single-scatter none');
      const zero = ordinary(r, 'σs = 0');
      const weak = [ordinary(r, 'weak scattering'), ordinary(r, 'weak scattering')];
      return [
        { ...zero, args: [0, ...zero.args.slice(1)] },
        ...weak.map((c) => ({ ...c, args: [r.logUniform(1e-3, 1e-2), ...c.args.slice(1)] })),
      ];
    },
  },
  {
    kind: 'generated-cases',
    name: 'Opaque medium and occluded light',
    points: 1,
    message:
      'For an opaque medium (σt ≥ 1e5) or a light behind more than 100 optical depths of it your ' +
      'result is wrong: the transmittances underflow to 0, never NaN.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'single-scatter opaque');
      const half = r.logUniform(5e4, 5e6);
      const occluded = ordinary(r, 'occluded light');
      const sigmaT = (occluded.args[0] ?? 0) + (occluded.args[1] ?? 0);
      return [
        {
          label: 'opaque',
          args: [half, half, r.uniform(0, 3), r.uniform(0, 3), r.uniform(0.5, 5), r.integer(4, 64)],
        },
        {
          ...occluded,
          args: [
            occluded.args[0] ?? 0,
            occluded.args[1] ?? 0,
            f(r.uniform(120, 300) / sigmaT),
            ...occluded.args.slice(3),
          ],
        },
        ordinary(r, 'partner'),
      ];
    },
  },
  {
    kind: 'generated-cases',
    name: 'Thin medium, many steps',
    points: 1,
    message: 'Through a thin medium with many steps your sum drifts from the reference.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'single-scatter thin');
      return Array.from({ length: 2 }, () => ({
        label: 'thin medium',
        args: [
          r.logUniform(1e-4, 1e-2),
          r.logUniform(1e-4, 1e-3),
          r.uniform(2, 5),
          r.uniform(0, 3),
          r.uniform(5, 20),
          r.integer(32, 128),
        ],
      }));
    },
  },
];
