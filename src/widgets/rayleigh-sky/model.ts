// What the rayleigh-sky widget computes, independent of the backend: its inputs,
// the atmosphere, the probe directions, and the float64 twin of the kernel's
// single-scattering integral (the CPU fallback and, with N = M = 1024, the
// converged reference the GPU probes are compared with).
//
// Physics (physics.md §2.6 for p_R; §1 for T = e^{−τ}): single Rayleigh scattering
// of a white sun (E_sun = 1 per channel) in a spherically symmetric atmosphere
// with density ρ(h) = e^{−h/H}, no absorption (σa = 0, ozone ignored):
//   L(λ) = ∫₀^{t_max} T(x→x_t) σs(λ, h(t)) p_R(ν) E_sun T_sun(x_t) dt,
// σs(λ, h) = β(λ)·ρ(h). Atmosphere and coefficients from Bruneton & Neyret,
// "Precomputed Atmospheric Scattering", EGSR 2008, §4: R_ground = 6360 km,
// R_top = 6420 km, H_R = 8 km, β_R = (5.8, 13.5, 33.1)·10⁻⁶ m⁻¹ at
// λ = (680, 550, 440) nm. Geometry in the (r, μ, μ_s, ν) form of the same paper.
import { rayleighEval } from '../../reference/phase.ts';
import { transmittanceFromOpticalThickness } from '../../reference/transmittance.ts';
import type { ParameterValues } from '../parameters.ts';
// The fit from the statistics module, the point type as a type only: this module stays
// free of the DOM (widget.ts imports it, and Node imports every widget.ts).
import { logLogSlope } from '../../statistics/regression.ts';
import type { SweepPoint } from '../base/sweep.ts';
import { CANVAS_HEIGHT, CANVAS_WIDTH, FIT_FROM_STEPS, REFERENCE_STEPS } from './constants.ts';

// The constants widget.ts needs live in constants.ts (every page loads widget.ts, not this).
export { CANVAS_HEIGHT, CANVAS_WIDTH, FIT_FROM_STEPS, REFERENCE_STEPS };

/** Earth radius and top of the atmosphere (m), Bruneton & Neyret 2008. */
export const EARTH_RADIUS = 6360e3;
export const ATMOSPHERE_TOP = 6420e3;
/** Rayleigh scale height H (m). */
export const SCALE_HEIGHT = 8e3;
/** Wavelengths (nm) of the red, green and blue channels. */
export const WAVELENGTHS_NM = [680, 550, 440] as const;
/** Sea-level Rayleigh scattering coefficients β (1/m) at WAVELENGTHS_NM. */
export const BETA_RAYLEIGH = [5.8e-6, 13.5e-6, 33.1e-6] as const;

/** The panorama: 120° of azimuth centred on the sun, elevation −5° … +85°. */
export const FIELD_OF_VIEW_DEG = 120;
export const ELEVATION_MIN_DEG = -5;
export const ELEVATION_MAX_DEG = 85;
/** Apparent angular radius of the sun (°), drawn enlarged ×4 so it is several pixels wide. */
export const SUN_RADIUS_DEG = 0.27;
export const SUN_ENLARGEMENT = 4;
/** Display: c = 1 − exp(−K·2^EV·L) per channel, then the sRGB transfer function. */
export const EXPOSURE_BASE = 30;
/** Hard caps of the kernel's loops (N ≤ 128 view samples, M ≤ 32 sun samples). */
export const MAX_STEPS = 128;

export interface SkyInputs {
  sunElevationDeg: number;
  /** sin and cos of the sun elevation, f32-rounded (the GPU sees the same numbers). */
  sinSun: number;
  cosSun: number;
  scattering: boolean;
  /** N view-ray samples and M = max(4, ⌈N/4⌉) sun-ray samples per view sample. */
  steps: number;
  sunSteps: number;
  exposure: number;
}

/** M: the sun ray halves its step with the view ray, so the error stays O(h²), at N²/4 cost. */
export function sunStepsFor(steps: number): number {
  return Math.max(4, Math.ceil(steps / 4));
}

export function inputsFrom(values: ParameterValues): SkyInputs {
  const sunElevationDeg = Number(values['sun-elevation']);
  const radians = (sunElevationDeg * Math.PI) / 180;
  const steps = Math.min(Math.max(Math.round(Number(values['steps'])), 1), MAX_STEPS);
  return {
    sunElevationDeg,
    sinSun: Math.fround(Math.sin(radians)),
    cosSun: Math.fround(Math.cos(radians)),
    scattering: values['scattering'] !== 'off',
    steps,
    sunSteps: sunStepsFor(steps),
    exposure: Number(values['exposure']),
  };
}

export type Rgb = [number, number, number];

