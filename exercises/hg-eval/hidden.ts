// Henyey–Greenstein evaluation: hidden tests from physics.md §9 rows 1, 3, 4 and §2.5.
// Cases are drawn from the grading seed (src/grading/checks/generated.ts); the only
// fixed case is the forward peak g = 0.999, μ = 1 (§9 row 1), which a check of f32
// cancellation needs. Each check has cases where the isotropic 1/(4π) is wrong, so a
// table of inputs plus a constant guess passes none.
import type { CaseSpec, CheckSpec } from '../../src/grading/exercise.ts';
import { caseSampler, type CaseSampler } from '../../src/grading/checks/generated.ts';
import { TOLERANCE } from './exercise.ts';

/**
 * An ordinary (g, μ): |g| ≤ 0.9 keeps 1 + g² − 2gμ ≥ 0.01, where even the textbook
 * form is accurate to 4e-5 in f32, well inside the 1e-4 tolerance.
 */
function ordinary(r: CaseSampler, label: string, gLow = 0): CaseSpec {
  return { label, args: [r.sign() * r.uniform(gLow, 0.9), r.uniform(-1, 1)] };
}

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'generated-cases',
    name: 'Arbitrary asymmetries and angles',
    points: 1,
    message: 'Your phase function is wrong for some g and μ: check the formula term by term.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hg-eval ordinary');
      // Many ordinary cases: deterministic cases cost one dispatch, and a submission right
      // only in part of the domain (the public region) fails a check of k uniform draws unless
      // all miss the wrong part: (1 − q)^k, 0.001 for q = 25 % at k = 24 (red team, issue 15).
      return Array.from({ length: 32 }, (_, k) => ordinary(r, `case ${k + 1}`));
    },
  },
  {
    kind: 'generated-cases',
    name: 'Far tail and sign convention',
    points: 2,
    message:
      'In the far tail of a strong lobe (|g| near 1, μ on the other side) your value is wrong: ' +
      'p is tiny there (about 2e-5 sr⁻¹ at g = 0.999); a mirrored convention (−μ) puts the peak ' +
      'on the wrong side.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hg-eval tail');
      return Array.from({ length: 4 }, (_, k) => {
        const side = k % 2 === 0 ? 1 : -1;
        return {
          label: side > 0 ? 'forward lobe, backward tail' : 'backward lobe, forward tail',
          args: [side * r.uniform(0.95, 0.999), -side * r.uniform(0.99, 1)],
        };
      });
    },
  },
  {
    kind: 'generated-cases',
    name: 'Isotropic scattering',
    points: 1,
    message:
      'At g = 0 Henyey–Greenstein is isotropic: 1/(4π) = 0.0795775 sr⁻¹ for every μ (and only there).',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hg-eval isotropic');
      const iso = Array.from({ length: 3 }, () => ({
        label: 'g = 0',
        args: [0, r.uniform(-1, 1)],
      }));
      return [...iso, ordinary(r, 'g ≠ 0', 0.1), ordinary(r, 'g ≠ 0', 0.1)];
    },
  },
  {
    kind: 'generated-cases',
    name: 'Forward peak',
    points: 1,
    message:
      'At the forward peak of a strong lobe your value is off: 1 + g² − 2gμ cancels in f32 when ' +
      'g and μ are near 1; compute it as (1 − g)² + 2g(1 − μ) (chapter 3, “In 32-bit floating point”).',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hg-eval peak');
      return [
        { label: 'g = 0.999, μ = 1 (the sharp forward peak)', args: [0.999, 1] },
        ...Array.from({ length: 3 }, () => ({
          label: 'near the peak',
          args: [r.uniform(0.99, 0.999), r.uniform(0.9999, 1)],
        })),
        { label: 'peak of a moderate lobe', args: [r.uniform(0.5, 0.9), 1] },
      ];
    },
  },
];
