// GPU backend of <sb-dipole-profile>: the profile curves from a compute pass of
// shaders/kernels/dipole-profile.wesl (the library's dipole module, timed with timestamp
// queries where available), the lit disc from its fragment pass, and the Monte Carlo
// from the slab kernel (shaders/kernels/slab.wesl) on the page's device.
import type { GpuContext } from '../../gpu/device.ts';
import { FullScreenPass } from '../../gpu/fullScreenPass.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import { runSlabGpu, type GpuSlabResult, type SlabRun } from '../../subsurface/slabKernel.ts';
import type { ProfileInputs } from './model.ts';
import {
  PROFILE_KERNEL,
  PROFILE_PARAMS,
  evaluateProfilesGpu,
  packParams,
  type GpuCurves,
} from './profileKernel.ts';

export class DipoleProfileGpu {
  private picture: Promise<FullScreenPass> | null = null;

  constructor(
    private readonly gpu: GpuContext,
    private readonly canvas: HTMLCanvasElement,
  ) {}

  private pass(): Promise<FullScreenPass> {
    this.picture ??= linkLibraryKernel(STATIC_KERNELS, PROFILE_KERNEL).then((code) =>
      FullScreenPass.create(this.gpu, this.canvas, {
        label: 'dipole-profile',
        code,
        vertexEntry: 'fullScreenVertex',
        fragmentEntry: 'discFragment',
        uniformBytes: PROFILE_PARAMS.size,
      }),
    );
    this.picture.catch(() => {
      this.picture = null;
    });
    return this.picture;
  }

  async curves(inputs: ProfileInputs): Promise<GpuCurves> {
    const code = await linkLibraryKernel(STATIC_KERNELS, PROFILE_KERNEL);
    return evaluateProfilesGpu(this.gpu.device, code, inputs);
  }

  async drawDisc(inputs: ProfileInputs): Promise<void> {
    const pass = await this.pass();
    await pass.draw(packParams(inputs, this.canvas.width, this.canvas.height));
  }

  monteCarlo(run: SlabRun): Promise<GpuSlabResult> {
    return runSlabGpu(this.gpu.device, STATIC_KERNELS, run);
  }
}
