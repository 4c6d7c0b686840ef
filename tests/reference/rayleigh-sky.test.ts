// The rayleigh-sky widget's float64 model (src/widgets/rayleigh-sky/model.ts) held
// to physical facts: β ∝ λ⁻⁴ in the Bruneton & Neyret 2008 coefficients, the
// geometry helpers against exact cases, the midpoint rule's O(h²) convergence, and
// the colours of the sky at noon and of the sun at sunset.
import { describe, expect, it } from 'vitest';
import {
  ATMOSPHERE_TOP,
  BETA_RAYLEIGH,
  EARTH_RADIUS,
  SCALE_HEIGHT,
  WAVELENGTHS_NM,
  altitudeAlong,
  computeProbes,
  distanceToTop,
  inputsFrom,
  probesFor,
  referenceProbes,
  skyRadiance,
  sunDensityIntegral,
  sunStepsFor,
  sunTransmittance,
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
