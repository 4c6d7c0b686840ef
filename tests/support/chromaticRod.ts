// Multiple scattering in a chromatic rod (the 1D slab of the rod model: a path moves along x
// in [0, L] and each scattering sends it forward or back with probability 1/2), by the three
// estimators of src/reference/chromatic.ts, against the closed-form two-stream solution of a
// homogeneous rod. With optical thickness τ = σt L and κ = sqrt(1 − α),
//   R = (1 − κ²)(e^{κτ} − e^{−κτ}) / Δ,  T = 4κ / Δ,  Δ = (1 + κ)² e^{κτ} − (1 − κ)² e^{−κτ}
// (α = 0 gives T = e^{−τ}, R = 0; α → 1 gives T = 1/(1 + τ/2), the conservative rod).
// Paths continue by Russian roulette with survival min(1, max channel weight), unbiased.
import {
  CHROMATIC_PASSED,
  CHROMATIC_SCATTERED,
  deltaFreeFlight,
  heroChannelWeights,
  heroEventLogPdfs,
  spectralFreeFlight,
  type ChromaticMedium,
  type Rgb,
} from '../../src/reference/chromatic.ts';
import { rngNextFloat, type RngState } from '../../src/reference/rng.ts';

export type RodEstimator = 'oneChannel' | 'hero' | 'spectralAverage' | 'spectralMax';

export interface RodEstimate {
  R: Rgb;
  T: Rgb;
}

const MAX_BOUNCES = 100_000;
const MAX_STEPS = 65536;

/** Closed-form reflectance and transmittance of a homogeneous rod, per channel. */
export function rodClosedForm(
  sigmaT: number,
  albedo: number,
  length: number,
): { R: number; T: number } {
  const tau = sigmaT * length;
  const k = Math.sqrt(Math.max(1 - albedo, 0));
  if (k === 0) return { R: tau / 2 / (1 + tau / 2), T: 1 / (1 + tau / 2) };
  const up = Math.exp(k * tau);
  const down = Math.exp(-k * tau);
  const delta = (1 + k) ** 2 * up - (1 - k) ** 2 * down;
  return { R: ((1 - k * k) * (up - down)) / delta, T: (4 * k) / delta };
}

/** One path entering at x = 0 moving +x: its contributions to R (leaving at 0) and T (at L). */
export function rodWalk(
  estimator: RodEstimator,
  medium: ChromaticMedium,
  length: number,
  state: RngState,
): RodEstimate {
  const out: RodEstimate = { R: [0, 0, 0], T: [0, 0, 0] };
  const channels: number[] = estimator === 'oneChannel' ? [0, 1, 2] : [-1];
  for (const channel of channels) {
    let x = 0;
    let direction = 1;
    let weight: Rgb = [1, 1, 1];
    let logPdfs: Rgb = [0, 0, 0];
    const hero = estimator === 'hero' ? Math.min(Math.floor(rngNextFloat(state) * 3), 2) : -1;
    for (let bounce = 0; bounce < MAX_BOUNCES; bounce++) {
      const d = direction > 0 ? length - x : x;
      let t: number;
      let event: number;
      if (estimator === 'oneChannel' || estimator === 'hero') {
        const c = estimator === 'hero' ? hero : channel;
        const f = deltaFreeFlight(medium, medium.sigmaT[c]!, d, state, MAX_STEPS);
        t = f.t;
        event = f.event;
        if (estimator === 'hero') {
          const step = heroEventLogPdfs(medium, t, event === CHROMATIC_SCATTERED);
          logPdfs = [logPdfs[0] + step[0], logPdfs[1] + step[1], logPdfs[2] + step[2]];
        }
      } else {
        const scheme = estimator === 'spectralMax' ? 1 : 0;
        const f = spectralFreeFlight(medium, d, weight, scheme, state, MAX_STEPS);
        t = f.t;
        event = f.event;
        weight = f.weight;
      }
      if (event === CHROMATIC_PASSED) {
        let contribution: Rgb = weight;
        if (estimator === 'hero') {
          const w = heroChannelWeights(logPdfs, hero);
          contribution = [weight[0] * w[0], weight[1] * w[1], weight[2] * w[2]];
        }
        const target = direction > 0 ? out.T : out.R;
        for (let c = 0; c < 3; c++) {
          if (channel < 0 || c === channel) target[c] = target[c]! + contribution[c]!;
        }
        break;
      }
      if (event !== CHROMATIC_SCATTERED) break;
      // A collision of delta tracking: the analog weight f_c/p_c of the own channel is α_c
      // (one channel at a time uses only its own entry).
      if (estimator === 'oneChannel' || estimator === 'hero') {
        weight = [
          weight[0] * medium.albedo[0],
          weight[1] * medium.albedo[1],
          weight[2] * medium.albedo[2],
        ];
      }
      x += direction * t;
      direction = rngNextFloat(state) < 0.5 ? 1 : -1;
      const live = channel < 0 ? Math.max(...weight) : weight[channel]!;
      const q = Math.min(1, live);
      if (!(rngNextFloat(state) < q)) break;
      weight = [weight[0] / q, weight[1] / q, weight[2] / q];
    }
  }
  return out;
}
