// The statistical checks' design on the CPU: the exact expectations of delta tracking's
// lookups against a float64 simulation, each test's false-fail rate and its power
// against the wrong estimators the issue names (a relative bias of 1 %, a sampler wrong
// inside a bin), and the rule that hidden checks draw their inputs from the seed.
import { describe, expect, it } from 'vitest';
import { EXERCISE_IDS } from '../../exercises/index.ts';
import { loadFullExercise } from '../../src/grading/node.ts';
import { mixSeed, seededUniforms } from '../../src/grading/stats.ts';
import {
  evaluateTracking,
  meanTestAlpha,
  meanTestPower,
  trackingExpectation,
  type CaseOutput,
  type MediumFamily,
  type TrackingCase,
  type TrackingCheck,
} from '../../src/grading/checks/tracking.ts';
import {
  distributionPower,
  distributionStatistics,
} from '../../src/grading/checks/distribution.ts';
import { casesForSeed, type GeneratedCasesCheck } from '../../src/grading/checks/generated.ts';
import { BUMP_MEDIUM, HIDDEN_CASES, HIDDEN_CHECKS } from '../../exercises/delta-tracking/hidden.ts';
import {
  PUBLIC_ALPHA,
  PUBLIC_CALLS,
  PUBLIC_CASE,
  SINE_MEDIUM,
} from '../../exercises/delta-tracking/exercise.ts';
import { DISTRIBUTION_DESIGN } from '../../exercises/hg-sample/hidden.ts';
import { hgCdf, hgInverseCdf } from '../../exercises/hg-sample/exercise.ts';

type Variant = 'canonical' | 'lookup-first' | 'double-lookup' | 'biased';

/** Delta tracking in float64 with counted lookups and draws (the statement's algorithm). */
function simulate(
  family: MediumFamily,
  c: TrackingCase,
  n: number,
  seed: number,
  variant: Variant = 'canonical',
): CaseOutput {
  const next = seededUniforms(seed);
  const [, , d, majorant] = c.args;
  const values = new Float64Array(n);
  const lookups = new Float64Array(n);
  const draws = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    let l = 0;
    let dr = 0;
    let t = 0;
    let x = 1;
    if (majorant > 0) {
      for (;;) {
        t += -Math.log(1 - next()) / majorant;
        dr++;
        if (variant === 'lookup-first') l++;
        if (t >= d) {
          x = 1;
          break;
        }
        if (variant !== 'lookup-first') l += variant === 'double-lookup' ? 2 : 1;
        dr++;
        // 'biased': a real collision with probability 0.95·σt/σ̄ (too few absorptions).
        const scale = variant === 'biased' ? 0.95 : 1;
        if (next() * majorant < scale * family.sigma(c.args, c.params, t)) {
          x = 0;
          break;
        }
      }
    }
    values[i] = x;
    lookups[i] = l;
    draws[i] = dr;
  }
  return { values, lookups, draws };
}

const TESTS = { mean: true, binary: true, work: true } as const;

describe('delta tracking: exact expectations of the estimate and its work', () => {
  it('match a float64 simulation (mean and variance of the lookup count)', () => {
    for (const seed of [1, 2, 3]) {
      for (const c of [...HIDDEN_CASES.hiddenMedia(seed), ...HIDDEN_CASES.thickMedium(seed)]) {
        const e = trackingExpectation(BUMP_MEDIUM, c);
        const n = 200_000;
        const out = simulate(BUMP_MEDIUM, c, n, mixSeed(seed, 99));
        let sum = 0;
        let squares = 0;
        let xs = 0;
        for (let i = 0; i < n; i++) {
          sum += out.lookups[i] ?? 0;
          squares += (out.lookups[i] ?? 0) ** 2;
          xs += out.values[i] ?? 0;
        }
        const mean = sum / n;
        const variance = squares / n - mean * mean;
        const moments = e.lookups[0] as { mean: number; variance: number };
        // Within 6 standard errors (mean) and 5 % (variance).
        expect(Math.abs(mean - moments.mean)).toBeLessThan(6 * Math.sqrt(moments.variance / n));
        expect(Math.abs(variance / moments.variance - 1)).toBeLessThan(0.05);
        const T = e.transmittance;
        expect(Math.abs(xs / n - T)).toBeLessThan(6 * Math.sqrt((T * (1 - T)) / n));
      }
    }
  });

  it('pass delta tracking in both orders and fail wasteful, biased or coin estimators', () => {
    const seed = 7;
    const cases = HIDDEN_CASES.hiddenMedia(seed);
    const n = 32768;
    const expectations = cases.map((c) => trackingExpectation(BUMP_MEDIUM, c));
    const run = (variant: Variant): ReturnType<typeof evaluateTracking> =>
      evaluateTracking(
        TESTS,
        1e-6,
        expectations,
        cases.map((c, k) => simulate(BUMP_MEDIUM, c, n, mixSeed(seed, k), variant)),
      );
    expect(run('canonical').pass).toBe(true);
    expect(run('lookup-first').pass).toBe(true);
    const double = run('double-lookup');
    expect(double.pass).toBe(false);
    expect(double.work?.pass).toBe(false);
    const biased = run('biased');
    expect(biased.mean?.pass).toBe(false);
    // A coin with the exact T: right mean, binary, but no lookups and one draw.
    const coin = evaluateTracking(
      TESTS,
      1e-6,
      expectations,
      cases.map((c, k) => {
        const next = seededUniforms(mixSeed(seed, 50 + k));
        const T = expectations[k]?.transmittance ?? 0;
        return {
          values: Float64Array.from({ length: n }, () => (next() < T ? 1 : 0)),
          lookups: new Float64Array(n),
          draws: new Float64Array(n).fill(1),
        };
      }),
    );
    expect(coin.mean?.pass).toBe(true);
    expect(coin.binary?.pass).toBe(true);
    expect(coin.work?.pass).toBe(false);
  });

  it('has power ≥ 0.99 against a relative bias of 1 % on every seed (hidden and public)', () => {
    const hidden = HIDDEN_CHECKS[0] as TrackingCheck;
    let worst = 1;
    for (let seed = 0; seed < 500; seed++) {
      const expectations = hidden.cases(seed).map((c) => trackingExpectation(BUMP_MEDIUM, c));
      worst = Math.min(
        worst,
        meanTestPower(expectations, hidden.n, meanTestAlpha(hidden), 0.01).power,
      );
    }
    expect(worst).toBeGreaterThanOrEqual(0.99);
    const pub = trackingExpectation(SINE_MEDIUM, { args: PUBLIC_CASE, params: [] });
    expect(meanTestPower([pub], PUBLIC_CALLS, PUBLIC_ALPHA, 0.01).power).toBeGreaterThanOrEqual(
      0.99,
    );
  });
});