/**
 * A probe direction as the kernel sees it: μ = cos of the view zenith angle and
 * ν = (view direction)·(direction to the sun), both f32-rounded. ν is also the
 * scattering cosine: sunlight travels along −s and reaches the camera along −d,
 * and (−s)·(−d) = s·d, so μ_scatter = ν in the convention of shaders/phase.wesl.
 */
export interface Probe {
  key: 'zenith' | 'toward' | 'away';
  label: string;
  mu: number;
  nu: number;
}

export function probesFor(inputs: Pick<SkyInputs, 'sinSun' | 'cosSun'>): Probe[] {
  const e = (10 * Math.PI) / 180;
  const { sinSun, cosSun } = inputs;
  return [
    { key: 'zenith', label: 'Zenith', mu: 1, nu: sinSun },
    {
      key: 'toward',
      label: '10° above the horizon, toward the sun',
      mu: Math.fround(Math.sin(e)),
      nu: Math.fround(Math.cos(e) * cosSun + Math.sin(e) * sinSun),
    },
    {
      key: 'away',
      label: '10° above the horizon, away from the sun',
      mu: Math.fround(Math.sin(e)),
      nu: Math.fround(-Math.cos(e) * cosSun + Math.sin(e) * sinSun),
    },
  ];
}

/**
 * Altitude (m) at distance s (m) along a ray that starts at altitude h with zenith
 * cosine μ: r_s² − R² = h(2R + h) + s(s + 2rμ) (law of cosines, r = R + h), and
 * h_s = (r_s² − R²)/(r_s + R), which avoids subtracting two radii of 6360 km.
 */
export function altitudeAlong(h: number, mu: number, s: number): number {
  const r = EARTH_RADIUS + h;
  const q = h * (2 * EARTH_RADIUS + h) + s * (s + 2 * r * mu);
  const rs = Math.sqrt(Math.max(EARTH_RADIUS * EARTH_RADIUS + q, 0));
  return Math.max(q / (rs + EARTH_RADIUS), 0);
}

/**
 * Distance (m) from altitude h along zenith cosine μ to the top of the atmosphere:
 * the positive root of s² + 2rμs − (R_top² − r²) = 0, in the form without
 * cancellation for either sign of μ. Null when the ray hits the Earth first
 * (μ < 0 and r²(1 − μ²) ≤ R², i.e. (rμ)² ≥ h(2R + h)).
 */
export function distanceToTop(h: number, mu: number): number | null {
  const r = EARTH_RADIUS + h;
  const rMu = r * mu;
  if (mu < 0 && rMu * rMu >= h * (2 * EARTH_RADIUS + h)) return null;
  const outside = (ATMOSPHERE_TOP - r) * (ATMOSPHERE_TOP + r);
  const root = Math.sqrt(Math.max(rMu * rMu + outside, 0));
  return mu >= 0 ? outside / (rMu + root) : root - rMu;
}

/**
 * ∫ρ ds (m) from altitude h toward the sun (zenith cosine μ_s) to the top of the
 * atmosphere, by the midpoint rule with `steps` samples; null in the Earth's shadow.
 */
export function sunDensityIntegral(h: number, muSun: number, steps: number): number | null {
  const length = distanceToTop(h, Math.min(Math.max(muSun, -1), 1));
  if (length === null) return null;
  const ds = length / steps;
  let sum = 0;
  for (let j = 0; j < steps; j++)
    sum += Math.exp(-altitudeAlong(h, muSun, (j + 0.5) * ds) / SCALE_HEIGHT);
  return sum * ds;
}

/** β per channel (1/m): the sea-level values, or 0 with scattering off. */
export function betaFor(scattering: boolean): Rgb {
  return scattering ? [...BETA_RAYLEIGH] : [0, 0, 0];
}

/** Transmittance of the direct sun to the observer at sea level, per channel. */
export function sunTransmittance(muSun: number, sunSteps: number, scattering: boolean): Rgb {
  const density = sunDensityIntegral(0, muSun, sunSteps);
  if (density === null) return [0, 0, 0];
  const beta = betaFor(scattering);
  return [0, 1, 2].map((c) => transmittanceFromOpticalThickness(beta[c]! * density)) as Rgb;
}

/**
 * Single-scattered radiance L (per unit E_sun, 1/sr) reaching the observer at sea
 * level from view zenith cosine μ ≥ 0, for a sun at zenith cosine μ_s with
 * ν = view·sun. N midpoint samples t_i = (i + ½)Δt on [0, t_max]; the view optical
 * depth to t_i is the midpoint sum over the previous cells plus half of cell i
 * (O(Δt²) like the rule itself). At each sample the sun's zenith cosine is
 * μ_s' = (R μ_s + t ν)/r_t (Bruneton & Neyret 2008, eq. 10 with r = R).
 * A view ray below the horizon (μ < 0) meets the ground: it returns 0 (no ground).
 */
