// The rayleigh-sky widget's float64 model (src/widgets/rayleigh-sky/model.ts) held
// to physical facts: β ∝ λ⁻⁴ in the Bruneton & Neyret 2008 coefficients, the
// geometry helpers against exact cases, the midpoint rule's O(h²) convergence, and
// the colours of the sky at noon and of the sun at sunset; and the sweep's pure
// logic: the error measure, the slope fits, the median, the timed pass count, and
// the reference cache (one computation per sun elevation, shared by every frame).
import { describe, expect, it } from 'vitest';
import {
  ATMOSPHERE_TOP,
  BETA_RAYLEIGH,
  EARTH_RADIUS,
  SCALE_HEIGHT,
  WAVELENGTHS_NM,
  FIT_FROM_STEPS,
  MAX_TIMED_PASSES,
  REFERENCE_STEPS,
  SWEEP_STEPS,
  TIMED_SPAN_MS,
  altitudeAlong,
  computeProbes,
  distanceToTop,
  fitSweep,
  hasCachedReference,
  inputsFrom,
  median,
  nextPassCount,
  probeError,
  probesFor,
  referenceProbes,
  referenceProbesAsync,
  skyRadiance,
  sunDensityIntegral,
  sunStepsFor,
  sunTransmittance,
  type Rgb,
  type SkyProbes,
} from '../../src/widgets/rayleigh-sky/model.ts';

const values = (elevation: number, scattering = 'on', steps = 32) => ({
  'sun-elevation': elevation,
  scattering,
  steps,
  exposure: 0,
});

describe('atmosphere constants (Bruneton & Neyret 2008)', () => {
  it('β(440 nm)/β(680 nm) is (680/440)⁴ within 5%: the coefficients follow β ∝ λ⁻⁴', () => {
    const ratio = BETA_RAYLEIGH[2] / BETA_RAYLEIGH[0];
    const lambdaLaw = (WAVELENGTHS_NM[0] / WAVELENGTHS_NM[2]) ** 4;
    expect(Math.abs(ratio / lambdaLaw - 1)).toBeLessThan(0.05);
    // and the middle channel too: β(550)/β(680) vs (680/550)⁴
    const green =
      BETA_RAYLEIGH[1] / BETA_RAYLEIGH[0] / (WAVELENGTHS_NM[0] / WAVELENGTHS_NM[1]) ** 4;
    expect(Math.abs(green - 1)).toBeLessThan(0.05);
  });
});

describe('geometry helpers', () => {
  it('straight up from sea level the top is 60 km away, and altitude grows linearly', () => {
    expect(distanceToTop(0, 1)).toBeCloseTo(ATMOSPHERE_TOP - EARTH_RADIUS, 6);
    expect(altitudeAlong(0, 1, 12345)).toBeCloseTo(12345, 6);
  });

  it('horizontally the top is √(R_top² − R²) away (Pythagoras), and a downward ray from sea level hits the ground', () => {
    const exact = Math.sqrt(ATMOSPHERE_TOP ** 2 - EARTH_RADIUS ** 2);
    expect(Math.abs(distanceToTop(0, 0)! - exact) / exact).toBeLessThan(1e-14);
    expect(distanceToTop(0, -0.01)).toBeNull();
    expect(sunTransmittance(-0.01, 8, true)).toEqual([0, 0, 0]);
  });

  it('altitudeAlong agrees with the naive |x + s·d| − R where that is well conditioned', () => {
    for (const [h, mu, s] of [
      [1000, 0.3, 50e3],
      [20e3, -0.2, 100e3],
      [0, 0.05, 500e3],
    ] as const) {
      const r = EARTH_RADIUS + h;
      const naive = Math.hypot(s * Math.sqrt(1 - mu * mu), r + s * mu) - EARTH_RADIUS;
      // The naive form loses ~1e-16·6.4e6 ≈ 1e-9 m to cancellation.
      expect(Math.abs(altitudeAlong(h, mu, s) - naive)).toBeLessThan(1e-6);
    }
  });

  it('the vertical density integral converges to H(1 − e^{−60 km/H}) (exact for an exponential)', () => {
    const exact = SCALE_HEIGHT * (1 - Math.exp(-(ATMOSPHERE_TOP - EARTH_RADIUS) / SCALE_HEIGHT));
    // The midpoint rule underestimates ∫e^{−s/H} by (Δs/H)²/24 relative to leading order
    // (Euler–Maclaurin): 2.34e-6 at Δs = 60 m; the next term is O((Δs/H)⁴) ≈ 3e-9.
    const relative = 1 - sunDensityIntegral(0, 1, 1000)! / exact;
    expect(Math.abs(relative - (60 / SCALE_HEIGHT) ** 2 / 24)).toBeLessThan(1e-8);
  });
});

