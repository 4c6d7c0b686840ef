// A node:test reporter that writes one JSON object for scripts/test.mjs to count:
// { passed, failed, skipped, tests: [{ name, suite, ok, ms, error?, notes }] }.
// Only tests count, not the describe blocks around them; a failure outside any
// test (a hook, or a file that does not load) counts as one failed test.
// Diagnostics a test writes (`t.diagnostic(...)`) are kept as its notes.
// node:test's own closing diagnostics (counts and duration), not a test's notes.
const SUMMARY = /^(tests|suites|pass|fail|cancelled|skipped|todo|duration_ms) /;

export default async function* jsonReporter(source) {
  const tests = [];
  const suites = [];
  // A test's diagnostics arrive after its pass or fail event, at its nesting.
  let last = null;
  for await (const event of source) {
    const data = event.data ?? {};
    if (event.type === 'test:start') {
      suites[data.nesting] = data.name;
    } else if (event.type === 'test:diagnostic') {
      if (last && last.nesting === data.nesting && !SUMMARY.test(data.message)) {
        last.test.notes.push(data.message);
      }
    } else if (event.type === 'test:pass' || event.type === 'test:fail') {
      const details = data.details ?? {};
      const failed = event.type === 'test:fail';
      const error = failed ? String(details.error?.cause ?? details.error ?? 'failed') : undefined;
      const suite = suites.slice(0, data.nesting).join(' › ');
      last = null;
      if (details.type === 'suite') {
        // A suite fails on its own only when a hook failed or nothing inside ran.
        if (failed && details.error?.failureType !== 'subtestsFailed') {
          tests.push({ name: `${data.name} (suite)`, suite, ok: false, ms: 0, error, notes: [] });
        }
        continue;
      }
      const test = {
        name: data.name,
        suite,
        ok: !failed,
        skipped: data.skip !== undefined || data.todo !== undefined,
        ms: Math.round(details.duration_ms ?? 0),
        ...(failed ? { error } : {}),
        notes: [],
      };
      tests.push(test);
      last = { nesting: data.nesting, test };
    }
  }
  const counted = tests.filter((test) => !test.skipped);
  const report = {
    passed: counted.filter((test) => test.ok).length,
    failed: counted.filter((test) => !test.ok).length,
    skipped: tests.length - counted.length,
    tests,
  };
  yield `${JSON.stringify(report, null, 2)}\n`;
}
