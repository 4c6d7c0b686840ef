// What an exercise is to the grader: the public description the page shows
// (ExerciseInfo, from types.ts), the function the student writes, the reference
// solution, the library helpers the student may call, and the checks. One
// exercise lives in exercises/<id>/: exercise.ts exports the public definition
// (safe for the page's bundle), hidden.ts exports the hidden checks (imported only
// by the command line and the tests).
import type { ExerciseInfo, GradeOutcome } from './types.ts';
import type { GeneratedCasesCheck } from './checks/generated.ts';
import type { DistributionCheck } from './checks/distribution.ts';
import type { TrackingCheck } from './checks/tracking.ts';

/** Parameter types the grader can feed: scalars, or the rng state pointer it seeds itself. */
export type ParamType = 'f32' | 'u32' | 'i32' | 'ptr<function, u32>';

export interface SubjectFunction {
  name: string;
  params: readonly { name: string; type: ParamType }[];
  result: 'f32';
}

/** One call of the student's function (the rng pointer, if any, is not listed: the grader seeds it). */
export interface CaseSpec {
  label: string;
  args: readonly number[];
  /** Failure message for this case when it needs its own words (e.g. a hard case). */
  message?: string;
}

interface CheckBase {
  name: string;
  points: number;
  /** Failure message in the chapter's words; the grader appends the first failing case. */
  message: string;
}

/**
 * Deterministic comparison with the reference solution on the same calls:
 * pass when |student − reference| ≤ atol + rtol·|reference| for every case (both
 * infinite with the same sign also passes; NaN never does).
 */
export interface CasesCheck extends CheckBase {
  kind: 'cases';
  cases: readonly CaseSpec[];
  rtol: number;
  atol: number;
  /** Which argument is the x axis of the figure the page draws, and its label. */
  figure?: { argIndex: number; xLabel: string };
}

/**
 * Distribution of a sampler's output against an analytic CDF by Pearson's chi-square
 * test. The grader feeds stratified uniforms ξ_k = (k + u_k)/n (u_k from the seed)
 * through `args(ξ)`; `bins` equiprobable bins under the CDF.
 */
export interface ChiSquareCheck extends CheckBase {
  kind: 'chi-square';
  n: number;
  bins: number;
  /** Significance level of the test. */
  alpha: number;
  args: (xi: number) => number[];
  /** The analytic CDF of the output, and its inverse for the bin edges. */
  cdf: (x: number) => number;
  inverseCdf: (p: number) => number;
  xLabel: string;
}

/**
 * A binary Monte Carlo estimator (0 or 1 per call) whose mean must be `expected`:
 * 'mean' is a two-sided z-test of the sample mean against `expected`; 'variance'
 * a two-sided z-test of the sample variance against T(1 − T), the variance of a
 * Bernoulli(T) estimator. n independent calls, each with its own rng stream.
 */
export interface MonteCarloCheck extends CheckBase {
  kind: 'mean' | 'variance';
  args: readonly number[];
  n: number;
  /** The exact expectation (float64), e.g. exp(−τ). */
  expected: number;
  /** Two-sided significance level. */
  alpha: number;
}

export type CheckSpec =
  | CasesCheck
  | ChiSquareCheck
  | MonteCarloCheck
  | GeneratedCasesCheck
  | DistributionCheck
  | TrackingCheck;

/** Library functions the student may call, linked in front of the submission. */
export interface Helpers {
  /** WESL import lines, e.g. `import package::rng::rngNextFloat;`. */
  imports: readonly string[];
  /**
   * Plain WGSL that calls every imported helper once (the linker keeps only what is
   * called), plus any exercise-specific helper functions the statement describes.
   */
  wgsl: string;
  /**
   * Private u32 counters the helpers declare and increment (e.g. extinction() lookups,
   * random numbers drawn). The harness zeroes them before each call and writes them
   * after the result, so checks can see how the estimator uses the helpers.
   */
  counters?: readonly string[];
  /**
   * Private f32 variables the helpers declare and read (a hidden medium's parameters).
   * The harness fills them from extra input words after the function's arguments, so
   * the student's code never sees them as arguments.
   */
  extraInputs?: readonly string[];
}

/**
 * A gradable exercise. It extends the page's ExerciseInfo so that the page can use
 * what loadExercise() returns both for display and for gradeSubmission().
 */
export interface ExerciseDefinition extends ExerciseInfo {
  subject: SubjectFunction;
  /** The reference solution: WESL that defines `subject.name`, usually by calling the library. */
  reference: string;
  helpers?: Helpers;
  /** Iteration budget per GPU thread, over all loops of the submission. */
  loopBudget?: number;
  /** Public checks (run in the page and by the command line). */
  checks: readonly CheckSpec[];
  /** Hidden checks, only present when loaded from hidden.ts by the command line. */
  hiddenChecks?: readonly CheckSpec[];
}

/** One known-wrong submission's expected outcome (exercises/<id>/wrong/expected.json). */
export interface WrongExpectation {
  file: string;
  /** Expected outcome status, default 'graded'. */
  status?: GradeOutcome['status'];
  /**
   * Expected score range [min, max] (inclusive) when graded, or 'full' for full marks
   * whatever the exercise's total (e.g. a correct solution in an unusual encoding).
   */
  score?: [number, number] | 'full';
  reason: string;
}

/** The signature as the statement writes it, e.g. `fn transmittance(sigmaT: f32, d: f32) -> f32`. */
export function signatureText(subject: SubjectFunction): string {
  const params = subject.params.map((p) => `${p.name}: ${p.type}`).join(', ');
  return `fn ${subject.name}(${params}) -> ${subject.result}`;
}
