// Host side of the slab Monte Carlo kernel (shaders/kernels/slab.wesl, physics.md §7):
// packs a run, dispatches it on a device (Dawn in Node, the page's device in a
// browser), replays the same walks with the float64 twin on the CPU, and turns the
// per-batch records of either into estimates with standard errors. Shared by the
// command line (`scatterbook slab`), the bench and the dipole-profile widget.
//
// STATISTICS. Each batch (one workgroup: 64 threads × photonsPerThread walks) is one
// sample of the tallies. A quantity is the ratio estimate Σ s_b / Σ n_b over batches b
// (s_b its sum, n_b the walks of the batch) with the standard error of a ratio of sums,
// SE² = B/(B − 1) · Σ (s_b − m·n_b)² / (Σ n_b)², which is the usual standard error of
// the batch means when every batch has the same size and stays valid when progressive
// runs append batches of another size.
import { runCompute } from '../gpu/compute.ts';
import { packStruct } from '../gpu/layout.ts';
import { slabKernel } from '../gpu/layouts.generated.ts';
import { linkLibraryKernel, type KernelLibrary } from '../gpu/link.ts';
import { rngSeed } from '../reference/rng.ts';
import {
  SLAB_EXIT_BOTTOM,
  SLAB_EXIT_CAPPED,
  SLAB_EXIT_TOP,
  SLAB_MAX_BINS,
  SLAB_MAX_COLLISIONS,
  SLAB_SEMI_INFINITE_THICKNESS,
  slabPhotonWalk,
  slabProfileBin,
  slabProfileBinEdge,
  slabSpecularReflectance,
  type SlabSetup,
} from '../reference/slab.ts';

export const SLAB_KERNEL = 'kernels/slab.wesl';
export const SLAB_WORKGROUP_SIZE = 64;
/** As SLAB_MAX_PHOTONS_PER_THREAD in the kernel. */
export const SLAB_MAX_PHOTONS_PER_THREAD = 256;
/** Words before the profile in a batch record. */
const RECORD_HEADER = 8;
/** The kernel's uniform, laid out from its WGSL declaration. */
const PARAMS = slabKernel.SlabKernelParams;
/** Largest f32, written for an infinite thickness (a half-space). */
const F32_MAX = 3.4028234663852886e38;

export interface SlabChannel {
  /** Absorption coefficient σa (1/L). */
  sigmaA: number;
  /** Scattering coefficient σs (1/L). */
  sigmaS: number;
}

export interface SlabProfileSpec {
  /** Number of radial bins (1 … 64): bin 0 is [0, rMin), the rest log-spaced up to rMax. */
  bins: number;
  rMin: number;
  rMax: number;
}

export interface SlabRun {
  /** One to four channels, each with its own coefficients (the widget's R, G, B). */
  channels: readonly SlabChannel[];
  /** HG asymmetry. */
  g: number;
  /** Thickness (L); Infinity (or ≥ 1e30) is a half-space. */
  thickness: number;
  /** Relative index n_medium/n_outside. */
  eta: number;
  /** Cosine of the incident beam with the inward normal. */
  incidenceCos: number;
  /** Walks per thread (1 … 256). */
  photonsPerThread: number;
  /** Batches (workgroups) per channel. */
  batches: number;
  /** Cap on free flights per walk (≤ 65536). */
  maxCollisions: number;
  seed: number;
  /** First thread index: a later run of the same seed continues with new streams. */
  threadOffset: number;
  profile: SlabProfileSpec;
}

/** The per-batch sums of one channel. */
export interface ChannelBatches {
  walks: number[];
  reflected: number[];
  transmitted: number[];
  unscattered: number[];
  cappedWeight: number[];
  collisions: number[];
  capped: number[];
  /** profile[b][k]: top weight of batch b in bin k. */
  profile: number[][];
}

export interface SlabBatches {
  channels: ChannelBatches[];
}

export interface Estimate {
  mean: number;
  /** Standard error from the batch spread (0 with fewer than two batches). */
  se: number;
}

