// Shared pieces of the two deployment kits: writing a file tree, the shell wrapper's
// last-resort results.json (when Node itself cannot run), and the names the kits,
// their scripts and the tests agree on.
import { chmodSync, mkdirSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { renderReport } from '../reports.ts';
import type { Platform } from './driver.ts';

/** The project copy's folder inside a kit. */
export const PROJECT_FOLDER = 'scatterbook';
/** Environment variable that points the kits' scripts at another installed project (the tests use this checkout). */
export const PROJECT_ENV = 'SCATTERBOOK_PROJECT';

export interface KitFile {
  path: string;
  data: Uint8Array;
  mode?: number;
}

export function text(path: string, content: string, mode?: number): KitFile {
  return { path, data: new TextEncoder().encode(content), ...(mode ? { mode } : {}) };
}

export function writeTree(root: string, files: readonly KitFile[]): void {
  for (const file of files) {
    const path = join(root, file.path);
    mkdirSync(dirname(path), { recursive: true });
    writeFileSync(path, file.data);
    if (file.mode) chmodSync(path, file.mode);
  }
}

/** The report of a grader failure, for a shell script to write when Node cannot run. */
export function lastResortReport(platform: Platform, exerciseId: string, title: string): string {
  return renderReport(
    platform,
    {
      status: 'internal-error',
      message: 'the grading program could not run on the grader machine (see the autograder log).',
    },
    { exerciseId, title },
  ).trim();
}

/** Single-quoted for sh: safe for any text. */
export function shellQuote(value: string): string {
  return `'${value.replace(/'/g, `'\\''`)}'`;
}

/**
 * The shell lines shared by run_autograder and entrypoint.sh: run the driver under
 * an outer `timeout`, then make sure results.json exists and parses, else write
 * `fallback` (a heredoc, so no quoting of the JSON is needed).
 */
export function driverInvocation(options: {
  platform: Platform;
  /** The exercise id as a shell word (quoted by the caller). */
  exerciseWord: string;
  timeLimitS: number;
  results: string;
  fallback: string;
}): string {
  const outer = options.timeLimitS + 60;
  return `mkdir -p "$(dirname "${options.results}")"
rm -f "${options.results}"
# The driver kills the grader shortly after the limit; the outer timeout only guards
# against the driver itself hanging.
( cd "$PROJECT" && timeout --kill-after=5 ${outer} node --import tsx src/grading/kit/driver.ts \\
    ${options.platform} --exercise ${options.exerciseWord} --time-limit ${options.timeLimitS} )
status=$?
if ! node -e 'JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"))' "${options.results}" 2>/dev/null; then
  echo "driver exited with status $status and left no valid results.json; writing a grader-failure report" >&2
  cat > "${options.results}" <<'SCATTERBOOK_JSON'
${options.fallback}
SCATTERBOOK_JSON
fi
exit 0
`;
}
