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
import { existsSync, readFileSync, rmSync } from 'node:fs';

let passed = 0;
let failed = 0;
const failures = [];

function run(name, command, args, env = {}) {
  console.log(`\n=== ${name}: ${[command, ...args].join(' ')}`);
  const result = spawnSync(command, args, { stdio: 'inherit', env: { ...process.env, ...env } });
  return result.status === 0;
}

function single(name, command, args) {
  if (run(name, command, args)) passed += 1;
  else {
    failed += 1;
    failures.push(name);
  }
}

/** Runs a test runner and adds the counts of its JSON report (or one failure if there is none). */
function runner(name, command, args, report, count) {
  rmSync(report, { force: true });
  const ok = run(name, command, args);
  if (!existsSync(report)) {
    failed += 1;
    failures.push(`${name} (no report)`);
    return;
  }
  const counts = count(JSON.parse(readFileSync(report, 'utf8')));
  passed += counts.passed;
  failed += counts.failed;
  if (!ok && counts.failed === 0) {
    failed += 1;
    failures.push(`${name} (exited with an error)`);
  } else if (counts.failed > 0) failures.push(`${name} (${counts.failed} failed)`);
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
);
const built = run('build', 'npx', ['vite', 'build', '--logLevel', 'warn']);
if (built) {
  passed += 1;
  runner('playwright', 'npx', ['playwright', 'test'], 'test-results/playwright.json', (r) => ({
    passed: r.stats?.expected ?? 0,
    failed: (r.stats?.unexpected ?? 0) + (r.stats?.flaky ?? 0),
  }));
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
  );
} else {
  failed += 1;
  failures.push('build (end-to-end tests not run)');
}

if (failures.length) console.log(`\nFailed: ${failures.join('; ')}`);
console.log(`\n${passed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
