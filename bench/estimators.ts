// Benchmark: the transmittance estimators of shaders/tracking.wesl on three media
// (homogeneous, smooth heterogeneous, sharp-edged grid), on the GPU and with the
// float64 twins on the CPU. Reports mean, variance (and its closed form where one
// exists, physics.md §4), density lookups, time and efficiency 1/(variance × time).
// Timing is reported, never asserted.
import { linkKernel } from '../src/gpu/link.ts';
import { runCompute } from '../src/gpu/compute.ts';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import {
  gridMedium,
  homogeneousMedium,
  mediumExtinction,
  mediumMajorant,
  mediumOpticalDepth,
  sineMedium,
  type Medium1D,
} from '../src/reference/medium.ts';
import { rngSeed } from '../src/reference/rng.ts';
import {
  deltaTrackingVariance,
  ratioTrackingVariance,
  transmittanceDeltaTracking,
  transmittanceRatioTracking,
  transmittanceResidualRatioTracking,
  transmittanceUnbiasedRayMarching,
  type TransmittanceEstimate,
} from '../src/reference/tracking.ts';
import { median, type BenchTable } from './table.ts';

export interface BenchMedium {
  name: string;
  medium: Medium1D;
  d: number;
}

export const MEDIA: BenchMedium[] = [
  { name: 'homogeneous σt = 1, d = 1', medium: homogeneousMedium(1), d: 1 },
  { name: 'smooth 1 + 0.5 sin 3s, d = 2', medium: sineMedium(1, 0.5, 3), d: 2 },
  {
    name: 'sharp grid (0.2 | 3 cells), d = 2',
    medium: gridMedium([0.2, 3, 0.2, 3, 0.2, 3, 0.2, 3], 0.25),
    d: 2,
  },
];

type Estimator = 'delta' | 'ratio' | 'residual' | 'urm';

const MAX_STEPS = 65536;

interface EstimatorSetup {
  estimator: Estimator;
  label: string;
  /** WGSL call for one walk, with `medium`, `state` in scope. */
  wgsl: string;
  twin: (state: { value: number }) => TransmittanceEstimate;
  closedFormVariance: number | null;
}

function setups(entry: BenchMedium): EstimatorSetup[] {
  const { medium, d } = entry;
  const sigmaMaj = mediumMajorant(medium, 0, d);
  const tau = mediumOpticalDepth(medium, 0, d);
  const T = Math.exp(-tau);
  const sigmaControl = tau / d;
  // Residual majorant: the largest |σt − σc| (sampled densely; the profiles are known).
  let residual = 0;
  for (let i = 0; i <= 4096; i++) {
    const s = (d * i) / 4096;
    residual = Math.max(residual, Math.abs(mediumExtinction(medium, s) - sigmaControl));
  }
  // ∫ f(σt(s)) ds by the midpoint rule on 4096 steps: the closed-form variances of
  // physics.md §4.2–4.3 need ∫σt²/σ̄ and ∫(σt − σc)²/σ̄r.
  const integral = (f: (sigma: number) => number): number => {
    let sum = 0;
    for (let i = 0; i < 4096; i++) sum += f(mediumExtinction(medium, (d * (i + 0.5)) / 4096));
    return (sum * d) / 4096;
  };
  const ratioVariance = ratioTrackingVariance(
    T,
    integral((sigma) => (sigma * sigma) / sigmaMaj),
  );
  const residualMajorant = Math.max(residual, 1e-6);
  const residualVariance = ratioTrackingVariance(
    T,
    integral((sigma) => ((sigma - sigmaControl) * (sigma - sigmaControl)) / residualMajorant),
  );
  const homogeneous = medium.kind === 0;
  return [
    {
      estimator: 'delta',
      label: `delta tracking, σ̄ = ${sigmaMaj.toFixed(3)}`,
      wgsl: `transmittanceDeltaTracking(medium, ${d}, ${sigmaMaj}, &state, ${MAX_STEPS}u)`,
      twin: (state) => transmittanceDeltaTracking(medium, d, sigmaMaj, state, MAX_STEPS),
      closedFormVariance: deltaTrackingVariance(T),
    },
    {
      estimator: 'ratio',
      label: `ratio tracking, σ̄ = ${sigmaMaj.toFixed(3)}`,
      wgsl: `transmittanceRatioTracking(medium, ${d}, ${sigmaMaj}, &state, ${MAX_STEPS}u)`,
      twin: (state) => transmittanceRatioTracking(medium, d, sigmaMaj, state, MAX_STEPS),
      closedFormVariance: ratioVariance,
    },
    {
      estimator: 'residual',
      label: `residual ratio, σc = ${sigmaControl.toFixed(3)}, σ̄r = ${residual.toFixed(3)}`,
      wgsl: `transmittanceResidualRatioTracking(medium, ${d}, ${sigmaControl}, ${residualMajorant}, &state, ${MAX_STEPS}u)`,
      twin: (state) =>
        transmittanceResidualRatioTracking(
          medium,
          d,
          sigmaControl,
          residualMajorant,
          state,
          MAX_STEPS,
        ),
      closedFormVariance: residualVariance,
    },
    {
      estimator: 'urm',
      label: `unbiased ray marching (Kettunen 2021), σ̄ = ${sigmaMaj.toFixed(3)}`,
      wgsl: `transmittanceUnbiasedRayMarching(medium, ${d}, ${sigmaMaj}, &state, ${MAX_STEPS}u)`,
      twin: (state) => transmittanceUnbiasedRayMarching(medium, d, sigmaMaj, state, MAX_STEPS),
      closedFormVariance: homogeneous ? 0 : null,
    },
  ];
}

