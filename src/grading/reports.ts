// Reports of one graded submission in the formats course autograders read:
// - Gradescope results.json (https://gradescope-autograders.readthedocs.io/en/latest/specs/,
//   "Output format"): top-level score, output, tests[] with name, score, max_score,
//   status ('passed' | 'failed'), visibility ('hidden' | 'after_due_date' |
//   'after_published' | 'visible') and output; execution_time (seconds) and
//   stdout_visibility at the top level;
// - PrairieLearn results.json (https://prairielearn.readthedocs.io/en/latest/externalGrading/,
//   "Grading results"): gradable, score in [0, 1], message, output, tests[] with name,
//   points, max_points, message, output;
// - our GradeOutcome as JSON;
// - JUnit XML (testsuite / testcase / failure), for CI dashboards.
import { isGraderSideFailure, type CheckResult, type GradeOutcome } from './types.ts';

export type ReportFormat = 'gradescope' | 'prairielearn' | 'json' | 'junit';
export const REPORT_FORMATS: readonly ReportFormat[] = [
  'gradescope',
  'prairielearn',
  'json',
  'junit',
];

export interface ReportContext {
  exerciseId: string;
  title: string;
  /** Wall-clock seconds the grading took (Gradescope's `execution_time`). */
  executionTimeS?: number;
}

/** One line per outcome that is not a grade (compile error, signature, loop budget, …). */
export function outcomeHeadline(outcome: GradeOutcome): string {
  switch (outcome.status) {
    case 'graded':
      return `Score ${formatPoints(outcome.score)} / ${formatPoints(outcome.maxScore)} (seed ${outcome.seed})`;
    case 'compile-error': {
      const where = outcome.diagnostics
        .filter((d) => d.severity === 'error')
        .map((d) => `line ${d.line}, column ${d.column}: ${d.message}`)
        .join('\n');
      return `Compile error — ${outcome.message}${where ? `\n${where}` : ''}`;
    }
    case 'wrong-signature':
      return `Wrong signature — ${outcome.message}`;
    case 'loop-budget':
      return `Loop budget exceeded — ${outcome.message}`;
    case 'rejected':
      return `Submission refused — ${outcome.message}`;
    case 'timeout':
      return `Timed out — ${outcome.message}`;
    case 'device-lost':
      return `GPU device lost — ${outcome.message}`;
    case 'internal-error':
      return `Grader error — ${outcome.message}`;
  }
}

function formatPoints(points: number): string {
  return Number.isInteger(points) ? String(points) : points.toFixed(2);
}

function checkOutput(check: CheckResult): string {
  const rows = (check.samples ?? [])
    .slice(0, 12)
    .map((s) => `  ${s.args}: yours ${s.student}, reference ${s.reference}`);
  return [check.message, ...rows].join('\n');
}

/** Points of the public checks only: what a student may see before grades are published. */
function publicPoints(checks: readonly CheckResult[]): { score: number; max: number } {
  const visible = checks.filter((c) => c.visibility === 'public');
  return {
    score: visible.reduce((sum, c) => sum + c.points, 0),
    max: visible.reduce((sum, c) => sum + c.maxPoints, 0),
  };
}

/** Shown to the student for a grader-side failure: what happened, and that it is not their score. */
function graderFailureText(outcome: GradeOutcome): string {
  return (
    `Grading failed on the grader's side (${outcome.status}), not because of your code: ` +
    `${outcomeHeadline(outcome)}\nThis is not your score; the submission will be regraded.`
  );
}

/** Test names for the student's own non-graded outcomes. */
const STATUS_TEST_NAMES: Record<
  Exclude<GradeOutcome['status'], 'graded' | 'timeout' | 'device-lost' | 'internal-error'>,
  string
> = {
  'compile-error': 'Your shader compiles',
  'wrong-signature': 'Your function has the signature the grader calls',
  'loop-budget': 'Your loops end within their budget',
  rejected: 'Your submission is accepted by the grader',
};

export const GRADER_FAILURE_TEST_NAME = 'Grading failed — will be regraded';