export interface ProfileEstimate {
  /** Bin edges (L), bins + 1 of them: 0, rMin, …, rMax. */
  edges: number[];
  /** Geometric centre of each bin (L); half the first edge for bin 0. */
  centres: number[];
  /** Reflected weight per unit area and incident flux, R(r) in 1/L². */
  density: Estimate[];
}

export interface ChannelEstimate {
  photons: number;
  batches: number;
  /** Specular reflectance of the entry (deterministic). */
  specular: number;
  /** Diffuse reflectance R_d (weight out of the top, without the specular part). */
  diffuseReflectance: Estimate;
  /** R_d + R_sp, the benchmark convention of Giovanelli (physics.md §7 B). */
  totalReflectance: Estimate;
  /** Total transmittance T_t including the unscattered part. */
  transmittance: Estimate;
  /** The unscattered transmittance T_u. */
  unscattered: Estimate;
  /** Collisions per walk. */
  collisionsPerPhoton: number;
  /** Walks stopped by the cap, and the weight they still carried per incident photon. */
  capped: number;
  cappedWeight: number;
  profile: ProfileEstimate;
}

/** Photons per thread and batches for about `photons` walks: ~128 batches, each 64·K walks. */
export function planBatches(photons: number): { photonsPerThread: number; batches: number } {
  const n = Math.max(1, Math.round(photons));
  const photonsPerThread = Math.min(
    Math.max(Math.round(n / (SLAB_WORKGROUP_SIZE * 128)), 1),
    SLAB_MAX_PHOTONS_PER_THREAD,
  );
  return {
    photonsPerThread,
    batches: Math.max(1, Math.ceil(n / (SLAB_WORKGROUP_SIZE * photonsPerThread))),
  };
}

function binCount(run: SlabRun): number {
  return Math.min(Math.max(Math.trunc(run.profile.bins), 1), SLAB_MAX_BINS);
}

function clampedThickness(thickness: number): number {
  return thickness >= SLAB_SEMI_INFINITE_THICKNESS || !Number.isFinite(thickness)
    ? F32_MAX
    : Math.max(thickness, 0);
}

/** The kernel's uniform block for a run. */
export function packSlabParams(run: SlabRun): Uint32Array<ArrayBuffer> {
  // Up to four channels in a vec4f each; missing channels stay zero.
  const lanes = (values: number[]): number[] => [...values, 0, 0, 0, 0].slice(0, 4);
  const channels = run.channels.slice(0, 4);
  return packStruct(PARAMS, {
    sigmaA: lanes(channels.map((channel) => channel.sigmaA)),
    sigmaS: lanes(channels.map((channel) => channel.sigmaS)),
    g: run.g,
    thickness: clampedThickness(run.thickness),
    eta: run.eta,
    incidenceCos: run.incidenceCos,
    photonsPerThread: Math.min(
      Math.max(Math.trunc(run.photonsPerThread), 1),
      SLAB_MAX_PHOTONS_PER_THREAD,
    ),
    maxCollisions: Math.min(Math.max(Math.trunc(run.maxCollisions), 1), SLAB_MAX_COLLISIONS),
    seed: run.seed >>> 0,
    threadOffset: run.threadOffset >>> 0,
    bins: binCount(run),
    rMin: run.profile.rMin,
    rMax: run.profile.rMax,
  });
}

function emptyChannel(): ChannelBatches {
  return {
    walks: [],
    reflected: [],
    transmitted: [],
    unscattered: [],
    cappedWeight: [],
    collisions: [],
    capped: [],
    profile: [],
  };
}

/** Unpacks the kernel's records (layout at the top of shaders/kernels/slab.wesl). */
export function unpackRecords(run: SlabRun, output: Uint32Array): SlabBatches {
  const bins = binCount(run);
  const record = RECORD_HEADER + bins;
  const floats = new Float32Array(output.buffer, output.byteOffset, output.length);
  const channels = run.channels.slice(0, 4).map((_, c) => {
    const channel = emptyChannel();
    for (let b = 0; b < run.batches; b++) {
      const o = (c * run.batches + b) * record;
      channel.reflected.push(floats[o]!);
      channel.transmitted.push(floats[o + 1]!);
      channel.unscattered.push(floats[o + 2]!);
      channel.cappedWeight.push(floats[o + 3]!);
      channel.walks.push(output[o + 4]!);
      channel.collisions.push(output[o + 5]!);
      channel.capped.push(output[o + 6]!);
      channel.profile.push(Array.from(floats.subarray(o + RECORD_HEADER, o + record)));
    }
    return channel;
  });
  return { channels };
}