describe('convergence of the twin in N (midpoint rule, O(h²))', () => {
  for (const elevation of [60, 20]) {
    it(`sun at ${elevation}°: the error ratio when N doubles (M = max(4, N/4) with it) is 4 within [3, 5]`, () => {
      const inputs = inputsFrom(values(elevation));
      const reference = computeProbes(inputs, 2048, 2048);
      for (const [k, probe] of probesFor(inputs).entries()) {
        const errors = [16, 32, 64].map((n) => {
          const l = skyRadiance(probe.mu, inputs.sinSun, probe.nu, n, sunStepsFor(n), true);
          return Math.abs(l[2] - reference.radiance[k]![2]) / reference.radiance[k]![2];
        });
        for (let i = 0; i + 1 < errors.length; i++) {
          const ratio = errors[i]! / errors[i + 1]!;
          expect(ratio, `${probe.key}: errors ${errors.join(', ')}`).toBeGreaterThan(3);
          expect(ratio, `${probe.key}: errors ${errors.join(', ')}`).toBeLessThan(5);
        }
      }
    });
  }

  it('the widget reference (N = M = 1024) is within 1e-5 of N = M = 4096 at 30° (so it is "converged" to the shown digits)', () => {
    const inputs = inputsFrom(values(30));
    const reference = referenceProbes(inputs);
    const fine = computeProbes(inputs, 4096, 4096);
    for (let k = 0; k < 3; k++)
      for (let c = 0; c < 3; c++)
        expect(Math.abs(reference.radiance[k]![c]! / fine.radiance[k]![c]! - 1)).toBeLessThan(1e-5);
  });
});

describe('colours (physics.md §2.6: σs ∝ λ⁻⁴)', () => {
  it('at noon (60°) the zenith is blue: L_blue/L_red > 1', () => {
    const zenith = referenceProbes(inputsFrom(values(60))).radiance[0]!;
    expect(zenith[2] / zenith[0]).toBeGreaterThan(1);
  });

  it('at sunset (2°) the direct sun is red: T_red/T_blue > 1, and much more so than at noon', () => {
    const sunset = referenceProbes(inputsFrom(values(2))).sunTransmittance;
    const noon = referenceProbes(inputsFrom(values(60))).sunTransmittance;
    expect(sunset[0] / sunset[2]).toBeGreaterThan(1);
    expect(sunset[0] / sunset[2]).toBeGreaterThan(2 * (noon[0] / noon[2]));
  });

  it('straight-up sun: T = e^{−β·H(1 − e^{−60/8})} per channel', () => {
    const t = sunTransmittance(1, 1024, true);
    const column = SCALE_HEIGHT * (1 - Math.exp(-60 / 8));
    for (let c = 0; c < 3; c++)
      expect(Math.abs(t[c]! / Math.exp(-BETA_RAYLEIGH[c]! * column) - 1)).toBeLessThan(1e-6);
  });

  it('with scattering off the sky is black and the sun white', () => {
    const probes = computeProbes(inputsFrom(values(30, 'off')));
    for (const l of probes.radiance) expect(l).toEqual([0, 0, 0]);
    expect(probes.sunTransmittance).toEqual([1, 1, 1]);
  });

  it('single scattering of an optically thin zenith column: L ≈ β·p_R(ν)·H·T (first order)', () => {
    // Sun at the zenith, looking up: ν = 1, all paths vertical. With τ = β H ≪ 1 the
    // integral is β p_R(1) ∫ρ e^{−β(…)} dt ≈ β p_R(1) H e^{−βH·(1 + ...)}; check at red,
    // where βH = 0.046, to first order: |L/(β p H) − e^{−2βH·…}| is bounded by e^{−βH}… e^{−2βH}.
    const l = skyRadiance(1, 1, 1, 512, 512, true)[0];
    const bH = BETA_RAYLEIGH[0] * SCALE_HEIGHT;
    const scale = BETA_RAYLEIGH[0] * ((3 / (16 * Math.PI)) * 2) * SCALE_HEIGHT;
    expect(l / scale).toBeLessThan(Math.exp(-bH));
    expect(l / scale).toBeGreaterThan(Math.exp(-2 * bH));
  });
});

