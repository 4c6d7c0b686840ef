// Ray marching: hidden tests (physics.md §9 rows 10, 17; §1.1 table). Cases are drawn
// from the grading seed (src/grading/checks/generated.ts), and each check pairs its
// edge cases (opaque, no medium, zero length) with ordinary partners, so neither a
// table of inputs nor a constant guess passes it.
import type { CaseSpec, CheckSpec } from '../../src/grading/exercise.ts';
import { caseSampler, type CaseSampler } from '../../src/grading/checks/generated.ts';
import { TOLERANCE } from './exercise.ts';

const f = Math.fround;

/**
 * A ray of optical depth about τ ∈ [τLow, τHigh] (σ0 d ≈ τ; a ∈ [0, 1] changes it by
 * at most a factor 2/3…4/3 over a whole period) with `steps` ∈ [stepsLow, stepsHigh].
 */
function ray(
  r: CaseSampler,
  label: string,
  tauLow: number,
  tauHigh: number,
  stepsLow: number,
  stepsHigh: number,
  dLow = 0.1,
  dHigh = 5,
): CaseSpec {
  const d = r.logUniform(dLow, dHigh);
  const tau = r.logUniform(tauLow, tauHigh);
  return {
    label,
    args: [f(tau / d), r.uniform(0, 1), d, r.integer(stepsLow, stepsHigh)],
  };
}

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'generated-cases',
    name: 'Media, lengths and step counts',
    points: 2,
    message:
      'For some media, ray lengths or step counts your marched transmittance differs from the ' +
      'exact per-step update with σt at the step midpoints.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'raymarch ordinary');
      // Many ordinary cases: deterministic cases cost one dispatch, and a submission right
      // only in part of the domain (the public region) fails a check of k uniform draws unless
      // all miss the wrong part: (1 − q)^k, 0.001 for q = 25 % at k = 24 (red team, issue 15).
      return Array.from({ length: 24 }, (_, k) => ray(r, `ray ${k + 1}`, 0.05, 8, 1, 64));
    },
  },
  {
    kind: 'generated-cases',
    name: 'Opaque medium',
    points: 1,
    message:
      'For σ0 ≥ 1e5 the ray is opaque and T must be exactly 0 (the linearised update gives huge ' +
      'values or NaN here); thick but not opaque rays keep their small T.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'raymarch opaque');
      return [
        {
          label: 'opaque',
          args: [r.logUniform(1e5, 1e7), r.uniform(0, 1), r.logUniform(0.5, 5), r.integer(8, 64)],
        },
        // Three partners: a first-order (left-endpoint) or one-step-too-many marcher can
        // land within tolerance on one ray by chance, not on three.
        ray(r, 'thick', 3, 10, 2, 32),
        ray(r, 'thick', 3, 10, 2, 32),
        ray(r, 'thick', 3, 10, 2, 32),
      ];
    },
  },
  {
    kind: 'generated-cases',
    name: 'No attenuation',
    points: 1,
    message:
      'With no medium or a ray of zero length nothing is attenuated: T must be 1; a thin medium ' +
      'still attenuates.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'raymarch none');
      return [
        { label: 'σ0 = 0', args: [0, r.uniform(0, 1), r.logUniform(0.1, 10), r.integer(1, 64)] },
        { label: 'd = 0', args: [r.logUniform(0.01, 10), r.uniform(0, 1), 0, r.integer(1, 64)] },
        ray(r, 'partner', 0.5, 2, 1, 8),
      ];
    },
  },
  {
    kind: 'generated-cases',
    name: 'Many steps over a long ray',
    points: 1,
    message: 'With many steps over a long ray your result drifts from the exact per-step product.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'raymarch long');
      return [
        ray(r, 'long ray', 0.5, 5, 32, 128, 5, 20),
        ray(r, 'long ray', 0.5, 5, 32, 128, 5, 20),
      ];
    },
  },
];
