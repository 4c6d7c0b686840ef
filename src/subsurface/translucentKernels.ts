// The GPU side of <sb-translucent-render> (chapter 11): the three kernels of
// shaders/kernels/translucent-{diffuse,gather,path}.wesl linked against the library and
// dispatched with runCompute, each timed (timestamp queries, else wall time). Takes the
// device and the library, so the widget (browser) and the tests (Dawn) run the same code.
import { runInBands } from '../gpu/bands.ts';
import { runCompute } from '../gpu/compute.ts';
import { linkLibraryKernel, type KernelLibrary } from '../gpu/link.ts';
import { packOctree, packParams, type Octree, type TranslucentScene } from './translucent.ts';

export interface TimedImage {
  /** RGB radiance per pixel (row 0 at the top). */
  image: Float32Array;
  milliseconds: number;
  /** 'gpu-timestamp' or 'gpu-wall'. */
  timing: string;
}

export interface GatherImage extends TimedImage {
  /** Octree nodes visited per pixel. */
  visited: Float32Array;
  /** Terms (nodes used whole or samples) summed per pixel. */
  terms: Float32Array;
}

export interface PathBatch {
  /** Per pixel: Σ L (RGB), Σ L² (RGB), walks capped; over `samples` samples. */
  sums: Float32Array;
  samples: number;
  milliseconds: number;
  timing: string;
}

/** GPU time one band of a gather may take (ms); see gather and bands.ts. */
export const GATHER_BAND_BUDGET_MS = 20;
/**
 * GPU time of a band of background accumulation that an input may interrupt (a path-traced
 * reference, a progressive picture): the input's picture waits for the bands in flight,
 * and two of GATHER_BAND_BUDGET_MS held it back 40–120 ms on SwiftShader (translucent-room,
 * bench/firstPictureProbe.ts). BatchOptions.bandBudgetMs asks for it.
 */
export const BACKGROUND_BAND_BUDGET_MS = 8;
/** Bands of a gather submitted before the first is read back (hides the read-back's latency). */
export const GATHER_BANDS_IN_FLIGHT = 2;
/** Rows of a gather's first bands, before its cost per row is known. */
const GATHER_FIRST_BAND_ROWS = 4;

const workgroups = (size: number): [number, number] => [Math.ceil(size / 8), Math.ceil(size / 8)];
const floats = (words: Uint32Array): Float32Array =>
  new Float32Array(words.buffer, words.byteOffset, words.length);

export class TranslucentKernels {
  private packedFor: Octree | null = null;
  private packed: { nodes: Uint32Array; samples: Uint32Array } | null = null;
  /** The path tracer's cost per row and sample, from its last batch. */
  private readonly pathEstimate = new BatchEstimate();

  constructor(
    private readonly device: GPUDevice,
    private readonly library: KernelLibrary,
  ) {}

  async diffuse(scene: TranslucentScene): Promise<TimedImage> {
    const code = await linkLibraryKernel(this.library, 'kernels/translucent-diffuse.wesl');
    const result = await runCompute(this.device, {
      code,
      entryPoint: 'diffuseMain',
      inputs: [],
      outputWords: 3 * scene.size * scene.size,
      workgroups: workgroups(scene.size),
      uniforms: packParams(scene, {}),
    });
    return {
      image: floats(result.output),
      milliseconds: result.gpuMs ?? result.wallMs,
      timing: result.gpuMs === null ? 'gpu-wall' : 'gpu-timestamp',
    };
  }

