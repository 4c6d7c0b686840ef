// Beer's law: hidden tests, the hard cases of physics.md §9 (rows 10, 11) and §1. Every
// case is drawn from the grading seed (src/grading/checks/generated.ts), and each check
// pairs its edge cases with ordinary partners, so neither a table of inputs nor a
// constant guess (1 for "nothing attenuated", 0 for "opaque") passes it.
import type { CaseSpec, CheckSpec } from '../../src/grading/exercise.ts';
import { caseSampler, type CaseSampler } from '../../src/grading/checks/generated.ts';
import { TOLERANCE } from './exercise.ts';

const f = Math.fround;

/** A medium of optical thickness τ ∈ [τLow, τHigh]: σt log-uniform over [1e-3, 1e4] 1/m. */
function medium(r: CaseSampler, tauLow: number, tauHigh: number, label: string): CaseSpec {
  const sigmaT = r.logUniform(1e-3, 1e4);
  const tau = r.logUniform(tauLow, tauHigh);
  return { label, args: [sigmaT, f(tau / sigmaT)] };
}

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'generated-cases',
    name: 'Media of any thickness',
    points: 2,
    message: 'Your transmittance does not follow T = exp(−σt d) for some media.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'beer-law media');
      // Many ordinary cases: deterministic cases cost one dispatch, and a submission right
      // only in part of the domain (the public region) fails a check of k uniform draws unless
      // all miss the wrong part: (1 − q)^k, 0.001 for q = 25 % at k = 24 (red team, issue 15).
      return Array.from({ length: 32 }, (_, k) => medium(r, 1e-4, 13, `medium ${k + 1}`));
    },
  },
  {
    kind: 'generated-cases',
    name: 'Zero thickness',
    points: 1,
    message:
      'With no distance or no medium nothing is attenuated: T must be exactly 1 (and slightly ' +
      'less than 1 for a thin slab).',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'beer-law zero thickness');
      return [
        { label: 'd = 0', args: [r.logUniform(1e-3, 1e4), 0] },
        { label: 'σt = 0', args: [0, r.logUniform(1e-3, 1e4)] },
        medium(r, 0.01, 0.1, 'thin slab'),
        medium(r, 0.01, 0.1, 'thin slab'),
      ];
    },
  },
  {
    kind: 'generated-cases',
    name: 'Optically thick media',
    points: 1,
    message:
      'For an optically thick medium (τ ≥ 1e5) the transmittance is 0; NaN or infinity means the ' +
      'exponent overflowed: keep τ ≥ 0 and let exp underflow to 0. Moderately thick media must ' +
      'still give their small T.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'beer-law thick');
      const huge = r.logUniform(1e5, 1e7);
      return [
        { label: 'τ ≥ 1e5', args: [huge, f(r.logUniform(1e5, 1e7) / huge)] },
        // σt = 1e6-ish over 1e-6-ish m: a large σt times a tiny d (§9 row 11).
        medium(r, 0.5, 3, 'large σt over a tiny distance'),
        medium(r, 3, 12, 'thick but not opaque'),
      ].map((c, k) =>
        k === 1 ? { ...c, args: [f((c.args[0] ?? 1) * 1e6), f((c.args[1] ?? 0) / 1e6)] } : c,
      );
    },
  },
  {
    kind: 'generated-cases',
    name: 'Negative inputs stay physical',
    points: 2,
    message:
      'Your transmittance must be exactly 1 for a negative σt or d (treat τ < 0 as no medium): ' +
      'clamp the optical thickness to τ ≥ 0 (neither exp(−τ) nor exp(−|τ|) is right for τ < 0), ' +
      'and stay exp(−σt d) for positive inputs.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'beer-law negative');
      const a = medium(r, 0.05, 5, 'positive partner');
      const b = medium(r, 0.05, 5, 'positive partner');
      return [
        { label: 'negative σt', args: [-(a.args[0] ?? 1), a.args[1] ?? 1] },
        a,
        { label: 'negative d', args: [b.args[0] ?? 1, -(b.args[1] ?? 1)] },
        b,
      ];
    },
  },
];