export function skyRadiance(
  mu: number,
  muSun: number,
  nu: number,
  steps: number,
  sunSteps: number,
  scattering: boolean,
): Rgb {
  const radiance: Rgb = [0, 0, 0];
  const beta = betaFor(scattering);
  if (!scattering || mu < 0) return radiance;
  const tMax = distanceToTop(0, mu) ?? 0;
  const dt = tMax / steps;
  let viewDensity = 0;
  for (let i = 0; i < steps; i++) {
    const t = (i + 0.5) * dt;
    const h = altitudeAlong(0, mu, t);
    const rho = Math.exp(-h / SCALE_HEIGHT);
    const toSample = viewDensity + 0.5 * rho * dt;
    viewDensity += rho * dt;
    const muSunHere = (EARTH_RADIUS * muSun + t * nu) / (EARTH_RADIUS + h);
    const toSun = sunDensityIntegral(h, muSunHere, sunSteps);
    if (toSun === null) continue;
    for (let c = 0; c < 3; c++)
      radiance[c] =
        radiance[c]! + transmittanceFromOpticalThickness(beta[c]! * (toSample + toSun)) * rho * dt;
  }
  const phase = rayleighEval(nu);
  return radiance.map((l, c) => l * beta[c]! * phase) as Rgb;
}

export interface SkyProbes {
  /** Radiance at the three probes, in probesFor order. */
  radiance: Rgb[];
  /** Direct-sun transmittance at sea level. */
  sunTransmittance: Rgb;
}

/** The probes and the sun with N view and M sun samples, in float64. */
export function computeProbes(
  inputs: SkyInputs,
  steps = inputs.steps,
  sunSteps = inputs.sunSteps,
): SkyProbes {
  return {
    radiance: probesFor(inputs).map((p) =>
      skyRadiance(p.mu, inputs.sinSun, p.nu, steps, sunSteps, inputs.scattering),
    ),
    sunTransmittance: sunTransmittance(inputs.sinSun, sunSteps, inputs.scattering),
  };
}

const referenceCache = new Map<string, SkyProbes>();
const pendingReferences = new Map<string, Promise<SkyProbes>>();

/**
 * The reference depends on the sun (sin and cos of its elevation) and on whether
 * air scatters, never on N, M or the exposure: one entry per (elevation, scattering).
 */
function referenceKey(inputs: Pick<SkyInputs, 'sinSun' | 'cosSun' | 'scattering'>): string {
  return `${inputs.sinSun},${inputs.cosSun},${inputs.scattering}`;
}

function storeReference(key: string, probes: SkyProbes): SkyProbes {
  if (referenceCache.size > 64) referenceCache.clear();
  referenceCache.set(key, probes);
  return probes;
}

/** The converged reference (N = M = 1024, float64), computed once per sun elevation. */
export function referenceProbes(inputs: SkyInputs): SkyProbes {
  const key = referenceKey(inputs);
  return (
    referenceCache.get(key) ??
    storeReference(key, computeProbes(inputs, REFERENCE_STEPS, REFERENCE_STEPS))
  );
}

/**
 * The same cached reference, computed one probe at a time with a yield to the page
 * between probes: a new sun elevation costs 3 × 1024 × 1024 sun-ray samples
 * (≈ 60 ms in float64), which would otherwise hold up input while a slider moves.
 * Concurrent requests for one key share one computation.
 */
export function referenceProbesAsync(inputs: SkyInputs): Promise<SkyProbes> {
  const key = referenceKey(inputs);
  const cached = referenceCache.get(key);
  if (cached) return Promise.resolve(cached);
  let pending = pendingReferences.get(key);
  if (!pending) {
    pending = (async () => {
      const radiance: Rgb[] = [];
      for (const probe of probesFor(inputs)) {
        await new Promise((resolve) => setTimeout(resolve, 0));
        radiance.push(
          skyRadiance(
            probe.mu,
            inputs.sinSun,
            probe.nu,
            REFERENCE_STEPS,
            REFERENCE_STEPS,
            inputs.scattering,
          ),
        );
      }
      const sun = sunTransmittance(inputs.sinSun, REFERENCE_STEPS, inputs.scattering);
      return storeReference(key, { radiance, sunTransmittance: sun });
    })().finally(() => pendingReferences.delete(key));
    pendingReferences.set(key, pending);
  }
  return pending;
}

/** Whether the reference for these inputs is already cached (tests check it is reused). */
export function hasCachedReference(inputs: SkyInputs): boolean {
  return referenceCache.has(referenceKey(inputs));
}

