// The report formats against their published field definitions:
// - Gradescope: https://gradescope-autograders.readthedocs.io/en/latest/specs/ ("Output format"):
//   top level score (number), execution_time, output, output_format, test_output_format,
//   test_name_format, visibility, stdout_visibility, extra_data, tests, leaderboard;
//   per test score, max_score, status ("passed" | "failed"), name, name_format, number,
//   output, output_format, tags, visibility ("hidden" | "after_due_date" |
//   "after_published" | "visible"), extra_data.
// - PrairieLearn: https://prairielearn.readthedocs.io/en/latest/externalGrading/
//   ("Grading results"): gradable (boolean), score (number in [0, 1]), message, output,
//   images, format_errors, tests; per test name, description, points, max_points,
//   message, output, images.
// - JUnit XML (the Ant/Surefire schema): testsuites > testsuite[name, tests, failures,
//   errors] > testcase[name, classname] > failure[message, type] | error.
import { describe, expect, it } from 'vitest';
import {
  escapeXml,
  gradescopeReport,
  junitReport,
  prairieLearnReport,
  renderReport,
} from '../../src/grading/reports.ts';
import type { GradeOutcome } from '../../src/grading/types.ts';

const GRADESCOPE_TOP = [
  'score',
  'execution_time',
  'output',
  'output_format',
  'test_output_format',
  'test_name_format',
  'visibility',
  'stdout_visibility',
  'extra_data',
  'tests',
  'leaderboard',
];
const GRADESCOPE_TEST = [
  'score',
  'max_score',
  'status',
  'name',
  'name_format',
  'number',
  'output',
  'output_format',
  'tags',
  'visibility',
  'extra_data',
];
const GRADESCOPE_VISIBILITY = ['hidden', 'after_due_date', 'after_published', 'visible'];
const PRAIRIELEARN_TOP = [
  'gradable',
  'score',
  'message',
  'output',
  'images',
  'format_errors',
  'tests',
];
const PRAIRIELEARN_TEST = [
  'name',
  'description',
  'points',
  'max_points',
  'message',
  'output',
  'images',
];

const graded: GradeOutcome = {
  status: 'graded',
  score: 6,
  maxScore: 10,
  seed: 1,
  checks: [
    {
      name: 'Typical <thicknesses> & "quotes"',
      visibility: 'public',
      verdict: 'pass',
      points: 6,
      maxPoints: 6,
      message: 'All cases agree.',
      samples: [{ args: 'd = 1', student: '0.3678794', reference: '0.3678794' }],
    },
    {
      name: 'Negative inputs',
      visibility: 'hidden',
      verdict: 'fail',
      points: 0,
      maxPoints: 4,
      message: 'Your transmittance exceeds 1 for negative σt <here>.',
    },
  ],
};
const compileError: Exclude<GradeOutcome, { status: 'graded' }> = {
  status: 'compile-error',
  message: "Your shader does not compile: line 5, column 3: expected ';'",
  diagnostics: [{ line: 5, column: 3, message: "expected ';'", severity: 'error' }],
};
const context = { exerciseId: 'beer-law', title: "Beer's law" };

function keysWithin(object: object, allowed: readonly string[]): void {
  for (const key of Object.keys(object)) expect(allowed, `unexpected field ${key}`).toContain(key);
}

describe('Gradescope results.json', () => {
  it('uses only published fields with the published types', () => {
    for (const outcome of [graded, compileError]) {
      const report = gradescopeReport(outcome, context) as Record<string, unknown>;
      keysWithin(report, GRADESCOPE_TOP);
      expect(typeof report.score).toBe('number');
      for (const test of report.tests as Record<string, unknown>[]) {
        keysWithin(test, GRADESCOPE_TEST);
        expect(typeof test.score).toBe('number');
        expect(typeof test.max_score).toBe('number');
        expect(['passed', 'failed']).toContain(test.status);
        expect(GRADESCOPE_VISIBILITY).toContain(test.visibility);
        expect(typeof test.output).toBe('string');
      }
    }
  });

  it('sums per-test scores to the total and hides hidden checks until published', () => {
    const report = gradescopeReport(graded, context) as {
      score: number;
      tests: { score: number; visibility: string }[];
    };
    expect(report.tests.reduce((s, t) => s + t.score, 0)).toBe(report.score);
    expect(report.tests.map((t) => t.visibility)).toEqual(['visible', 'after_published']);
    expect((gradescopeReport(compileError, context) as { output: string }).output).toContain(
      'line 5, column 3',
    );
  });
});

describe('PrairieLearn results.json', () => {
  it('uses only published fields, with score in [0, 1]', () => {
    for (const outcome of [graded, compileError]) {
      const report = prairieLearnReport(outcome, context) as Record<string, unknown>;
      keysWithin(report, PRAIRIELEARN_TOP);
      expect(typeof report.gradable).toBe('boolean');
      expect(report.score).toBeGreaterThanOrEqual(0);
      expect(report.score).toBeLessThanOrEqual(1);
      for (const test of report.tests as Record<string, unknown>[]) {
        keysWithin(test, PRAIRIELEARN_TEST);
        expect(typeof test.points).toBe('number');
        expect(typeof test.max_points).toBe('number');
        expect(typeof test.message).toBe('string');
      }
    }
    const report = prairieLearnReport(graded, context) as { score: number; gradable: boolean };
    expect(report.score).toBeCloseTo(0.6, 12);
    expect(report.gradable).toBe(true);
    expect((prairieLearnReport(compileError, context) as { gradable: boolean }).gradable).toBe(
      false,
    );
  });
});