  /**
   * Pass 2 of Jensen & Buhler on the GPU with threshold ε (octree built on the CPU).
   * `packed` is packOctree(octree) where the caller has it already (the widget packs in
   * its worker); otherwise it is packed here, once per octree.
   *
   * The image goes in bands of rows, each about GATHER_BAND_BUDGET_MS of GPU time (sized
   * from the rows before, in this call: the cost per row depends on ε and the octree), at
   * most GATHER_BANDS_IN_FLIGHT submitted at once. The GPU runs a dispatch to its end, so
   * a whole 64² gather in one (≈ 380 ms on SwiftShader; the exact sum more) held the
   * picture of the next input behind it (issue 23). `signal`, checked before each band,
   * rejects with an AbortError. `whole`: the image in one dispatch (a small preview, where
   * each band would add a read-back round trip to the first picture).
   */
  async gather(
    scene: TranslucentScene,
    octree: Octree,
    epsilon: number,
    packed?: { nodes: Uint32Array; samples: Uint32Array },
    signal?: AbortSignal,
    whole = false,
  ): Promise<GatherImage> {
    const code = await linkLibraryKernel(this.library, 'kernels/translucent-gather.wesl');
    if (this.packedFor !== octree || !this.packed) {
      this.packed = packed ?? packOctree(octree);
      this.packedFor = octree;
    }
    const { nodes, samples } = this.packed;
    const size = scene.size;
    const pixels = size * size;
    const image = new Float32Array(3 * pixels);
    const visited = new Float32Array(pixels);
    const terms = new Float32Array(pixels);
    const { bands } = await runInBands(
      0,
      size,
      {
        budgetMs: GATHER_BAND_BUDGET_MS,
        firstRows: GATHER_FIRST_BAND_ROWS,
        inFlight: GATHER_BANDS_IN_FLIGHT,
        ...(signal ? { signal } : {}),
        ...(whole ? { fixedRows: size } : {}),
      },
      async ({ start, rows }) => {
        const result = await runCompute(this.device, {
          code,
          entryPoint: 'gatherMain',
          inputs: [nodes, samples],
          outputWords: 5 * rows * size,
          workgroups: [Math.ceil(size / 8), Math.ceil(rows / 8)],
          uniforms: packParams(scene, { count: octree.nodes.length, epsilon, offset: start }),
        });
        return { result, milliseconds: result.gpuMs ?? result.wallMs };
      },
    );
    for (const { start, rows, result } of bands) {
      const out = floats(result.output);
      for (let q = 0; q < rows * size; q++) {
        const p = start * size + q;
        image[3 * p] = out[5 * q]!;
        image[3 * p + 1] = out[5 * q + 1]!;
        image[3 * p + 2] = out[5 * q + 2]!;
        visited[p] = out[5 * q + 3]!;
        terms[p] = out[5 * q + 4]!;
      }
    }
    const milliseconds = bands.reduce((sum, band) => sum + band.milliseconds, 0);
    const wall = bands.some((band) => band.result.gpuMs === null);
    return {
      image,
      visited,
      terms,
      milliseconds,
      timing: wall ? 'gpu-wall' : 'gpu-timestamp',
    };
  }

  /**
   * `samples` path-traced samples per pixel, the first with index `offset` of stream `seed`,
   * in bands of rows (imageBatchInBands): one sample per pixel of the widget's default skin
   * is 33 ms of GPU time in Dawn on SwiftShader, more in Chrome.
   */
  async pathBatch(
    scene: TranslucentScene,
    options: BatchOptions & { ambient?: number; maxBounces?: number },
  ): Promise<PathBatch> {
    const code = await linkLibraryKernel(this.library, 'kernels/translucent-path.wesl');
    return imageBatchInBands(this.device, {
      code,
      entryPoint: 'pathMain',
      inputs: [],
      size: scene.size,
      options,
      estimate: this.pathEstimate,
      uniforms: (rowStart) =>
        packParams(scene, {
          count: options.samples,
          seed: options.seed,
          offset: options.offset,
          rowStart,
          ...(options.ambient !== undefined ? { ambient: options.ambient } : {}),
          ...(options.maxBounces !== undefined ? { maxBounces: options.maxBounces } : {}),
        }),
    });
  }
}

/** What an image batch is asked for: its samples and stream, an input, one dispatch. */
export interface BatchOptions {
  samples: number;
  offset: number;
  seed: number;
  /** Checked before each band: an aborted signal rejects with an AbortError. */
  signal?: AbortSignal;
  /** The whole image in one dispatch (a preview: bands would add a read-back each). */
  whole?: boolean;
  /**
   * GPU time a band may take (ms; default GATHER_BAND_BUDGET_MS). Background accumulation
   * that an input may interrupt asks for less: the input's picture waits for the bands in
   * flight.
   */
  bandBudgetMs?: number;
}

/** The GPU time of an image kernel's last batch, per sample: sizes the next one's bands. */
export class BatchEstimate {
  /** Mean ms per image row and sample (null: no batch timed yet). */
  msPerRowSample: number | null = null;
  /** Each row's ms per sample, from a batch cut into several bands (null: none yet). */
  rowMsPerSample: Float64Array | null = null;
}

/** Rows of an image kernel's first band when none of its batches has been timed yet. */
const FIRST_BAND_ROWS = 2;

