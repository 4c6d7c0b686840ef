// Reports of one graded submission in the formats course autograders read:
// - Gradescope results.json (https://gradescope-autograders.readthedocs.io/en/latest/specs/,
//   "Output format"): top-level score, output, tests[] with name, score, max_score,
//   status ('passed' | 'failed'), visibility ('hidden' | 'after_due_date' |
//   'after_published' | 'visible') and output;
// - PrairieLearn results.json (https://prairielearn.readthedocs.io/en/latest/externalGrading/,
//   "Grading results"): gradable, score in [0, 1], message, output, tests[] with name,
//   points, max_points, message, output;
// - our GradeOutcome as JSON;
// - JUnit XML (testsuite / testcase / failure), for CI dashboards.
import type { CheckResult, GradeOutcome } from './types.ts';

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

/** Gradescope's results.json. Hidden checks are shown after the grades are published. */
export function gradescopeReport(outcome: GradeOutcome, context: ReportContext): object {
  if (outcome.status !== 'graded') {
    return {
      score: 0,
      output: `${context.title}: ${outcomeHeadline(outcome)}`,
      tests: [],
    };
  }
  return {
    score: outcome.score,
    output: `${context.title}: ${outcomeHeadline(outcome)}`,
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
 * PrairieLearn's results.json. A submission that cannot be graded for reasons of
 * its form (it does not compile, wrong signature) or of the grader's machine
 * (timeout, device loss) is `gradable: false`, which PrairieLearn shows as invalid
 * without charging an attempt; an endless loop is the student's program and scores 0.
 */
export function prairieLearnReport(outcome: GradeOutcome, context: ReportContext): object {
  if (outcome.status !== 'graded') {
    const gradable = outcome.status === 'loop-budget';
    return {
      gradable,
      score: 0,
      message: outcomeHeadline(outcome),
      output: `${context.title}\n${outcomeHeadline(outcome)}`,
      tests: [],
    };
  }
  return {
    gradable: true,
    score: outcome.maxScore > 0 ? outcome.score / outcome.maxScore : 0,
    message: outcomeHeadline(outcome),
    output: context.title,
    tests: outcome.checks.map((check) => ({
      name: check.name,
      points: check.points,
      max_points: check.maxPoints,
      message: check.message,
      output: checkOutput(check),
    })),
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