/**
 * Gradescope's results.json. Per the spec, `score` is optional at the top level when
 * every test has one, and overrides their sum when present. So:
 * - graded: top-level `score` is the total (Gradescope needs it for the grade); hidden
 *   checks are tests with visibility 'after_published'; the top-level `output`, which
 *   students see at once, names only the public checks' points.
 * - a grader-side failure (timeout, device loss, internal error): no top-level score,
 *   one visible test "Grading failed — will be regraded" worth 0 of 0 points with the
 *   reason, so nothing reads as the student's mark; extra_data.grader_failure lets the
 *   instructor find these submissions to regrade them.
 * - the student's own non-graded outcomes (compile error, refused, wrong signature,
 *   every check looping past its budget): score 0 and a visible test saying why.
 * `stdout_visibility` is 'hidden': the command's stderr summary names hidden checks.
 */
export function gradescopeReport(outcome: GradeOutcome, context: ReportContext): object {
  const timing =
    context.executionTimeS !== undefined
      ? { execution_time: Math.max(0, Math.round(context.executionTimeS)) }
      : {};
  if (isGraderSideFailure(outcome)) {
    const text = graderFailureText(outcome);
    return {
      ...timing,
      output: `${context.title}: ${text}`,
      stdout_visibility: 'hidden',
      extra_data: { grader_failure: outcome.status },
      tests: [
        {
          name: GRADER_FAILURE_TEST_NAME,
          score: 0,
          max_score: 0,
          status: 'failed',
          visibility: 'visible',
          output: text,
        },
      ],
    };
  }
  if (outcome.status !== 'graded') {
    return {
      score: 0,
      ...timing,
      output: `${context.title}: ${outcomeHeadline(outcome)}`,
      stdout_visibility: 'hidden',
      tests: [
        {
          name: STATUS_TEST_NAMES[outcome.status],
          score: 0,
          max_score: 0,
          status: 'failed',
          visibility: 'visible',
          output: outcomeHeadline(outcome),
        },
      ],
    };
  }
  const visible = publicPoints(outcome.checks);
  const hidden = outcome.checks.some((c) => c.visibility === 'hidden');
  return {
    score: outcome.score,
    ...timing,
    output:
      `${context.title}: public checks ${formatPoints(visible.score)} / ${formatPoints(visible.max)} points` +
      (hidden ? '; the hidden checks are shown when grades are published.' : '.') +
      ` (seed ${outcome.seed})`,
    stdout_visibility: 'hidden',
    tests: outcome.checks.map((check) => ({
      name: check.name,
      score: check.points,
      max_score: check.maxPoints,
      status: check.verdict === 'pass' ? 'passed' : 'failed',
      visibility: check.visibility === 'hidden' ? 'after_published' : 'visible',
      output: checkOutput(check),
    })),
  };
}

/**
 * PrairieLearn's results.json. `gradable: false` (PrairieLearn shows the submission
 * as invalid without charging an attempt) for submissions that cannot be graded
 * because of their form (they do not compile, are refused, have the wrong signature)
 * and for grader-side failures (timeout, device loss, internal error), whose message
 * says so; an endless loop is the student's program and scores 0. Hidden checks show
 * only their name and pass/fail: no arguments, reference values, messages or samples.
 */
export function prairieLearnReport(outcome: GradeOutcome, context: ReportContext): object {
  if (outcome.status !== 'graded') {
    const gradable = outcome.status === 'loop-budget';
    const message = isGraderSideFailure(outcome)
      ? graderFailureText(outcome)
      : outcomeHeadline(outcome);
    return {
      gradable,
      score: 0,
      message,
      output: `${context.title}\n${message}`,
      tests: [],
    };
  }
  const visible = publicPoints(outcome.checks);
  return {
    gradable: true,
    score: outcome.maxScore > 0 ? outcome.score / outcome.maxScore : 0,
    message: `${outcomeHeadline(outcome)}; public checks ${formatPoints(visible.score)} / ${formatPoints(visible.max)}`,
    output: context.title,
    tests: outcome.checks.map((check) => {
      const verdict = check.verdict === 'pass' ? 'passed' : 'failed';
      return check.visibility === 'hidden'
        ? {
            name: `${check.name} (hidden)`,
            points: check.points,
            max_points: check.maxPoints,
            message: verdict,
          }
        : {
            name: check.name,
            points: check.points,
            max_points: check.maxPoints,
            message: check.message,
            output: checkOutput(check),
          };
    }),
  };
}

