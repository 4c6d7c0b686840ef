// The dipole: hidden tests (physics.md §9 rows 19–21, §6.1). Materials and distances are
// drawn from the grading seed (src/grading/checks/generated.ts); each check pairs its
// edge cases (α' = 0, σa = 0, no medium) with ordinary partners, so neither a table of
// inputs nor a constant guess (0) passes it. Lengths in mm, R_d in mm⁻².
import type { CaseSpec, CheckSpec } from '../../src/grading/exercise.ts';
import { caseSampler, type CaseSampler } from '../../src/grading/checks/generated.ts';

const f = Math.fround;

/**
 * Hidden tolerance: relative only in practice (atol 1e-15 mm⁻², below every value drawn
 * here), so that far from the source, where R_d is 1e-12…1e-6 mm⁻², the test still
 * compares digits (the public atol of 1e-9 would accept anything there).
 */
const HIDDEN_TOLERANCE = { rtol: 1e-4, atol: 1e-15 } as const;

interface Material {
  sigmaSPrime: number;
  sigmaA: number;
  eta: number;
}

/** σs' ∈ [0.1, 20] mm⁻¹, σa ∈ [1e-4, 0.5] mm⁻¹ (log-uniform), η ∈ [1.05, 1.6]. */
function material(r: CaseSampler): Material {
  return {
    sigmaSPrime: r.logUniform(0.1, 20),
    sigmaA: r.logUniform(1e-4, 0.5),
    eta: r.uniform(1.05, 1.6),
  };
}

/** A distance of 0.01 to 20 mean free paths z_r = 1/σt' (log-uniform). */
function ordinary(r: CaseSampler, label: string, m: Material = material(r)): CaseSpec {
  const zr = 1 / (m.sigmaSPrime + m.sigmaA);
  return { label, args: [m.sigmaSPrime, m.sigmaA, m.eta, f(zr * r.logUniform(0.01, 20))] };
}

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'generated-cases',
    name: 'Materials and distances',
    points: 2,
    message:
      "For some materials or distances your profile does not match the dipole: check σt', α', " +
      'σtr, z_r, z_v = z_r(1 + 4A/3) and both source terms.',
    ...HIDDEN_TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'dipole ordinary');
      // Many ordinary cases: deterministic cases cost one dispatch, and a submission right
      // only in part of the domain (the public region) fails a check of k uniform draws unless
      // all miss the wrong part: (1 − q)^k, 0.001 for q = 25 % at k = 24 (red team, issue 15).
      const cases = Array.from({ length: 24 }, (_, k) => ordinary(r, `material ${k + 1}`));
      const m = material(r);
      return [...cases, { label: 'r = 0', args: [m.sigmaSPrime, m.sigmaA, m.eta, 0] }];
    },
  },
  {
    kind: 'generated-cases',
    name: 'No scattering',
    points: 1,
    message:
      "With σs' = 0 (α' = 0) nothing scatters back: R_d must be exactly 0; a weakly " +
      'scattering material still reflects.',
    ...HIDDEN_TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'dipole no scattering');
      const zero = ordinary(r, "α' = 0");
      const weak = {
        sigmaSPrime: r.logUniform(0.01, 0.1),
        sigmaA: r.logUniform(0.1, 1),
        eta: r.uniform(1.05, 1.6),
      };
      return [
        { ...zero, args: [0, ...zero.args.slice(1)] },
        ordinary(r, 'weak scattering', weak),
        ordinary(r, 'partner'),
      ];
    },
  },
  {
    kind: 'generated-cases',
    name: 'No absorption',
    points: 1,
    message:
      "With σa = 0 (α' = 1, σtr = 0) the profile is a finite power law; yours is wrong there.",
    ...HIDDEN_TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'dipole no absorption');
      return [0, 1].map((k) => {
        const c = ordinary(r, k === 0 ? 'σa = 0' : 'σa = 0, r = 0');
        const [sp = 1, , eta = 1.3, radius = 1] = c.args;
        return { ...c, args: [sp, 0, eta, k === 0 ? radius : 0] };
      });
    },
  },
  {
    kind: 'generated-cases',
    name: 'No medium',
    points: 1,
    message: "With σs' = σa = 0 there is no medium: return 0 instead of dividing by σt' = 0 (NaN).",
    ...HIDDEN_TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'dipole no medium');
      const none = ordinary(r, "σs' = σa = 0");
      return [{ ...none, args: [0, 0, ...none.args.slice(2)] }, ordinary(r, 'partner')];
    },
  },
  {
    kind: 'generated-cases',
    name: 'Far from the source',
    points: 1,
    message:
      'Far from the entry point (σtr·r between 3 and 8, e.g. r ≈ 100 mm in skim milk) your profile ' +
      'is off: there the exponential tail dominates and the virtual source still matters.',
    ...HIDDEN_TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'dipole far');
      return Array.from({ length: 2 }, () => {
        const m = material(r);
        const st = m.sigmaSPrime + m.sigmaA;
        const sigmaTr = Math.sqrt(3 * m.sigmaA * st);
        return {
          label: 'far field',
          args: [m.sigmaSPrime, m.sigmaA, m.eta, f(r.uniform(3, 8) / sigmaTr)],
        };
      });
    },
  },
];
