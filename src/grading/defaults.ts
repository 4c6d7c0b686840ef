// The grader's default watchdog, apart from grade.ts so that the exercise widget can show
// it without loading the grader (which brings the WESL linker and the shader library, and
// is loaded on the first check: src/widgets/exercise/exerciseSource.ts).

/** Milliseconds a student's GPU submission may run before the watchdog stops it. */
export const DEFAULT_TIMEOUT_MS = 20_000;