function wgslMedium(medium: Medium1D): string {
  const cells = Array.from({ length: 16 }, (_, i) => `${(medium.cells[i] ?? 0).toFixed(9)}`).join(
    ', ',
  );
  return (
    `Medium1D(${medium.kind}u, ${medium.sigma0}, ${medium.amplitude}, ${medium.frequency}, ${medium.phase}, ` +
    `${medium.cellSize}, ${medium.cellCount}u, array<f32, 16>(${cells}))`
  );
}

function kernel(entry: BenchMedium, setup: EstimatorSetup, walks: number): string {
  return `
import package::medium::Medium1D;
import package::rng::rngSeed;
import package::tracking::{TransmittanceEstimate, ${setup.wgsl.slice(0, setup.wgsl.indexOf('('))}};
@group(0) @binding(0) var<storage, read_write> results: array<u32>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= ${walks}u) { return; }
  let medium = ${wgslMedium(entry.medium)};
  var state = rngSeed(i, 7u);
  let r = ${setup.wgsl};
  results[3u * i] = bitcast<u32>(r.estimate);
  results[3u * i + 1u] = r.lookups;
  results[3u * i + 2u] = r.capped;
}`;
}

interface Moments {
  mean: number;
  variance: number;
  lookups: number;
  capped: number;
}

function moments(
  estimates: ArrayLike<number>,
  lookups: ArrayLike<number>,
  capped: ArrayLike<number>,
): Moments {
  const n = estimates.length;
  let sum = 0;
  let sumSquares = 0;
  let lookupSum = 0;
  let cappedSum = 0;
  for (let i = 0; i < n; i++) {
    const x = estimates[i] ?? 0;
    sum += x;
    sumSquares += x * x;
    lookupSum += lookups[i] ?? 0;
    cappedSum += capped[i] ?? 0;
  }
  const mean = sum / n;
  return {
    mean,
    variance: Math.max(sumSquares / n - mean * mean, 0) * (n / (n - 1)),
    lookups: lookupSum / n,
    capped: cappedSum,
  };
}