describe('the sweep: error measure, fits and timing helpers', () => {
  const probes = (radiance: Rgb[]): SkyProbes => ({ radiance, sunTransmittance: [1, 1, 1] });
  const reference = probes([
    [1, 2, 4],
    [0.5, 1, 2],
    [0.25, 0.5, 1],
  ]);

  it('probeError is the relative RMS over probes and channels: δ when every value is off by a factor 1 + δ', () => {
    expect(probeError(reference, reference)).toBe(0);
    const scaled = probes(reference.radiance.map((rgb) => rgb.map((l) => l * 1.01) as Rgb));
    expect(probeError(scaled, reference)).toBeCloseTo(0.01, 14);
    // One of nine pairs off by 3%: √(0.03²/9) = 0.01.
    const one = probes(reference.radiance.map((rgb) => [...rgb] as Rgb));
    one.radiance[1]![2] = 2 * 1.03;
    expect(probeError(one, reference)).toBeCloseTo(0.01, 14);
  });

  it('probeError skips reference values of 0 and is null when all are 0 (scattering off)', () => {
    const dark = probes([
      [0, 0, 0],
      [0, 0, 0],
      [0, 0, 0],
    ]);
    expect(probeError(dark, dark)).toBeNull();
    const partly = probes([
      [0, 2, 4],
      [0.5, 1, 2],
      [0.25, 0.5, 1],
    ]);
    const estimate = probes([
      [7, 2, 4],
      [0.5, 1, 2],
      [0.25, 0.5, 1.08],
    ]);
    // The 7 against a reference of 0 is left out: √(0.08²/8).
    expect(probeError(estimate, partly)).toBeCloseTo(0.08 / Math.sqrt(8), 14);
  });

  it('fitSweep recovers p = −2, a = 2, q = −1 from error ∝ N⁻², time ∝ N², and ignores N < 16', () => {
    const points = SWEEP_STEPS.map((n) => ({
      n,
      // Below N = 16 a plateau, as the sun ray's fixed M = 4 gives in the widget.
      rmse: n < FIT_FROM_STEPS ? 0.03 : 5 / n ** 2,
      milliseconds: n < FIT_FROM_STEPS ? 1 : 0.01 * n ** 2,
    }));
    const fit = fitSweep(points);
    expect(fit.count).toBe(SWEEP_STEPS.filter((n) => n >= FIT_FROM_STEPS).length);
    expect(fit.order).toBeCloseTo(-2, 12);
    expect(fit.timeExponent).toBeCloseTo(2, 12);
    expect(fit.timeOrder).toBeCloseTo(-1, 12);
  });

  it('fitSweep gives no slopes when every error is 0 (nothing to fit on a log scale)', () => {
    const fit = fitSweep(SWEEP_STEPS.map((n) => ({ n, rmse: 0, milliseconds: n })));
    expect(fit.order).toBeNull();
    expect(fit.timeOrder).toBeNull();
  });

  for (const elevation of [60, 20, 2]) {
    it(`the twin's sweep at ${elevation}°: p within 0.2 of −2 over N ≥ 16 (the midpoint rule on a smooth integrand)`, () => {
      const inputs = inputsFrom(values(elevation));
      const exact = referenceProbes(inputs);
      const points = SWEEP_STEPS.map((n) => ({
        n,
        rmse: probeError(computeProbes(inputs, n, sunStepsFor(n)), exact)!,
        milliseconds: n * sunStepsFor(n),
      }));
      const { order, timeOrder } = fitSweep(points);
      expect(order).toBeGreaterThan(-2.2);
      expect(order).toBeLessThan(-1.8);
      // With the work N·M = N²/4 as the time, the error falls as time⁻¹.
      expect(timeOrder).toBeGreaterThan(-1.1);
      expect(timeOrder).toBeLessThan(-0.9);
    });
  }

  it('with the sun 2° below the horizon the Earth shadow cuts the integrand and the fitted order drops', () => {
    const inputs = inputsFrom(values(-2));
    const exact = referenceProbes(inputs);
    const points = SWEEP_STEPS.map((n) => ({
      n,
      rmse: probeError(computeProbes(inputs, n, sunStepsFor(n)), exact)!,
      milliseconds: n,
    }));
    expect(fitSweep(points).order).toBeGreaterThan(-1.6);
  });

  it('median: the middle value, or the mean of the two middle ones; an empty list throws', () => {
    expect(median([5, 1, 3])).toBe(3);
    expect(median([4, 1, 3, 2])).toBe(2.5);
    expect(median([7])).toBe(7);
    expect(() => median([])).toThrow();
  });

  it('nextPassCount keeps the count once the span reaches the target, and raises it (to at most the cap) below it', () => {
    expect(nextPassCount(1, TIMED_SPAN_MS)).toBe(1);
    expect(nextPassCount(3, 450)).toBe(3);
    // A span quantized to 0: eight times the passes.
    expect(nextPassCount(1, 0)).toBe(8);
    // 0.1 ms for one pass: ⌈1.25 × 2 / 0.1⌉ = 25 passes for a 2.5 ms span.
    expect(nextPassCount(1, 0.1)).toBe(25);
    expect(nextPassCount(8, 0)).toBe(MAX_TIMED_PASSES);
    expect(nextPassCount(MAX_TIMED_PASSES, 0)).toBe(MAX_TIMED_PASSES);
    // Always at least one more pass when under the target (no endless recalibration).
    expect(nextPassCount(4, 1.99)).toBeGreaterThan(4);
  });
});

