// `npm test`: every check the project has, in order, with one summary line.
//   1. Debian's chromium is present (installed when root)
//   2. typecheck (tsc), lint (eslint), formatting (prettier)
//   3. Vitest: twins, WGSL through Dawn, hard cases, the chapter build
//   4. the production build, then Playwright end-to-end tests in Chromium
//   5. the Firefox end-to-end tests (tests/firefox, node:test + puppeteer-core), with
//      firefox-esr and mesa-vulkan-drivers (lavapipe) installed when root
// Each of tsc/eslint/prettier/build counts as one test; Vitest, Playwright and the
// Firefox tests count their own tests. The last line is "N passed, N failed".
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

let passed = 0;
let failed = 0;
const failures = [];
/** Wall time of each stage, printed with the summary (the suite's budget is 30 minutes). */
const timings = [];

function run(name, command, args, env = {}) {
  console.log(`\n=== ${name}: ${[command, ...args].join(' ')}`);
  const started = Date.now();
  const result = spawnSync(command, args, { stdio: 'inherit', env: { ...process.env, ...env } });
  timings.push(`${name} ${((Date.now() - started) / 60_000).toFixed(1)} min`);
  return result.status === 0;
}

function single(name, command, args) {
  if (run(name, command, args)) passed += 1;
  else {
    failed += 1;
    failures.push(name);
  }
}

/**
 * Runs a test runner and adds the counts of its JSON report (or one failure if there is
 * none). `names` lists the failed tests of the report: CI keeps only the end of the
 * output, so they are repeated in the summary at the end.
 */
function runner(name, command, args, report, count, names = () => []) {
  rmSync(report, { force: true });
  const ok = run(name, command, args);
  if (!existsSync(report)) {
    failed += 1;
    failures.push(`${name} (no report)`);
    return;
  }
  const parsed = JSON.parse(readFileSync(report, 'utf8'));
  const counts = count(parsed);
  passed += counts.passed;
  failed += counts.failed;
  if (!ok && counts.failed === 0) {
    failed += 1;
    failures.push(`${name} (exited with an error)`);
  } else if (counts.failed > 0) {
    const listed = names(parsed).slice(0, 20);
    failures.push(
      `${name} (${counts.failed} failed${listed.length ? `: ${listed.join(' | ')}` : ''})`,
    );
  }
}

/** Failed or flaky tests of a Playwright JSON report, as "file › title". */
function playwrightFailures(report) {
  const out = [];
  const walk = (suite) => {
    for (const spec of suite.specs ?? [])
      for (const t of spec.tests ?? [])
        if (t.status === 'unexpected' || t.status === 'flaky')
          out.push(`${spec.file} › ${spec.title} [${t.projectName}]`);
    for (const child of suite.suites ?? []) walk(child);
  };
  for (const suite of report.suites ?? []) walk(suite);
  return out;
}

/** Failed tests of a Vitest JSON report, as "file › title". */
function vitestFailures(report) {
  return (report.testResults ?? []).flatMap((file) => {
    const path = String(file.name ?? '').replace(`${process.cwd()}/`, '');
    const failedTests = (file.assertionResults ?? []).filter((t) => t.status === 'failed');
    if (failedTests.length === 0 && file.status === 'failed') return [`${path} (file)`];
    return failedTests.map((t) => `${path} › ${t.fullName ?? t.title}`);
  });
}

if (!run('chromium', 'sh', ['scripts/ensure-chromium.sh'])) {
  console.log('\n0 passed, 1 failed');
  process.exit(1);
}
if (!run('firefox', 'sh', ['scripts/ensure-firefox.sh'])) {
  console.log('\n0 passed, 1 failed');
  process.exit(1);
}

single('typecheck', 'npx', ['tsc', '--noEmit', '-p', '.']);
single('lint', 'npx', ['eslint', '.']);
single('format', 'npx', ['prettier', '--check', '.']);
runner(
  'vitest',
  'sh',
  ['scripts/gpu-env.sh', 'npx', 'vitest', 'run'],
  'test-results/vitest.json',
  (r) => ({
    passed: r.numPassedTests ?? 0,
    failed: r.numFailedTests ?? 0,
  }),
  vitestFailures,
);
const built = run('build', 'npx', ['vite', 'build', '--logLevel', 'warn']);
if (built) {
  passed += 1;
  // The book built for a deep sub-path, made once for the two specs that serve it
  // (tests/e2e/publish.spec.ts, tests/e2e/offline.spec.ts; support.ts, subPathBuild):
  // without it each would build its own.
  const subDist = mkdtempSync(join(tmpdir(), 'scatterbook-subpath-'));
  if (
    run('sub-path build', 'npx', [
      'vite',
      'build',
      '--base',
      '/courses/cmsc740/book/',
      '--outDir',
      subDist,
      '--emptyOutDir',
      '--logLevel',
      'warn',
    ])
  )
    process.env['E2E_SUB_DIST'] = subDist;
  runner(
    'playwright',
    'npx',
    ['playwright', 'test'],
    'test-results/playwright.json',
    (r) => ({
      passed: r.stats?.expected ?? 0,
      failed: (r.stats?.unexpected ?? 0) + (r.stats?.flaky ?? 0),
    }),
    playwrightFailures,
  );
  rmSync(subDist, { recursive: true, force: true });
  runner(
    'firefox e2e',
    'node',
    [
      '--import',
      'tsx',
      '--test',
      '--test-reporter=spec',
      '--test-reporter-destination=stdout',
      '--test-reporter=./tests/firefox/reporter.mjs',
      '--test-reporter-destination=test-results/firefox.json',
      'tests/firefox/book.firefox.ts',
    ],
    'test-results/firefox.json',
    (r) => ({ passed: r.passed ?? 0, failed: r.failed ?? 0 }),
    (r) => (r.tests ?? []).filter((t) => !t.ok).map((t) => `${t.suite} › ${t.name}`),
  );
} else {
  failed += 1;
  failures.push('build (end-to-end tests not run)');
}

if (failures.length) console.log(`\nFailed: ${failures.join('; ')}`);
console.log(`Stage times: ${timings.join(', ')}`);
console.log(`\n${passed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
