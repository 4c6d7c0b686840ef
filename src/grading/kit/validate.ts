// Validators of the results.json files the kits hand to the platforms, against the
// platforms' documented fields. The kit's driver refuses a report that fails them
// (and reports a grader failure instead), and the kit tests run them on every
// report the kits write.
// - Gradescope: https://gradescope-autograders.readthedocs.io/en/latest/specs/
//   ("Output format"): top level score, execution_time, output, output_format,
//   test_output_format, test_name_format, visibility, stdout_visibility, extra_data,
//   tests, leaderboard; each test score, max_score, status, name, name_format, number,
//   output, output_format, tags, visibility, extra_data.
// - PrairieLearn: https://prairielearn.readthedocs.io/en/latest/externalGrading/
//   ("Grading results"): gradable, score (required when gradable, in [0, 1]), message,
//   output, format_errors, images, tests[] with name, description, points, max_points,
//   message, output, images; the file at most 1 MB.

const GRADESCOPE_VISIBILITY = ['hidden', 'after_due_date', 'after_published', 'visible'];
const GRADESCOPE_FORMATS = ['text', 'html', 'simple_format', 'md', 'ansi'];
const GRADESCOPE_TOP = new Set([
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
]);
const GRADESCOPE_TEST = new Set([
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
]);
const PL_TOP = new Set([
  'gradable',
  'score',
  'message',
  'output',
  'format_errors',
  'images',
  'tests',
  'partial_scores',
]);
const PL_TEST = new Set([
  'name',
  'description',
  'points',
  'max_points',
  'message',
  'output',
  'images',
]);
/** PrairieLearn's limit on results.json. */
export const PRAIRIELEARN_MAX_BYTES = 1024 * 1024;

function isObject(value: unknown): value is Record<string, unknown> {
  return typeof value === 'object' && value !== null && !Array.isArray(value);
}

function finite(value: unknown): value is number {
  return typeof value === 'number' && Number.isFinite(value);
}

/** Problems of a Gradescope results.json (empty when valid). */
export function gradescopeProblems(results: unknown): string[] {
  const problems: string[] = [];
  if (!isObject(results)) return ['results.json is not a JSON object'];
  for (const key of Object.keys(results))
    if (!GRADESCOPE_TOP.has(key)) problems.push(`unknown top-level field "${key}"`);
  const tests = results['tests'];
  if (results['score'] === undefined) {
    // Without a top-level score Gradescope sums the tests' scores, so every test needs one.
    if (!Array.isArray(tests) || tests.length === 0)
      problems.push('no top-level score and no tests to sum');
  } else if (!finite(results['score']) || results['score'] < 0) {
    problems.push('score must be a finite number ≥ 0');
  }
  if (
    results['execution_time'] !== undefined &&
    !(finite(results['execution_time']) && results['execution_time'] >= 0)
  )
    problems.push('execution_time must be a number of seconds ≥ 0');
  for (const key of ['output'])
    if (results[key] !== undefined && typeof results[key] !== 'string')
      problems.push(`${key} must be a string`);
  for (const key of ['output_format', 'test_output_format', 'test_name_format'])
    if (results[key] !== undefined && !GRADESCOPE_FORMATS.includes(results[key] as string))
      problems.push(`${key} must be one of ${GRADESCOPE_FORMATS.join(', ')}`);
  for (const key of ['visibility', 'stdout_visibility'])
    if (results[key] !== undefined && !GRADESCOPE_VISIBILITY.includes(results[key] as string))
      problems.push(`${key} must be one of ${GRADESCOPE_VISIBILITY.join(', ')}`);
  if (results['extra_data'] !== undefined && !isObject(results['extra_data']))
    problems.push('extra_data must be an object');
  if (tests !== undefined && !Array.isArray(tests)) problems.push('tests must be an array');
  let maxTotal = 0;
  (Array.isArray(tests) ? tests : []).forEach((test: unknown, i) => {
    const at = `tests[${i}]`;
    if (!isObject(test)) {
      problems.push(`${at} is not an object`);
      return;
    }
    for (const key of Object.keys(test))
      if (!GRADESCOPE_TEST.has(key)) problems.push(`${at}: unknown field "${key}"`);
    if (typeof test['name'] !== 'string' || test['name'] === '')
      problems.push(`${at}.name must be a non-empty string`);
    if (results['score'] === undefined && test['score'] === undefined)
      problems.push(`${at} needs a score when the top level has none`);
    const score = test['score'];
    const max = test['max_score'];
    if (score !== undefined && !(finite(score) && score >= 0))
      problems.push(`${at}.score must be a finite number ≥ 0`);
    if (max !== undefined && !(finite(max) && max >= 0))
      problems.push(`${at}.max_score must be a finite number ≥ 0`);
    if (finite(score) && finite(max) && score > max)
      problems.push(`${at}.score ${score} exceeds max_score ${max}`);
    if (finite(max)) maxTotal += max;
    if (test['status'] !== undefined && !['passed', 'failed'].includes(test['status'] as string))
      problems.push(`${at}.status must be "passed" or "failed"`);
    if (
      test['visibility'] !== undefined &&
      !GRADESCOPE_VISIBILITY.includes(test['visibility'] as string)
    )
      problems.push(`${at}.visibility must be one of ${GRADESCOPE_VISIBILITY.join(', ')}`);
    if (test['output'] !== undefined && typeof test['output'] !== 'string')
      problems.push(`${at}.output must be a string`);
    if (
      test['tags'] !== undefined &&
      !(Array.isArray(test['tags']) && test['tags'].every((t) => typeof t === 'string'))
    )
      problems.push(`${at}.tags must be an array of strings`);
  });
  // A graded report's total cannot exceed the points its tests offer.
  if (
    finite(results['score']) &&
    Array.isArray(tests) &&
    maxTotal > 0 &&
    results['score'] > maxTotal + 1e-9
  )
    problems.push(`score ${results['score']} exceeds the tests' total ${maxTotal}`);
  return problems;
}

