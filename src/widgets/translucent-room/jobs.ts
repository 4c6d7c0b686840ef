// The CPU fallback of <sb-translucent-room>, run in the compute worker (src/workers/
// compute.ts): the float64 twins of both kernels on a small picture, pass 1 (twice) and the
// dipole picture, and the path-traced reference, each timed. No DOM, no GPU.
import {
  roomDipoleCpu,
  roomIrradianceCpu,
  roomPathCpu,
  type RoomScene,
} from '../../subsurface/translucentRoom.ts';
import { IRRADIANCE, IRRADIANCE_PASSES } from './model.ts';

/** The fallback's two pictures as 7-float-per-pixel sums over `spp` samples, and their times. */
export interface CpuRoomPictures {
  reference: Float32Array;
  dipole: Float32Array;
  /** The irradiance samples of the last pass (12 floats each). */
  samples: Float32Array;
  spp: number;
  referenceMs: number;
  irradianceMs: number;
  dipoleMs: number;
}

export const jobs = {
  pictures(scene: RoomScene, spp: number, seed: number): CpuRoomPictures {
    const { samples: count, rays } = IRRADIANCE.cpu;
    const start = performance.now();
    let samples: Float32Array = new Float32Array(0);
    for (let pass = 0; pass < IRRADIANCE_PASSES; pass++)
      samples = roomIrradianceCpu(scene, count, rays, seed + 2 + pass, samples);
    const irradianceDone = performance.now();
    const dipole = roomDipoleCpu(scene, samples, { samples: spp, offset: 0, seed: seed + 1 });
    const dipoleDone = performance.now();
    const reference = roomPathCpu(scene, { samples: spp, offset: 0, seed });
    return {
      reference,
      dipole,
      samples,
      spp,
      referenceMs: performance.now() - dipoleDone,
      irradianceMs: irradianceDone - start,
      dipoleMs: dipoleDone - irradianceDone,
    };
  },
};