export async function benchEstimators(
  device: GPUDevice,
  options: { gpuWalks: number; cpuWalks: number; repeats: number },
): Promise<BenchTable> {
  const library = loadShaderLibrary(new URL('../shaders', import.meta.url).pathname);
  const rows: BenchTable['rows'] = [];
  for (const entry of MEDIA) {
    const exact = Math.exp(-mediumOpticalDepth(entry.medium, 0, entry.d));
    for (const setup of setups(entry)) {
      const code = await linkKernel(library, kernel(entry, setup, options.gpuWalks));
      const times: number[] = [];
      let gpu: Moments | null = null;
      let timing = 'gpu-timestamp';
      for (let r = 0; r < options.repeats; r++) {
        const { output, gpuMs, wallMs } = await runCompute(device, {
          code,
          inputs: [],
          outputWords: 3 * options.gpuWalks,
          workgroups: [Math.ceil(options.gpuWalks / 64)],
        });
        if (gpuMs === null) timing = 'gpu-wall';
        times.push(gpuMs ?? wallMs);
        if (!gpu) {
          const floats = new Float32Array(output.buffer);
          const n = options.gpuWalks;
          gpu = moments(
            Float32Array.from({ length: n }, (_, i) => floats[3 * i] ?? 0),
            Uint32Array.from({ length: n }, (_, i) => output[3 * i + 1] ?? 0),
            Uint32Array.from({ length: n }, (_, i) => output[3 * i + 2] ?? 0),
          );
        }
      }
      const cpuTimes: number[] = [];
      let cpu: Moments | null = null;
      for (let r = 0; r < options.repeats; r++) {
        const estimates = new Float64Array(options.cpuWalks);
        const lookups = new Float64Array(options.cpuWalks);
        const capped = new Float64Array(options.cpuWalks);
        const start = performance.now();
        for (let i = 0; i < options.cpuWalks; i++) {
          const result = setup.twin({ value: rngSeed(i, 7) });
          estimates[i] = result.estimate;
          lookups[i] = result.lookups;
          capped[i] = result.capped;
        }
        cpuTimes.push(performance.now() - start);
        cpu ??= moments(estimates, lookups, capped);
      }
      if (!gpu || !cpu) continue;
      const gpuSecondsPerWalk = median(times) / 1000 / options.gpuWalks;
      const cpuSecondsPerWalk = median(cpuTimes) / 1000 / options.cpuWalks;
      rows.push({
        medium: entry.name,
        estimator: setup.label,
        exact,
        'gpu mean': gpu.mean,
        'gpu variance': gpu.variance,
        'closed-form variance': setup.closedFormVariance,
        'lookups/walk': gpu.lookups,
        'gpu capped': gpu.capped,
        [`gpu ns/walk (${timing})`]: gpuSecondsPerWalk * 1e9,
        'gpu efficiency 1/(Var·s)':
          gpu.variance > 0 ? 1 / (gpu.variance * gpuSecondsPerWalk) : Infinity,
        'cpu mean': cpu.mean,
        'cpu variance': cpu.variance,
        'cpu ns/walk': cpuSecondsPerWalk * 1e9,
        'cpu efficiency 1/(Var·s)':
          cpu.variance > 0 ? 1 / (cpu.variance * cpuSecondsPerWalk) : Infinity,
      });
    }
  }
  return {
    title: 'Transmittance estimators (physics.md §4): variance × time',
    notes: [
      `GPU: ${options.gpuWalks} walks per dispatch, median of ${options.repeats} dispatches; CPU (float64 twin): ${options.cpuWalks} walks, median of ${options.repeats}.`,
      'Efficiency is 1/(variance × seconds per estimate): higher is better. Zero variance shows as Infinity.',
      'Closed forms (physics.md §4): delta tracking T(1−T); ratio tracking T²(exp(∫σt²/σ̄) − 1); residual ratio tracking T²(exp(∫(σt−σc)²/σ̄r) − 1); unbiased ray marching has none (0 for homogeneous media).',
    ],
    rows,
  };
}
