// The contract between the grading core (src/grading/, the instructor's `grade`
// command) and the in-page exercise widget (src/widgets/exercise/). One core grades
// in both places: the page runs the public checks on navigator.gpu, the command line
// runs public and hidden checks on Dawn in Node. Hidden checks live in
// exercises/<id>/hidden.ts, which only the command line imports, so they never reach
// the page's bundle.

/** A position in the student's source, 1-based, as the shader compiler reports it. */
export interface SourceDiagnostic {
  line: number;
  column: number;
  message: string;
  severity: 'error' | 'warning';
}

/** What a student submits: the WGSL (or TypeScript, for CPU exercises) source text. */
export interface Submission {
  exerciseId: string;
  source: string;
}

/**
 * The public part of an exercise, safe to ship to the page (exercises/<id>/exercise.ts).
 * The statement is Markdown with TeX math; the chapter build renders it with KaTeX.
 */
export interface ExerciseInfo {
  id: string;
  /** Chapter file stem it is embedded in, e.g. `02-extinction-and-transmittance`. */
  chapter: string;
  title: string;
  /** WGSL source the editor starts from (and Reset returns to). */
  starter: string;
  /** The function the student writes, e.g. `fn transmittance(sigmaT: f32, d: f32) -> f32`. */
  signature: string;
  /** Revealed one at a time in the page. */
  hints: readonly string[];
  /** Tolerances and tests, in the chapter's words, as the statement states them. */
  gradingNotes: string;
}

/** How one check compares the student's output with the reference's. */
export type Verdict = 'pass' | 'fail';

/** Data the page can draw next to a check: both outputs, over an x axis or as images. */
export type CheckFigure =
  | { kind: 'series'; x: number[]; xLabel: string; student: number[]; reference: number[] }
  | {
      kind: 'histogram';
      edges: number[];
      observed: number[];
      expected: number[];
      xLabel: string;
    }
  | { kind: 'image'; width: number; height: number; student: number[]; reference: number[] };

export interface CheckResult {
  name: string;
  visibility: 'public' | 'hidden';
  verdict: Verdict;
  points: number;
  maxPoints: number;
  /** In the chapter's words; for failures, says what is wrong and where to look. */
  message: string;
  /** Short table of cases: arguments, the student's value, the reference's value. */
  samples?: { args: string; student: string; reference: string }[];
  figure?: CheckFigure;
}

/** The outcome of running a submission; `status` says whether grading could happen. */
export type GradeOutcome =
  | {
      status: 'graded';
      checks: CheckResult[];
      score: number;
      maxScore: number;
      /** Seed the stochastic checks used (reported so a grade can be reproduced). */
      seed: number;
    }
  | { status: 'compile-error'; diagnostics: SourceDiagnostic[]; message: string }
  | { status: 'wrong-signature'; message: string }
  /** A loop ran past its iteration budget (loops are bounded by source instrumentation). */
  | { status: 'loop-budget'; message: string }
  /**
   * Refused before compilation: too large, or declarations the harness does not allow
   * (bindings, entry points, `enable`/`requires`, `override`, reserved names). The
   * message says which and where. The student's to fix, like a compile error.
   */
  | { status: 'rejected'; message: string }
  /**
   * Grader-side failures, not the student's: 'timeout' (a GPU watchdog or the whole
   * run's wall-clock limit), 'device-lost', 'internal-error' (an exception in the
   * grader). Reports present them as "grading failed", never as a score of 0.
   */
  | { status: 'timeout' | 'device-lost' | 'internal-error'; message: string };

/** The statuses that are failures of the grader (or its machine), not of the submission. */
export const GRADER_SIDE_STATUSES: readonly GradeOutcome['status'][] = [
  'timeout',
  'device-lost',
  'internal-error',
];

/** Whether `outcome` is a failure on the grader's side (to be regraded, not scored). */
export function isGraderSideFailure(
  outcome: GradeOutcome,
): outcome is Extract<GradeOutcome, { status: 'timeout' | 'device-lost' | 'internal-error' }> {
  return GRADER_SIDE_STATUSES.includes(outcome.status);
}

export interface GradeOptions {
  /** Which checks to run: the page runs 'public'; the instructor 'all'. */
  which: 'public' | 'all';
  seed?: number;
  /** Watchdog: milliseconds before a GPU submission is abandoned. */
  timeoutMs?: number;
  signal?: AbortSignal;
  onProgress?: (done: number, total: number) => void;
}