export interface GpuSlabResult {
  batches: SlabBatches;
  /** GPU time of the dispatch (timestamp queries), or null where the device has none. */
  gpuMs: number | null;
  wallMs: number;
}

/** One dispatch of the kernel on `device`, linked from `library`. */
export async function runSlabGpu(
  device: GPUDevice,
  library: KernelLibrary,
  run: SlabRun,
): Promise<GpuSlabResult> {
  const code = await linkLibraryKernel(library, SLAB_KERNEL);
  const channels = Math.min(Math.max(run.channels.length, 1), 4);
  const { output, gpuMs, wallMs } = await runCompute(device, {
    code,
    entryPoint: 'simulateSlab',
    inputs: [],
    outputWords: channels * run.batches * (RECORD_HEADER + binCount(run)),
    workgroups: [run.batches, channels],
    uniforms: packSlabParams(run),
  });
  return { batches: unpackRecords(run, output), gpuMs, wallMs };
}

/** The library's SlabSetup of channel c, with every input rounded to f32 as the GPU sees it. */
export function channelSetup(run: SlabRun, c: number): SlabSetup {
  const channel = run.channels[c]!;
  return {
    sigmaA: Math.fround(channel.sigmaA),
    sigmaS: Math.fround(channel.sigmaS),
    g: Math.fround(run.g),
    thickness: Math.fround(clampedThickness(run.thickness)),
    eta: Math.fround(run.eta),
    incidenceCos: Math.fround(run.incidenceCos),
    maxCollisions: run.maxCollisions,
  };
}

/**
 * The twin's replay of batches [first, last) of every channel: the same threads, streams
 * and walks as the kernel, in float64. Appends to `into` (one ChannelBatches per channel).
 */
export function runSlabCpuBatches(
  run: SlabRun,
  first: number,
  last: number,
  into: SlabBatches = { channels: run.channels.slice(0, 4).map(emptyChannel) },
): SlabBatches {
  const bins = binCount(run);
  const rMin = Math.fround(run.profile.rMin);
  const rMax = Math.fround(run.profile.rMax);
  const photons = Math.min(Math.max(Math.trunc(run.photonsPerThread), 1), 256);
  run.channels.slice(0, 4).forEach((_, c) => {
    const setup = channelSetup(run, c);
    const target = into.channels[c]!;
    const frame = (8 * (run.seed >>> 0) + c) >>> 0;
    for (let b = first; b < last; b++) {
      let reflected = 0;
      let transmitted = 0;
      let unscattered = 0;
      let cappedWeight = 0;
      let collisions = 0;
      let capped = 0;
      const profile = new Array<number>(bins).fill(0);
      for (let lane = 0; lane < SLAB_WORKGROUP_SIZE; lane++) {
        const state = {
          value: rngSeed((run.threadOffset + b * SLAB_WORKGROUP_SIZE + lane) >>> 0, frame),
        };
        for (let p = 0; p < photons; p++) {
          const photon = slabPhotonWalk(setup, state);
          collisions += photon.collisions;
          if (photon.exit === SLAB_EXIT_TOP) {
            reflected += photon.weight;
            const bin = slabProfileBin(photon.radius, rMin, rMax, bins);
            if (bin < bins) profile[bin]! += photon.weight;
          } else if (photon.exit === SLAB_EXIT_BOTTOM) {
            transmitted += photon.weight;
            if (photon.collisions === 0) unscattered += photon.weight;
          } else if (photon.exit === SLAB_EXIT_CAPPED) {
            cappedWeight += photon.weight;
            capped += 1;
          }
        }
      }
      target.walks.push(SLAB_WORKGROUP_SIZE * photons);
      target.reflected.push(reflected);
      target.transmitted.push(transmitted);
      target.unscattered.push(unscattered);
      target.cappedWeight.push(cappedWeight);
      target.collisions.push(collisions);
      target.capped.push(capped);
      target.profile.push(profile);
    }
  });
  return into;
}