/**
 * One image kernel with 7 words per pixel (Σ L, Σ L², capped walks; translucent-path and
 * the translucent room's path and dipole kernels) in bands of rows of about
 * GATHER_BAND_BUDGET_MS of GPU time, GATHER_BANDS_IN_FLIGHT at once, cut by each row's time
 * measured on the kernel's last batch (`estimate`). The GPU runs a dispatch to its end, and
 * one sample per pixel of these references was a 33–84 ms dispatch on SwiftShader, which an
 * input's picture waited for (issue 23). `uniforms(rowStart)` packs a band's parameters;
 * the kernel writes the band's rows only.
 */
export async function imageBatchInBands(
  device: GPUDevice,
  job: {
    code: string;
    entryPoint: string;
    inputs: Uint32Array[];
    size: number;
    options: BatchOptions;
    estimate: BatchEstimate;
    uniforms: (rowStart: number) => Uint32Array;
  },
): Promise<PathBatch> {
  const { size, options, estimate } = job;
  const { samples } = options;
  const perRow = estimate.rowMsPerSample;
  const { bands, rowMs } = await runInBands(
    0,
    size,
    {
      budgetMs: options.bandBudgetMs ?? GATHER_BAND_BUDGET_MS,
      firstRows: FIRST_BAND_ROWS,
      inFlight: GATHER_BANDS_IN_FLIGHT,
      msPerRow: estimate.msPerRowSample === null ? null : estimate.msPerRowSample * samples,
      rowMs: perRow && perRow.length === size ? perRow.map((ms) => ms * samples) : null,
      ...(options.signal ? { signal: options.signal } : {}),
      ...(options.whole ? { fixedRows: size } : {}),
    },
    async ({ start, rows }) => {
      const result = await runCompute(device, {
        code: job.code,
        entryPoint: job.entryPoint,
        inputs: job.inputs,
        outputWords: 7 * rows * size,
        workgroups: [Math.ceil(size / 8), Math.ceil(rows / 8)],
        uniforms: job.uniforms(start),
      });
      return { result, milliseconds: result.gpuMs ?? result.wallMs };
    },
  );
  // The mean over the image, not the last band's (the rows below the sphere cost nearly
  // nothing, and a next batch sized by them went in one band of 35 ms); the rows' own
  // times only from a batch cut into bands (one band says nothing of the rows apart).
  const milliseconds = bands.reduce((sum, band) => sum + band.milliseconds, 0);
  if (milliseconds > 0 && samples > 0) {
    estimate.msPerRowSample = milliseconds / size / samples;
    if (bands.length > 1) estimate.rowMsPerSample = rowMs.map((ms) => ms / samples);
  }
  const sums = new Float32Array(7 * size * size);
  for (const { start, rows, result } of bands)
    sums.set(floats(result.output).subarray(0, 7 * rows * size), 7 * start * size);
  return {
    sums,
    samples,
    milliseconds,
    timing: bands.some((band) => band.result.gpuMs === null) ? 'gpu-wall' : 'gpu-timestamp',
  };
}

/** Progressive accumulation of path-traced batches in float64, with per-pixel standard error. */
export class PathAccumulator {
  readonly sum: Float64Array;
  readonly sumSquares: Float64Array;
  samples = 0;
  capped = 0;
  milliseconds = 0;

  constructor(readonly pixels: number) {
    this.sum = new Float64Array(3 * pixels);
    this.sumSquares = new Float64Array(3 * pixels);
  }

  add(batch: PathBatch): void {
    for (let p = 0; p < this.pixels; p++) {
      for (let c = 0; c < 3; c++) {
        this.sum[3 * p + c] = this.sum[3 * p + c]! + batch.sums[7 * p + c]!;
        this.sumSquares[3 * p + c] = this.sumSquares[3 * p + c]! + batch.sums[7 * p + 3 + c]!;
      }
      this.capped += batch.sums[7 * p + 6]!;
    }
    this.samples += batch.samples;
    this.milliseconds += batch.milliseconds;
  }

  /** Mean radiance per pixel and channel. */
  mean(): Float32Array {
    const n = Math.max(this.samples, 1);
    return Float32Array.from(this.sum, (s) => s / n);
  }

  /** Standard error of the mean per pixel and channel, √((Σx²/n − x̄²)/(n − 1)). */
  standardError(): Float32Array {
    const n = this.samples;
    if (n < 2) return new Float32Array(this.sum.length).fill(NaN);
    return Float32Array.from(this.sum, (s, k) => {
      const mean = s / n;
      const variance = Math.max(0, this.sumSquares[k]! / n - mean * mean) * (n / (n - 1));
      return Math.sqrt(variance / n);
    });
  }
}
