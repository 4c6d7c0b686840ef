// Deterministic checks whose cases are drawn from the grading seed. A fixed list of
// hidden inputs can be learnt (from a leaked report, a classmate, an old page) and
// answered by a lookup table; cases drawn afresh from each grading seed over the valid
// domain cannot. Each generator mixes its own salt into the seed, so two checks (or
// two exercises) never draw the same stream, and one seed always reproduces a grade.
import type { CaseSpec, CasesCheck } from '../exercise.ts';
import { mixSeed, seededUniforms } from '../stats.ts';

/**
 * A CasesCheck whose cases come from `generate(seed)`; compared with the reference
 * like a CasesCheck (|student − reference| ≤ atol + rtol·|reference|).
 */
export interface GeneratedCasesCheck extends Omit<CasesCheck, 'kind' | 'cases' | 'figure'> {
  kind: 'generated-cases';
  /** The cases for one grading seed: fixed edge cases and seeded ones. */
  generate: (seed: number) => readonly CaseSpec[];
}

/** FNV-1a of a string, to turn a generator's name into a seed salt. */
export function saltOf(text: string): number {
  let h = 0x811c9dc5;
  for (let i = 0; i < text.length; i++) {
    h = Math.imul(h ^ text.charCodeAt(i), 0x01000193) >>> 0;
  }
  return h;
}

/** Seeded draws over physical ranges; every value is rounded to f32 (what the GPU gets). */
export interface CaseSampler {
  /** Uniform in [lo, hi). */
  uniform(lo: number, hi: number): number;
  /** Log-uniform in [lo, hi) (lo, hi > 0): every decade equally likely. */
  logUniform(lo: number, hi: number): number;
  /** +1 or −1 with equal probability. */
  sign(): number;
  /** An integer in [lo, hi], uniformly. */
  integer(lo: number, hi: number): number;
}

export function caseSampler(seed: number, salt: string): CaseSampler {
  const next = seededUniforms(mixSeed(seed >>> 0, saltOf(salt)));
  const f = Math.fround;
  return {
    uniform: (lo, hi) => f(lo + (hi - lo) * next()),
    logUniform: (lo, hi) => f(Math.exp(Math.log(lo) + (Math.log(hi) - Math.log(lo)) * next())),
    sign: () => (next() < 0.5 ? -1 : 1),
    integer: (lo, hi) => lo + Math.min(hi - lo, Math.floor((hi - lo + 1) * next())),
  };
}

/** The CasesCheck a GeneratedCasesCheck is under one seed. */
export function casesForSeed(check: GeneratedCasesCheck, seed: number): CasesCheck {
  return {
    kind: 'cases',
    name: check.name,
    points: check.points,
    message: check.message,
    rtol: check.rtol,
    atol: check.atol,
    cases: check.generate(seed),
  };
}