/** All batches of a run on the CPU twin. */
export function runSlabCpu(run: SlabRun): SlabBatches {
  return runSlabCpuBatches(run, 0, run.batches);
}

/** Appends the batches of `more` (a later run of the same setup) to `into`. */
export function appendBatches(into: SlabBatches, more: SlabBatches): SlabBatches {
  more.channels.forEach((channel, c) => {
    const target = into.channels[c];
    if (!target) {
      into.channels[c] = channel;
      return;
    }
    target.walks.push(...channel.walks);
    target.reflected.push(...channel.reflected);
    target.transmitted.push(...channel.transmitted);
    target.unscattered.push(...channel.unscattered);
    target.cappedWeight.push(...channel.cappedWeight);
    target.collisions.push(...channel.collisions);
    target.capped.push(...channel.capped);
    target.profile.push(...channel.profile);
  });
  return into;
}

/** Ratio estimate Σs/Σn with the standard error of the batch spread. */
export function ratioEstimate(sums: readonly number[], walks: readonly number[]): Estimate {
  let total = 0;
  let n = 0;
  for (let b = 0; b < sums.length; b++) {
    total += sums[b]!;
    n += walks[b]!;
  }
  if (n === 0) return { mean: 0, se: 0 };
  const mean = total / n;
  const batches = sums.length;
  if (batches < 2) return { mean, se: 0 };
  let squares = 0;
  for (let b = 0; b < batches; b++) squares += (sums[b]! - mean * walks[b]!) ** 2;
  return { mean, se: Math.sqrt((batches / (batches - 1)) * squares) / n };
}

/** Bin edges of a profile: 0, rMin, …, rMax. */
export function profileEdges(profile: SlabProfileSpec): number[] {
  const bins = Math.min(Math.max(Math.trunc(profile.bins), 1), SLAB_MAX_BINS);
  return Array.from({ length: bins + 1 }, (_, k) =>
    slabProfileBinEdge(k, profile.rMin, profile.rMax, bins),
  );
}

/** Estimates with standard errors for every channel of a run's batches. */
export function summarize(run: SlabRun, batches: SlabBatches): ChannelEstimate[] {
  const edges = profileEdges(run.profile);
  const centres = edges
    .slice(0, -1)
    .map((inner, k) => (k === 0 ? edges[1]! / 2 : Math.sqrt(inner * edges[k + 1]!)));
  return batches.channels.map((channel) => {
    const photons = channel.walks.reduce((a, b) => a + b, 0);
    const specular = slabSpecularReflectance(Math.fround(run.eta), Math.fround(run.incidenceCos));
    const diffuseReflectance = ratioEstimate(channel.reflected, channel.walks);
    const density = edges.slice(0, -1).map((inner, k) => {
      const area = Math.PI * (edges[k + 1]! ** 2 - inner ** 2);
      const weight = ratioEstimate(
        channel.profile.map((bins) => bins[k] ?? 0),
        channel.walks,
      );
      return { mean: weight.mean / area, se: weight.se / area };
    });
    return {
      photons,
      batches: channel.walks.length,
      specular,
      diffuseReflectance,
      totalReflectance: { mean: diffuseReflectance.mean + specular, se: diffuseReflectance.se },
      transmittance: ratioEstimate(channel.transmitted, channel.walks),
      unscattered: ratioEstimate(channel.unscattered, channel.walks),
      collisionsPerPhoton:
        photons > 0 ? channel.collisions.reduce((a, b) => a + b, 0) / photons : 0,
      capped: channel.capped.reduce((a, b) => a + b, 0),
      cappedWeight: photons > 0 ? channel.cappedWeight.reduce((a, b) => a + b, 0) / photons : 0,
      profile: { edges, centres, density },
    };
  });
}
