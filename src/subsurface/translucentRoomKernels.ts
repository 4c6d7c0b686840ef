// The GPU side of <sb-translucent-room> (chapter 12): the kernels of shaders/kernels/
// translucent-room-{path,dipole}.wesl linked against the library and dispatched with
// runCompute, each timed (timestamp queries, else wall time). Takes the device and the
// library, so the widget (browser), the tests and the bench (Dawn) run the same code.
import { runInBands } from '../gpu/bands.ts';
import { runCompute } from '../gpu/compute.ts';
import { linkLibraryKernel, type KernelLibrary } from '../gpu/link.ts';
import {
  GATHER_BAND_BUDGET_MS,
  GATHER_BANDS_IN_FLIGHT,
  type PathBatch,
} from './translucentKernels.ts';
import { packRoomParams, SAMPLE_FLOATS, type RoomScene } from './translucentRoom.ts';

export interface IrradiancePass {
  /** 12 floats per sample (translucentRoom.ts, SAMPLE_FLOATS). */
  samples: Float32Array;
  milliseconds: number;
  timing: string;
}

const floats = (words: Uint32Array): Float32Array =>
  new Float32Array(words.buffer, words.byteOffset, words.length);
const timingOf = (gpuMs: number | null): string => (gpuMs === null ? 'gpu-wall' : 'gpu-timestamp');

/** What an image batch is asked for: its samples and stream, an input, one dispatch. */
export interface BatchOptions {
  samples: number;
  offset: number;
  seed: number;
  /** Checked before each band: an aborted signal rejects with an AbortError. */
  signal?: AbortSignal;
  /** The whole image in one dispatch (a preview: bands would add a read-back each). */
  whole?: boolean;
}

/** Rows of an image kernel's first band when none of its batches has been timed yet. */
const FIRST_BAND_ROWS = 2;

export class RoomKernels {
  /**
   * GPU ms per image row and sample of each image kernel's last batch, by kernel and (for
   * the dipole picture, whose cost grows with it) irradiance sample count.
   */
  private readonly msPerRowSample = new Map<string, number>();
  /** The same per row (each row's GPU ms per sample): bands cut by the rows' own costs. */
  private readonly rowMsPerSample = new Map<string, Float64Array>();

  constructor(
    private readonly device: GPUDevice,
    private readonly library: KernelLibrary,
  ) {}

  /**
   * `samples` reference samples per pixel, the first with index `offset` of stream `seed`,
   * in bands of rows (imageInBands); `signal` stops it between bands.
   */
  async pathBatch(scene: RoomScene, options: BatchOptions): Promise<PathBatch> {
    const code = await linkLibraryKernel(this.library, 'kernels/translucent-room-path.wesl');
    return this.imageInBands('path', code, 'roomPathMain', [], scene, options, {});
  }

  /**
   * One image kernel (7 words per pixel: Σ L, Σ L², capped walks) in bands of rows of about
   * GATHER_BAND_BUDGET_MS of GPU time, two in flight, as translucent-render's path tracer:
   * one sample per pixel of the room's reference took 84 ms in one dispatch on
   * SwiftShader, and an input's picture waited for it (issue 23). The first band is sized
   * from the mean time per row and sample of the kernel's last batch.
   */
  private async imageInBands(
    kind: string,
    code: string,
    entryPoint: string,
    inputs: Uint32Array[],
    scene: RoomScene,
    options: BatchOptions,
    extra: { samples?: number },
  ): Promise<PathBatch> {
    const size = scene.size;
    const { samples } = options;
    const known = this.msPerRowSample.get(kind) ?? null;
    const perRow = this.rowMsPerSample.get(kind);
    const { bands, rowMs } = await runInBands(
      0,
      size,
      {
        budgetMs: GATHER_BAND_BUDGET_MS,
        firstRows: FIRST_BAND_ROWS,
        inFlight: GATHER_BANDS_IN_FLIGHT,
        msPerRow: known === null ? null : known * samples,
        rowMs: perRow && perRow.length === size ? perRow.map((ms) => ms * samples) : null,
        ...(options.signal ? { signal: options.signal } : {}),
        ...(options.whole ? { fixedRows: size } : {}),
      },
      async ({ start, rows }) => {
        const result = await runCompute(this.device, {
          code,
          entryPoint,
          inputs,
          outputWords: 7 * rows * size,
          workgroups: [Math.ceil(size / 8), Math.ceil(rows / 8)],
          uniforms: packRoomParams(scene, {
            count: samples,
            seed: options.seed,
            offset: options.offset,
            rowStart: start,
            ...extra,
          }),
        });
        return { result, milliseconds: result.gpuMs ?? result.wallMs };
      },
    );
    const milliseconds = bands.reduce((sum, band) => sum + band.milliseconds, 0);
    if (milliseconds > 0 && samples > 0) {
      this.msPerRowSample.set(kind, milliseconds / size / samples);
      // One band (a whole image) says nothing of the rows apart: the profile stays.
      if (bands.length > 1)
        this.rowMsPerSample.set(
          kind,
          rowMs.map((ms) => ms / samples),
        );
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

  /**
   * Pass 1: `count` irradiance samples, `rays` rays each; paths that come back to the sphere
   * see the dipole from `previous` (12 floats a sample; empty: only its mirror reflection).
   */
  async irradiance(
    scene: RoomScene,
    count: number,
    rays: number,
    seed: number,
    previous: Float32Array,
  ): Promise<IrradiancePass> {
    const code = await linkLibraryKernel(this.library, 'kernels/translucent-room-dipole.wesl');
    // A storage binding cannot be empty: one zero sample stands in, with a count of 0.
    const given = previous.length > 0 ? previous : new Float32Array(SAMPLE_FLOATS);
    const input = new Uint32Array(given.buffer.slice(0), given.byteOffset, given.length);
    const result = await runCompute(this.device, {
      code,
      entryPoint: 'irradianceMain',
      inputs: [input],
      outputWords: SAMPLE_FLOATS * count,
      workgroups: [Math.ceil(count / 64), 1],
      uniforms: packRoomParams(
        { ...scene, size: previous.length / SAMPLE_FLOATS },
        { count: rays, seed, samples: count },
      ),
    });
    return {
      samples: Float32Array.from(floats(result.output)),
      milliseconds: result.gpuMs ?? result.wallMs,
      timing: timingOf(result.gpuMs),
    };
  }

  /**
   * `samples` dipole-picture samples per pixel over the irradiance samples `irradiance`, in
   * bands of rows (imageInBands); `signal` stops it between bands.
   */
  async dipoleBatch(
    scene: RoomScene,
    irradiance: Float32Array,
    options: BatchOptions,
  ): Promise<PathBatch> {
    const code = await linkLibraryKernel(this.library, 'kernels/translucent-room-dipole.wesl');
    const input = new Uint32Array(
      irradiance.buffer.slice(0),
      irradiance.byteOffset,
      irradiance.length,
    );
    const count = irradiance.length / SAMPLE_FLOATS;
    return this.imageInBands(`dipole:${count}`, code, 'dipoleMain', [input], scene, options, {
      samples: count,
    });
  }
}
