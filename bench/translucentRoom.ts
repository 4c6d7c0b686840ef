// Benchmark of <sb-translucent-room> (chapter 12): a translucent sphere in the Cornell-box-like
// room, by volumetric path tracing through its boundary (the reference) and by the dipole
// BSSRDF over irradiance samples that path tracing of the room computed. For each
// material and wall setting: the reference's GPU time and noise, the dipole's GPU time (pass 1
// and the picture) and its error against the reference over the pixels wholly on the sphere
// (relative RMSE with both images' noise subtracted, and the error of the mean), and the share
// of the sphere's transmitted power that came off the walls. Timing is printed, never asserted.
import type { BenchTable } from './table.ts';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import { findMaterial } from '../src/subsurface/materials.ts';
import { PathAccumulator } from '../src/subsurface/translucentKernels.ts';
import { indirectShare, roomScene, sphereMask } from '../src/subsurface/translucentRoom.ts';
import { RoomKernels } from '../src/subsurface/translucentRoomKernels.ts';
import { errorAgainstNoisyReference } from '../src/widgets/translucent-render/model.ts';

const WALL_NAMES = ['Cornell colours', 'white', 'black'];

export async function benchTranslucentRoom(
  device: GPUDevice,
  options: {
    size: number;
    referenceSpp: number;
    dipoleSpp: number;
    batch: number;
    samples: number;
    rays: number;
    /** Irradiance passes: 2 adds the light that leaves the sphere and comes back off a wall. */
    passes: number;
    cases: readonly { material: string; radius: number; walls: number }[];
  },
): Promise<BenchTable[]> {
  const library = loadShaderLibrary(new URL('../shaders', import.meta.url).pathname);
  const kernels = new RoomKernels(device, library);
  const rows: Record<string, string | number | null>[] = [];
  for (const c of options.cases) {
    const scene = roomScene(findMaterial(c.material)!, c.radius, c.walls, options.size);
    const mask = sphereMask(scene);
    const pixels = scene.size * scene.size;
    const reference = new PathAccumulator(pixels);
    for (let offset = 0; offset < options.referenceSpp; offset += options.batch)
      reference.add(await kernels.pathBatch(scene, { samples: options.batch, offset, seed: 1 }));
    let irradianceMs = 0;
    let samples: Float32Array = new Float32Array(0);
    for (let pass = 0; pass < options.passes; pass++) {
      const r = await kernels.irradiance(scene, options.samples, options.rays, 2 + pass, samples);
      samples = r.samples;
      irradianceMs += r.milliseconds;
    }
    const dipole = new PathAccumulator(pixels);
    for (let offset = 0; offset < options.dipoleSpp; offset += options.batch)
      dipole.add(
        await kernels.dipoleBatch(scene, samples, { samples: options.batch, offset, seed: 3 }),
      );
    const refSe = reference.standardError();
    const dipSe = dipole.standardError();
    const combined = refSe.map((s, k) => Math.hypot(s, dipSe[k]!));
    const error = errorAgainstNoisyReference(dipole.mean(), reference.mean(), combined, mask);
    const noise = errorAgainstNoisyReference(reference.mean(), reference.mean(), refSe, mask);
    rows.push({
      sphere: `${findMaterial(c.material)!.label}, R = ${c.radius} mm`,
      walls: WALL_NAMES[c.walls]!,
      'ref spp': reference.samples,
      'ref ms': Math.round(reference.milliseconds),
      'ref noise %': Number((100 * noise.referenceNoise).toFixed(2)),
      'pass 1 ms': Math.round(irradianceMs),
      'dipole ms': Math.round(dipole.milliseconds),
      'dipole rel. RMSE %': Number((100 * error.relativeRmse).toFixed(1)),
      'dipole mean err %': Number((100 * error.meanError).toFixed(1)),
      'indirect %': Number((100 * indirectShare(samples).all).toFixed(1)),
      capped: reference.capped + dipole.capped,
    });
  }
  return [
    {
      title: `translucent-room: path tracing vs dipole in the room (${options.size}² px, reference ${options.referenceSpp} spp, dipole ${options.dipoleSpp} spp, ${options.samples} irradiance samples × ${options.rays} rays × ${options.passes} pass(es))`,
      notes: [
        'errors over the pixels wholly on the sphere; the RMSE subtracts both images’ noise variance',
        'indirect %: share of the sphere’s transmitted power ΣΔA·E that did not come straight from the emitter',
      ],
      rows,
    },
  ];
}