/** Problems of a PrairieLearn results.json (empty when valid). */
export function prairieLearnProblems(results: unknown, bytes = 0): string[] {
  const problems: string[] = [];
  if (bytes > PRAIRIELEARN_MAX_BYTES) problems.push(`results.json is ${bytes} bytes (limit 1 MB)`);
  if (!isObject(results)) return [...problems, 'results.json is not a JSON object'];
  for (const key of Object.keys(results))
    if (!PL_TOP.has(key)) problems.push(`unknown top-level field "${key}"`);
  const gradable = results['gradable'];
  if (gradable !== undefined && typeof gradable !== 'boolean')
    problems.push('gradable must be a boolean');
  const score = results['score'];
  if (gradable !== false || score !== undefined) {
    if (!(finite(score) && score >= 0 && score <= 1))
      problems.push('score must be a number in [0, 1]');
  }
  for (const key of ['message', 'output'])
    if (results[key] !== undefined && typeof results[key] !== 'string')
      problems.push(`${key} must be a string`);
  const formatErrors = results['format_errors'];
  if (
    formatErrors !== undefined &&
    typeof formatErrors !== 'string' &&
    !(Array.isArray(formatErrors) && formatErrors.every((e) => typeof e === 'string'))
  )
    problems.push('format_errors must be a string or an array of strings');
  const tests = results['tests'];
  if (tests !== undefined && !Array.isArray(tests)) problems.push('tests must be an array');
  (Array.isArray(tests) ? tests : []).forEach((test: unknown, i) => {
    const at = `tests[${i}]`;
    if (!isObject(test)) {
      problems.push(`${at} is not an object`);
      return;
    }
    for (const key of Object.keys(test))
      if (!PL_TEST.has(key)) problems.push(`${at}: unknown field "${key}"`);
    if (typeof test['name'] !== 'string' || test['name'] === '')
      problems.push(`${at}.name must be a non-empty string`);
    const points = test['points'];
    const max = test['max_points'];
    if (points !== undefined && !(finite(points) && points >= 0))
      problems.push(`${at}.points must be a finite number ≥ 0`);
    if (max !== undefined && !(finite(max) && max >= 0))
      problems.push(`${at}.max_points must be a finite number ≥ 0`);
    if (finite(points) && finite(max) && points > max)
      problems.push(`${at}.points ${points} exceeds max_points ${max}`);
    for (const key of ['description', 'message', 'output'])
      if (test[key] !== undefined && typeof test[key] !== 'string')
        problems.push(`${at}.${key} must be a string`);
  });
  return problems;
}