describe('HG sampling: the distribution check', () => {
  const { n, bins, alpha, gRange } = DISTRIBUTION_DESIGN;
  /** G(p) = P(F(X) ≤ p) for the sampler exact at ξ = j/20 and linear in between. */
  const quantileLinear =
    (g: number) =>
    (p: number): number => {
      const mu = hgInverseCdf(g, p);
      for (let j = 0; j < 20; j++) {
        const a = hgInverseCdf(g, j / 20);
        const b = hgInverseCdf(g, (j + 1) / 20);
        if (mu <= b || j === 19) return (j + Math.min(1, Math.max(0, (mu - a) / (b - a)))) / 20;
      }
      return 1;
    };

  it('has power ≥ 0.99 against the 21-quantile linear sampler for every |g| it draws', () => {
    for (let k = 0; k <= 9; k++) {
      const g = gRange[0] + ((gRange[1] - gRange[0]) * k) / 9;
      expect(distributionPower(n, bins, alpha, quantileLinear(g)).power).toBeGreaterThanOrEqual(
        0.99,
      );
    }
    // A correct sampler: the alternative is the null, so the power is the size.
    expect(distributionPower(n, bins, alpha, (p) => p).chiSquare).toBeLessThan(1e-6);
  });

  it('accepts exact samples and rejects the 21-quantile linear sampler', () => {
    const g = 0.6;
    const next = seededUniforms(11);
    const exact: number[] = [];
    const linear: number[] = [];
    const G = quantileLinear(g);
    for (let i = 0; i < n; i++) {
      const xi = next();
      exact.push(hgCdf(g, hgInverseCdf(g, xi)));
      linear.push(G(xi));
    }
    const good = distributionStatistics(exact, bins, alpha, 0.37);
    expect(good.chiSquare).toBeLessThan(good.chiSquareCritical);
    expect(good.ks).toBeLessThan(good.ksCritical);
    const bad = distributionStatistics(linear, bins, alpha, 0.37);
    expect(bad.chiSquare).toBeGreaterThan(bad.chiSquareCritical);
  });
});

describe('hidden checks', () => {
  it('draw their inputs from the seed (no fixed table of hidden inputs)', async () => {
    for (const id of EXERCISE_IDS) {
      const exercise = await loadFullExercise(id);
      for (const check of exercise.hiddenChecks ?? []) {
        expect(['generated-cases', 'distribution', 'tracking'], `${id}: ${check.name}`).toContain(
          check.kind,
        );
        if (check.kind === 'generated-cases') {
          const a = casesForSeed(check as GeneratedCasesCheck, 1).cases.map((c) => c.args.join());
          const b = casesForSeed(check as GeneratedCasesCheck, 2).cases.map((c) => c.args.join());
          // At most one fixed edge case (e.g. the §9 forward peak) may repeat.
          expect(a.filter((x) => b.includes(x)).length, `${id}: ${check.name}`).toBeLessThanOrEqual(
            1,
          );
        }
        if (check.kind === 'tracking') {
          expect(JSON.stringify(check.cases(1))).not.toBe(JSON.stringify(check.cases(2)));
        }
      }
    }
  });
});
