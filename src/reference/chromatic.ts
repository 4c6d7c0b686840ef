// Float64 twin of shaders/chromatic.wesl (chapter 12, colour in a medium): free flights and
// path weights of a chromatic medium, σt,c(s) = ρ(s)·σt,c with ρ(s) = max(ρ0 + ρ1 s, 0), by
// one channel at a time (delta tracking per channel), hero wavelength (Wilkie et al. 2014,
// one-sample balance heuristic over the channels' path pdfs) and spectral tracking (Kutz,
// Habel, Li & Novák 2017). The same names, arguments and random-number draws as the shader,
// so a test replays a GPU walk seed by seed.
import { averageComponent, maxComponent } from './integrator.ts';
import { rngNextFloat, type RngState } from './rng.ts';
import { sampleFreeFlight } from './tracking.ts';

export type Rgb = [number, number, number];

export const CHROMATIC_PASSED = 0;
export const CHROMATIC_SCATTERED = 1;
export const CHROMATIC_ABSORBED = 2;
export const SPECTRAL_AVERAGE = 0;
export const SPECTRAL_MAX = 1;
export const CHROMATIC_LOG_ZERO = -1e30;

export interface ChromaticMedium {
  /** Per-channel extinction at density 1 (1/m). */
  sigmaT: Rgb;
  /** ρ0 (dimensionless). */
  densityBase: number;
  /** Per-channel single-scattering albedo. */
  albedo: Rgb;
  /** ρ1 (1/m). */
  densitySlope: number;
}

export interface ChromaticFlight {
  t: number;
  event: number;
  weight: Rgb;
  lookups: number;
  capped: number;
}

const map3 = (v: Rgb, f: (x: number, i: number) => number): Rgb => [
  f(v[0], 0),
  f(v[1], 1),
  f(v[2], 2),
];

export function chromaticDensity(medium: ChromaticMedium, s: number): number {
  return Math.max(medium.densityBase + medium.densitySlope * s, 0);
}

/** D(s) = ∫0^s max(ρ0 + ρ1 u, 0) du in closed form. */
export function chromaticOpticalDepth(medium: ChromaticMedium, s: number): number {
  const b = medium.densityBase;
  const a = medium.densitySlope;
  if (!(s > 0)) return 0;
  if (a === 0) return Math.max(b, 0) * s;
  if (a > 0) {
    if (b >= 0) return s * (b + 0.5 * a * s);
    const r = Math.max(s + b / a, 0);
    return 0.5 * a * r * r;
  }
  if (b <= 0) return 0;
  const u = Math.min(s, -b / a);
  return u * (b + 0.5 * a * u);
}

export function chromaticMajorantDensity(medium: ChromaticMedium, d: number): number {
  return Math.max(chromaticDensity(medium, 0), chromaticDensity(medium, Math.max(d, 0)));
}

export function chromaticTransmittance(medium: ChromaticMedium, s: number): Rgb {
  const depth = chromaticOpticalDepth(medium, s);
  return map3(medium.sigmaT, (x) => Math.exp(-x * depth));
}

/** One channel's delta tracking (extinction `sigma` at density 1). */
export function deltaFreeFlight(
  medium: ChromaticMedium,
  sigma: number,
  d: number,
  state: RngState,
  maxSteps: number,
): ChromaticFlight {
  const flight: ChromaticFlight = {
    t: d,
    event: CHROMATIC_PASSED,
    weight: [1, 1, 1],
    lookups: 0,
    capped: 0,
  };
  const densityMaj = chromaticMajorantDensity(medium, d);
  const sigmaMaj = sigma * densityMaj;
  if (!(sigmaMaj > 0) || !(d > 0)) return flight;
  let t = 0;
  for (;;) {
    const step = sampleFreeFlight(sigmaMaj, rngNextFloat(state));
    if (step >= d - t) break;
    if (flight.lookups >= maxSteps) {
      flight.capped = 1;
      break;
    }
    flight.lookups++;
    t += step;
    if (rngNextFloat(state) * densityMaj < chromaticDensity(medium, t)) {
      flight.t = t;
      flight.event = CHROMATIC_SCATTERED;
      break;
    }
  }
  return flight;
}