describe('the converged reference is computed once per (sun elevation, scattering) and reused', () => {
  it('N, M and the exposure do not change the cache entry: every frame gets the same object', () => {
    const a = referenceProbes(inputsFrom({ ...values(41), steps: 8, exposure: 2 }));
    const b = referenceProbes(inputsFrom({ ...values(41), steps: 128, exposure: -1 }));
    expect(b).toBe(a);
    expect(referenceProbes(inputsFrom(values(41, 'off')))).not.toBe(a);
    expect(referenceProbes(inputsFrom(values(42)))).not.toBe(a);
  });

  it('the asynchronous reference (the widget yields between probes) fills the same cache, once, with the same numbers', async () => {
    const inputs = inputsFrom(values(37.5));
    expect(hasCachedReference(inputs)).toBe(false);
    const [first, second] = await Promise.all([
      referenceProbesAsync(inputs),
      referenceProbesAsync({ ...inputs, steps: 64 }),
    ]);
    expect(second).toBe(first);
    expect(hasCachedReference(inputs)).toBe(true);
    expect(referenceProbes(inputs)).toBe(first);
    expect(await referenceProbesAsync(inputs)).toBe(first);
    expect(first).toEqual(computeProbes(inputs, REFERENCE_STEPS, REFERENCE_STEPS));
  });
});