export function escapeXml(text: string): string {
  return (
    text
      .replace(/&/g, '&amp;')
      .replace(/</g, '&lt;')
      .replace(/>/g, '&gt;')
      .replace(/"/g, '&quot;')
      .replace(/'/g, '&apos;')
      // Characters XML 1.0 cannot carry at all.
      // eslint-disable-next-line no-control-regex
      .replace(/[\u0000-\u0008\u000B\u000C\u000E-\u001F]/g, '')
  );
}

/** JUnit XML: one testcase per check; a submission that cannot be graded is one errored case. */
export function junitReport(outcome: GradeOutcome, context: ReportContext): string {
  const suite = escapeXml(`exercise.${context.exerciseId}`);
  const lines = ['<?xml version="1.0" encoding="UTF-8"?>'];
  if (outcome.status !== 'graded') {
    lines.push(
      `<testsuites name="${suite}" tests="1" failures="0" errors="1">`,
      `  <testsuite name="${suite}" tests="1" failures="0" errors="1">`,
      `    <testcase name="${escapeXml(outcome.status)}" classname="${suite}">`,
      `      <error message="${escapeXml(outcome.message)}" type="${escapeXml(outcome.status)}">${escapeXml(outcomeHeadline(outcome))}</error>`,
      '    </testcase>',
      '  </testsuite>',
      '</testsuites>',
    );
    return `${lines.join('\n')}\n`;
  }
  const failures = outcome.checks.filter((c) => c.verdict === 'fail').length;
  const count = outcome.checks.length;
  lines.push(
    `<testsuites name="${suite}" tests="${count}" failures="${failures}" errors="0">`,
    `  <testsuite name="${suite}" tests="${count}" failures="${failures}" errors="0">`,
  );
  for (const check of outcome.checks) {
    const name = escapeXml(check.name);
    const classname = `${suite}.${check.visibility}`;
    if (check.verdict === 'pass') {
      lines.push(`    <testcase name="${name}" classname="${classname}"/>`);
    } else {
      lines.push(
        `    <testcase name="${name}" classname="${classname}">`,
        `      <failure message="${escapeXml(check.message)}" type="check">${escapeXml(checkOutput(check))}</failure>`,
        '    </testcase>',
      );
    }
  }
  lines.push('  </testsuite>', '</testsuites>');
  return `${lines.join('\n')}\n`;
}

/** The report in `format` as the text to write. */
export function renderReport(
  format: ReportFormat,
  outcome: GradeOutcome,
  context: ReportContext,
): string {
  switch (format) {
    case 'gradescope':
      return `${JSON.stringify(gradescopeReport(outcome, context), null, 2)}\n`;
    case 'prairielearn':
      return `${JSON.stringify(prairieLearnReport(outcome, context), null, 2)}\n`;
    case 'json':
      return `${JSON.stringify({ exercise: context.exerciseId, ...outcome }, null, 2)}\n`;
    case 'junit':
      return junitReport(outcome, context);
  }
}

/** A short human summary for the terminal. */
export function summary(outcome: GradeOutcome, context: ReportContext): string {
  const lines = [`${context.exerciseId} — ${context.title}`, outcomeHeadline(outcome)];
  if (outcome.status === 'graded') {
    for (const check of outcome.checks) {
      const mark = check.verdict === 'pass' ? 'PASS' : 'FAIL';
      lines.push(
        `  ${mark} ${formatPoints(check.points)}/${formatPoints(check.maxPoints)} ` +
          `[${check.visibility}] ${check.name}` +
          (check.verdict === 'fail' ? `\n         ${check.message}` : ''),
      );
    }
  }
  return lines.join('\n');
}