/** ln p_c of a collision at t (ln σt,c ρ(t) − σt,c D(t)) or of passing at t = d (−σt,c D(d)). */
export function heroEventLogPdfs(medium: ChromaticMedium, t: number, collided: boolean): Rgb {
  const depth = chromaticOpticalDepth(medium, t);
  if (!collided) return map3(medium.sigmaT, (x) => -x * depth);
  const density = chromaticDensity(medium, t);
  return map3(medium.sigmaT, (x) => {
    const rate = x * density;
    return rate > 0 ? Math.log(rate) - x * depth : CHROMATIC_LOG_ZERO;
  });
}

/** One-sample balance heuristic: f_c·w_h/(p_h/3) = f_c·3/Σp_k, whichever channel h was the hero. */
export function heroBalanceWeight(pdfs: Rgb, _hero: number): number {
  const total = pdfs[0] + pdfs[1] + pdfs[2];
  return total > 0 ? 3 / total : 0;
}

/** 3·p_c/Σp_k from log pdfs, shifted by their maximum so that nothing underflows. */
export function heroChannelWeights(logPdfs: Rgb, hero: number): Rgb {
  const top = maxComponent(logPdfs);
  const ratios = map3(logPdfs, (x) => Math.exp(x - top));
  const w = heroBalanceWeight(ratios, hero);
  return map3(ratios, (x) => x * w);
}

/** (P_a, P_s, P_n) ∝ avg or max over channels of σ_x ⊙ w (Kutz et al. 2017 §5.1). */
export function spectralEventProbabilities(
  sigmaA: Rgb,
  sigmaS: Rgb,
  sigmaN: Rgb,
  weight: Rgb,
  scheme: number,
): Rgb {
  const reduce = scheme === SPECTRAL_MAX ? maxComponent : averageComponent;
  const times = (s: Rgb): Rgb => map3(s, (x, i) => x * weight[i]!);
  const p = map3([reduce(times(sigmaA)), reduce(times(sigmaS)), reduce(times(sigmaN))], (x) =>
    Math.max(x, 0),
  );
  const total = p[0] + p[1] + p[2];
  if (!(total > 0)) return [1, 0, 0];
  return map3(p, (x) => x / total);
}

/** Spectral tracking through [0, d] at the majorant ρ̄·max σt,c, starting with weight w0. */
export function spectralFreeFlight(
  medium: ChromaticMedium,
  d: number,
  weight: Rgb,
  scheme: number,
  state: RngState,
  maxSteps: number,
): ChromaticFlight {
  const flight: ChromaticFlight = {
    t: d,
    event: CHROMATIC_PASSED,
    weight: [...weight],
    lookups: 0,
    capped: 0,
  };
  const majorant = maxComponent(medium.sigmaT) * chromaticMajorantDensity(medium, d);
  if (!(majorant > 0) || !(d > 0)) return flight;
  const albedo = map3(medium.albedo, (x) => Math.min(Math.max(x, 0), 1));
  let t = 0;
  for (;;) {
    const step = sampleFreeFlight(majorant, rngNextFloat(state));
    if (step >= d - t) break;
    if (flight.lookups >= maxSteps) {
      flight.capped = 1;
      break;
    }
    flight.lookups++;
    t += step;
    const density = chromaticDensity(medium, t);
    const sigmaT = map3(medium.sigmaT, (x) => density * x);
    const sigmaS = map3(sigmaT, (x, i) => albedo[i]! * x);
    const sigmaA = map3(sigmaT, (x, i) => x - sigmaS[i]!);
    const sigmaN = map3(sigmaT, (x) => Math.max(majorant - x, 0));
    const p = spectralEventProbabilities(sigmaA, sigmaS, sigmaN, flight.weight, scheme);
    const xi = rngNextFloat(state);
    if (xi < p[0] || (p[1] <= 0 && p[2] <= 0)) {
      flight.t = t;
      flight.event = CHROMATIC_ABSORBED;
      break;
    }
    if (xi < p[0] + p[1] || p[2] <= 0) {
      flight.t = t;
      flight.event = CHROMATIC_SCATTERED;
      flight.weight = map3(flight.weight, (x, i) => (x * sigmaS[i]!) / (majorant * p[1]));
      break;
    }
    flight.weight = map3(flight.weight, (x, i) => (x * sigmaN[i]!) / (majorant * p[2]));
  }
  return flight;
}
