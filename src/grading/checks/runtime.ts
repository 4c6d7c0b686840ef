// What a check runner in src/grading/checks/ gets from the grading core (grade.ts):
// a way to run calls through the submission's program (optionally linked with other
// helpers, e.g. a hidden medium) and the core's formatting, so the runners stay free
// of GPU plumbing and can be tested on the CPU.
import type { ExerciseDefinition, Helpers } from '../exercise.ts';

export interface RunOutput {
  /** One result per call. */
  values: number[];
  /** counters[k][i]: helper counter k (Helpers.counters order) after call i. */
  counters: number[][];
}

export interface CheckRuntime {
  exercise: ExerciseDefinition;
  /** The grading seed. */
  seed: number;
  /**
   * Runs `calls` (the function's arguments, then the helpers' extra inputs) through the
   * program under grading, linked with `helpers` (default: the exercise's). Each call
   * gets its own random stream derived from `streamSeed`. Runs with the same arguments
   * are shared between checks.
   */
  run(
    calls: readonly (readonly number[])[],
    streamSeed: number,
    what: string,
    helpers?: Helpers,
    /** Runs with the same key (and the same program) are done once and shared. */
    shareKey?: string,
  ): Promise<RunOutput>;
  formatArgs(args: readonly number[]): string;
  formatNumber(value: number): string;
}