describe('JUnit XML', () => {
  it('has one testcase per check, failures counted, everything escaped', () => {
    const xml = junitReport(graded, context);
    expect(xml).toMatch(/^<\?xml version="1.0" encoding="UTF-8"\?>/);
    expect(xml).toContain('<testsuite name="exercise.beer-law" tests="2" failures="1" errors="0">');
    expect(xml.match(/<testcase /g)).toHaveLength(2);
    expect(xml.match(/<failure /g)).toHaveLength(1);
    expect(xml).toContain('Typical &lt;thicknesses&gt; &amp; &quot;quotes&quot;');
    expect(xml).not.toMatch(/<here>/);
    // Every tag that opens closes (a cheap well-formedness check).
    const opens = (xml.match(/<(testsuites|testsuite|testcase|failure)[ >]/g) ?? []).length;
    const selfClosed = (xml.match(/\/>/g) ?? []).length;
    const closes = (xml.match(/<\/(testsuites|testsuite|testcase|failure)>/g) ?? []).length;
    expect(opens).toBe(closes + selfClosed);
    expect(junitReport(compileError, context)).toContain('<error message=');
    expect(escapeXml('a\u0001b<')).toBe('ab&lt;');
  });

  it('renders json as the outcome itself', () => {
    const parsed = JSON.parse(renderReport('json', graded, context)) as {
      exercise: string;
      score: number;
    };
    expect(parsed.exercise).toBe('beer-law');
    expect(parsed.score).toBe(6);
  });
});

describe('what students see before publication, and grader-side failures', () => {
  const failures: Exclude<GradeOutcome, { status: 'graded' }>[] = [
    { status: 'timeout', message: 'The whole run passed its wall-clock limit of 120 s.' },
    { status: 'device-lost', message: 'The GPU device was lost (simulated).' },
    { status: 'internal-error', message: 'TypeError: x is undefined' },
  ];

  it('Gradescope: the top-level output names only the public points', () => {
    const report = gradescopeReport(graded, { ...context, executionTimeS: 3.4 }) as Record<
      string,
      unknown
    >;
    expect(report.output).toContain('public checks 6 / 6 points');
    // The total (6 / 10) includes the hidden check's points: not before publication.
    expect(report.output).not.toMatch(/\/ 10\b/);
    expect(report.output).not.toContain('Negative inputs');
    expect(report.execution_time).toBe(3);
    expect(report.stdout_visibility).toBe('hidden');
    expect(report.score).toBe(6);
  });

  it('Gradescope: a grader-side failure is a visible "will be regraded" test, with no score', () => {
    for (const outcome of failures) {
      const report = gradescopeReport(outcome, context) as Record<string, unknown>;
      keysWithin(report, GRADESCOPE_TOP);
      // No top-level score: the spec lets the tests carry it, and the one test is worth 0 of 0.
      expect(report).not.toHaveProperty('score');
      const tests = report.tests as Record<string, unknown>[];
      expect(tests).toHaveLength(1);
      keysWithin(tests[0] as object, GRADESCOPE_TEST);
      expect(tests[0]).toMatchObject({
        name: 'Grading failed — will be regraded',
        score: 0,
        max_score: 0,
        status: 'failed',
        visibility: 'visible',
      });
      expect(tests[0]?.output).toContain(outcome.message);
      expect(report.output).toContain('not your score');
      expect(report.extra_data).toEqual({ grader_failure: outcome.status });
    }
  });

  it("Gradescope: the student's own non-graded outcomes score 0 with a visible reason", () => {
    const rejected = {
      status: 'rejected' as const,
      message: 'line 1, column 1: `@group(1)` declares a resource binding',
    };
    for (const outcome of [compileError, rejected]) {
      const report = gradescopeReport(outcome, context) as Record<string, unknown>;
      expect(report.score).toBe(0);
      const tests = report.tests as Record<string, unknown>[];
      expect(tests[0]?.visibility).toBe('visible');
      expect(tests[0]?.output).toContain(outcome.message.slice(0, 20));
    }
  });

  it('PrairieLearn: hidden checks show only their name and pass/fail', () => {
    const checks = graded.status === 'graded' ? graded.checks : [];
    const withSamples: GradeOutcome = {
      ...graded,
      checks: checks.map((c) =>
        c.visibility === 'hidden'
          ? {
              ...c,
              samples: [{ args: 'sigmaT = -2, d = 1', student: '7.389057', reference: '1' }],
            }
          : c,
      ),
    };
    const report = prairieLearnReport(withSamples, context) as {
      tests: Record<string, unknown>[];
    };
    const hidden = report.tests[1] as Record<string, unknown>;
    expect(Object.keys(hidden).sort()).toEqual(['max_points', 'message', 'name', 'points']);
    expect(hidden.message).toBe('failed');
    const text = JSON.stringify(report);
    expect(text).not.toContain('sigmaT = -2');
    expect(text).not.toContain('7.389057');
    expect(text).not.toContain('exceeds 1 for negative');
    // The public check keeps its message and samples.
    expect(report.tests[0]?.output).toContain('yours 0.3678794');
  });

  it('PrairieLearn: a grader-side failure is gradable: false with the reason', () => {
    for (const outcome of failures) {
      const report = prairieLearnReport(outcome, context) as Record<string, unknown>;
      keysWithin(report, PRAIRIELEARN_TOP);
      expect(report.gradable).toBe(false);
      expect(report.message).toContain(outcome.message);
      expect(report.message).toContain('regraded');
    }
    const loop = prairieLearnReport({ status: 'loop-budget', message: 'endless' }, context) as {
      gradable: boolean;
    };
    expect(loop.gradable).toBe(true);
  });
});