/**
 * The sweep's error measure: the relative RMS error over the three probes and the
 * three channels, √(Σ ((L − L_ref)/L_ref)² / K) over the K pairs with L_ref > 0.
 * Relative, so the dim red and the bright blue channel weigh alike. Null when
 * every reference value is 0 (scattering off: both are exactly 0 at every N).
 */
export function probeError(
  estimate: Pick<SkyProbes, 'radiance'>,
  reference: SkyProbes,
): number | null {
  let sum = 0;
  let count = 0;
  reference.radiance.forEach((referenceRgb, k) => {
    for (let c = 0; c < 3; c++) {
      const exact = referenceRgb[c]!;
      if (!(exact > 0)) continue;
      sum += ((estimate.radiance[k]![c]! - exact) / exact) ** 2;
      count += 1;
    }
  });
  return count > 0 ? Math.sqrt(sum / count) : null;
}

/** The view-ray sample counts N of the convergence sweep (M = sunStepsFor(N) with each). */
export const SWEEP_STEPS = [4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128] as const;

export interface SweepFit {
  /** p in error ∝ N^p: −2 for the midpoint rule on a smooth integrand (physics.md §3). */
  order: number | null;
  /** a in time ∝ N^a: 2 where the work N·M = N²/4 dominates, less where fixed costs do. */
  timeExponent: number | null;
  /** q in error ∝ time^q, fitted directly (≈ p/a). */
  timeOrder: number | null;
  /** The number of points fitted. */
  count: number;
}

/** Least-squares log–log slopes over the sweep points with N ≥ FIT_FROM_STEPS. */
export function fitSweep(points: readonly SweepPoint[]): SweepFit {
  const used = points.filter((p) => p.n >= FIT_FROM_STEPS);
  const n = used.map((p) => p.n);
  const time = used.map((p) => p.milliseconds);
  const error = used.map((p) => p.rmse);
  return {
    order: logLogSlope(n, error),
    timeExponent: logLogSlope(n, time),
    timeOrder: logLogSlope(time, error),
    count: used.length,
  };
}

/** The median of a non-empty list (the middle value, or the mean of the two middle ones). */
export function median(values: readonly number[]): number {
  if (values.length === 0) throw new Error('median of an empty list');
  const sorted = [...values].sort((a, b) => a - b);
  const middle = Math.floor(sorted.length / 2);
  return sorted.length % 2 === 1 ? sorted[middle]! : (sorted[middle - 1]! + sorted[middle]!) / 2;
}

/**
 * GPU timestamps are quantized (to 100 µs in Chrome), so a panorama that takes a few
 * µs on a fast GPU reads 0. It is drawn `passes` times in one submit and timed as
 * one span; this picks the pass count for the next measurement from the last span:
 * enough passes for TIMED_SPAN_MS, at most MAX_TIMED_PASSES.
 */
export const TIMED_SPAN_MS = 2;
export const MAX_TIMED_PASSES = 64;
export function nextPassCount(passes: number, spanMilliseconds: number): number {
  if (spanMilliseconds >= TIMED_SPAN_MS || passes >= MAX_TIMED_PASSES) return passes;
  const wanted =
    spanMilliseconds > 0
      ? Math.ceil((1.25 * passes * TIMED_SPAN_MS) / spanMilliseconds)
      : 8 * passes;
  return Math.min(Math.max(wanted, passes + 1), MAX_TIMED_PASSES);
}

/** Largest relative error over the channels, or null when the reference is 0 (then both are 0). */
export function relativeError(estimate: Rgb, reference: Rgb): number | null {
  let worst: number | null = null;
  for (let c = 0; c < 3; c++) {
    if (reference[c]! <= 0) continue;
    const error = Math.abs(estimate[c]! - reference[c]!) / reference[c]!;
    worst = Math.max(worst ?? 0, error);
  }
  return worst;
}

/** The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1]. */
export function srgbEncode(linear: number): number {
  const c = Math.min(Math.max(linear, 0), 1);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055;
}

/** K·2^EV: the factor applied to L before c = 1 − e^{−K·2^EV·L}. */
export function exposureScale(exposure: number): number {
  return EXPOSURE_BASE * 2 ** exposure;
}

/** The view direction of a panorama position (pixels from the top left) as elevation and azimuth (rad). */
export function panoramaAngles(
  px: number,
  py: number,
  width: number,
  height: number,
): { elevation: number; azimuth: number } {
  const degrees = Math.PI / 180;
  return {
    azimuth: (px / width - 0.5) * FIELD_OF_VIEW_DEG * degrees,
    elevation:
      (ELEVATION_MAX_DEG - (py / height) * (ELEVATION_MAX_DEG - ELEVATION_MIN_DEG)) * degrees,
  };
}
