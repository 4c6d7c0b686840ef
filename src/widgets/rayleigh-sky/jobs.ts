// The heavy float64 work of <sb-rayleigh-sky>, run in the compute worker
// (src/workers/compute.ts) and cached there by arguments: the converged reference
// (once per sun elevation), the CPU fallback's panorama at a refinement stage's
// resolution, and the CPU probes timed over enough repetitions for the clock. No DOM,
// no GPU: plain functions of structured-cloneable arguments.
import { skyPixels } from './cpuBackend.ts';
import { REFERENCE_STEPS, computeProbes, median, type SkyInputs, type SkyProbes } from './model.ts';

/** The CPU probes are timed in batches of at least this long (the clock's resolution is 5–100 µs). */
export const PROBE_BATCH_MS = 5;
/** Batches per timing; the time is the median of the batch means. */
export const PROBE_BATCHES = 3;

/** The panorama's pixels and the float64 time it took (ms). */
export interface SkyImage {
  pixels: Uint8ClampedArray<ArrayBuffer>;
  width: number;
  height: number;
  milliseconds: number;
}

/** The float64 probes at the inputs' N and M and the time of one evaluation (ms). */
export interface TimedProbes {
  probes: SkyProbes;
  milliseconds: number;
  /** Evaluations timed in all (the time is a mean over each batch's repeats). */
  repeats: number;
}

/**
 * The CPU wall time of the three float64 probes and the sun: one evaluation takes µs
 * to ms, below the clock's resolution at small N, so each of PROBE_BATCHES batches
 * repeats it for at least PROBE_BATCH_MS; the median of the batch means.
 */
export function timeProbes(
  inputs: SkyInputs,
  batchMs = PROBE_BATCH_MS,
  batches = PROBE_BATCHES,
): TimedProbes {
  let probes = computeProbes(inputs);
  const perEvaluation: number[] = [];
  let repeats = 0;
  for (let batch = 0; batch < batches; batch++) {
    let count = 0;
    const start = performance.now();
    let elapsed = 0;
    do {
      probes = computeProbes(inputs);
      count += 1;
      elapsed = performance.now() - start;
    } while (elapsed < batchMs);
    repeats += count;
    perEvaluation.push(elapsed / count);
  }
  return { probes, milliseconds: median(perEvaluation), repeats };
}

export const jobs = {
  /** The converged reference (N = M = REFERENCE_STEPS): it depends on the sun and the air only. */
  reference(sinSun: number, cosSun: number, scattering: boolean): SkyProbes {
    const inputs: SkyInputs = {
      sunElevationDeg: (Math.atan2(sinSun, cosSun) * 180) / Math.PI,
      sinSun,
      cosSun,
      scattering,
      steps: REFERENCE_STEPS,
      sunSteps: REFERENCE_STEPS,
      exposure: 0,
    };
    return computeProbes(inputs, REFERENCE_STEPS, REFERENCE_STEPS);
  },
  /** The CPU fallback's panorama at width × height (the float64 twin of skyFragment). */
  panorama(inputs: SkyInputs, width: number, height: number): SkyImage {
    const start = performance.now();
    const pixels = skyPixels(inputs, width, height);
    return { pixels, width, height, milliseconds: performance.now() - start };
  },
  /** The CPU probes with their time per evaluation (timeProbes). */
  probes(inputs: SkyInputs): TimedProbes {
    return timeProbes(inputs);
  },
};
