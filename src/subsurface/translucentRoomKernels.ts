// The GPU side of <sb-translucent-room> (chapter 12): the kernels of shaders/kernels/
// translucent-room-{path,dipole}.wesl linked against the library and dispatched with
// runCompute, each timed (timestamp queries, else wall time). Takes the device and the
// library, so the widget (browser), the tests and the bench (Dawn) run the same code.
import { runCompute } from '../gpu/compute.ts';
import { linkLibraryKernel, type KernelLibrary } from '../gpu/link.ts';
import {
  BatchEstimate,
  imageBatchInBands,
  type BatchOptions,
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

export class RoomKernels {
  /** Each image kernel's cost per row and sample (the dipole's by irradiance sample count). */
  private readonly estimates = new Map<string, BatchEstimate>();

  constructor(
    private readonly device: GPUDevice,
    private readonly library: KernelLibrary,
  ) {}

  /**
   * `samples` reference samples per pixel, the first with index `offset` of stream `seed`,
   * in bands of rows (imageBatchInBands); `signal` stops it between bands.
   */
  async pathBatch(scene: RoomScene, options: BatchOptions): Promise<PathBatch> {
    const code = await linkLibraryKernel(this.library, 'kernels/translucent-room-path.wesl');
    return imageBatchInBands(this.device, {
      code,
      entryPoint: 'roomPathMain',
      inputs: [],
      size: scene.size,
      options,
      estimate: this.estimate('path'),
      uniforms: (rowStart) =>
        packRoomParams(scene, {
          count: options.samples,
          seed: options.seed,
          offset: options.offset,
          rowStart,
        }),
    });
  }

  /** The estimate of image kernel `kind`, made on first use. */
  private estimate(kind: string): BatchEstimate {
    let estimate = this.estimates.get(kind);
    if (!estimate) {
      estimate = new BatchEstimate();
      this.estimates.set(kind, estimate);
    }
    return estimate;
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
   * bands of rows (imageBatchInBands); `signal` stops it between bands.
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
    return imageBatchInBands(this.device, {
      code,
      entryPoint: 'dipoleMain',
      inputs: [input],
      size: scene.size,
      options,
      // The dipole picture's cost grows with the irradiance samples it sums over.
      estimate: this.estimate(`dipole:${count}`),
      uniforms: (rowStart) =>
        packRoomParams(scene, {
          count: options.samples,
          seed: options.seed,
          offset: options.offset,
          samples: count,
          rowStart,
        }),
    });
  }
}
