// The kernels of <sb-translucent-room> (shaders/kernels/translucent-room-{path,dipole}.wesl)
// against their float64 twins in src/subsurface/translucentRoom.ts. The twins draw from the
// same PCG streams but f32 and f64 paths part ways, so the comparison is statistical: image
// means (over pixels and samples) agree within 4.5 standard errors of the difference, the
// standard errors taken from the per-pixel sample variances both sides report.
import { describe, expect, it } from 'vitest';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';
import { findMaterial } from '../../src/subsurface/materials.ts';
import {
  indirectShare,
  roomDipoleCpu,
  roomIrradianceCpu,
  roomPathCpu,
  roomScene,
  SAMPLE_FLOATS,
} from '../../src/subsurface/translucentRoom.ts';
import { RoomKernels } from '../../src/subsurface/translucentRoomKernels.ts';
import type { BatchEstimate } from '../../src/subsurface/translucentKernels.ts';

/** Mean over pixels and channels of a 7-float-per-pixel sum buffer, and its standard error. */
function imageMean(sums: Float32Array, samples: number): { mean: number; se: number } {
  const pixels = sums.length / 7;
  let total = 0;
  let variance = 0;
  for (let p = 0; p < pixels; p++)
    for (let c = 0; c < 3; c++) {
      const m = sums[7 * p + c]! / samples;
      total += m;
      variance += Math.max(0, sums[7 * p + 3 + c]! / samples - m * m) / (samples - 1);
    }
  const n = 3 * pixels;
  // Pixels are independent streams: Var(mean of means) = Σ Var(mean_p) / n².
  return { mean: total / n, se: Math.sqrt(variance) / n };
}

const agree = (a: { mean: number; se: number }, b: { mean: number; se: number }): void => {
  const bound = 4.5 * Math.hypot(a.se, b.se);
  expect(Math.abs(a.mean - b.mean), `${a.mean} vs ${b.mean} (bound ${bound})`).toBeLessThan(bound);
};

const skin = findMaterial('skin1')!;

describe('translucent-room kernels vs their twins', () => {
  it('the path-traced reference: image means agree (skin, R = 2 mm, Cornell walls)', async () => {
    const kernels = new RoomKernels(await nodeDevice(), SHADER_LIBRARY);
    const scene = roomScene(skin, 2, 0, 8);
    const options = { samples: 48, offset: 0, seed: 3 };
    const gpu = await kernels.pathBatch(scene, options);
    const cpu = roomPathCpu(scene, options);
    const g = imageMean(gpu.sums, 48);
    agree(g, imageMean(cpu, 48));
    expect(g.mean).toBeGreaterThan(0);
    // No path reaches the caps in this scene.
    let capped = 0;
    for (let p = 0; p < 64; p++) capped += gpu.sums[7 * p + 6]!;
    expect(capped).toBe(0);
  });

  it('both image kernels in bands of rows: the same sums whatever the cut, and an input stops them', async () => {
    const device = await nodeDevice();
    const scene = roomScene(skin, 2, 0, 16);
    const options = { samples: 2, offset: 0, seed: 9 };
    const irradiance = (
      await new RoomKernels(device, SHADER_LIBRARY).irradiance(
        scene,
        64,
        16,
        5,
        new Float32Array(0),
      )
    ).samples;
    const batches = (kernels: RoomKernels) => [
      () => kernels.pathBatch(scene, options),
      () => kernels.dipoleBatch(scene, irradiance, options),
    ];
    // A fresh instance starts with bands of 2 rows and then sizes them by the budget; the
    // second call is cut by the time per row measured; a third instance in single rows.
    const fresh = new RoomKernels(device, SHADER_LIBRARY);
    const rows = new RoomKernels(device, SHADER_LIBRARY);
    const slow = (rows as unknown as { estimate: (kind: string) => BatchEstimate }).estimate.bind(
      rows,
    );
    slow('path').msPerRowSample = 1e6;
    slow(`dipole:${irradiance.length / SAMPLE_FLOATS}`).msPerRowSample = 1e6;
    for (const [k, run] of batches(fresh).entries()) {
      const first = Array.from((await run()).sums);
      expect(Array.from((await run()).sums)).toEqual(first);
      expect(Array.from((await batches(rows)[k]!()).sums)).toEqual(first);
      // Every row was traced: a band that ignored its first row leaves the lower rows empty.
      for (let row = 0; row < 16; row++) {
        let light = 0;
        for (let i = 0; i < 16; i++) light += first[7 * (row * 16 + i)]!;
        expect(light, `row ${row}`).toBeGreaterThan(0);
      }
    }
    const controller = new AbortController();
    controller.abort();
    await expect(
      fresh.pathBatch(scene, { ...options, signal: controller.signal }),
    ).rejects.toMatchObject({ name: 'AbortError' });
    await expect(
      fresh.dipoleBatch(scene, irradiance, { ...options, signal: controller.signal }),
    ).rejects.toMatchObject({ name: 'AbortError' });
  });

  it('irradiance samples and the dipole picture agree; black walls leave only direct light', async () => {
    const kernels = new RoomKernels(await nodeDevice(), SHADER_LIBRARY);
    const scene = roomScene(skin, 2, 0, 8);
    const count = 64;
    const zeros = new Float32Array(SAMPLE_FLOATS * count);
    const none = new Float32Array(0);
    const gpu = await kernels.irradiance(scene, count, 64, 5, none);
    const cpu = roomIrradianceCpu(scene, count, 64, 5, none);
    // Positions and areas are deterministic (the lattice to WGSL sin/cos, 2⁻¹¹ of R); ΣΔA E
    // agrees within its noise (a few per cent).
    let gpuPower = 0;
    let cpuPower = 0;
    for (let i = 0; i < count; i++) {
      const o = SAMPLE_FLOATS * i;
      for (let k = 0; k < 4; k++)
        expect(Math.abs(gpu.samples[o + k]! - cpu[o + k]!)).toBeLessThan(1e-3 * scene.radius);
      for (let c = 0; c < 3; c++) {
        gpuPower += gpu.samples[o + 3]! * gpu.samples[o + 4 + c]!;
        cpuPower += cpu[o + 3]! * cpu[o + 4 + c]!;
      }
    }
    expect(gpuPower).toBeGreaterThan(0);
    expect(Math.abs(gpuPower / cpuPower - 1)).toBeLessThan(0.08);
    // The indirect share is between 0 and 1, and the red channel gets more (the red wall).
    const share = indirectShare(gpu.samples);
    expect(share.all).toBeGreaterThan(0.05);
    expect(share.all).toBeLessThan(0.9);

    // A second pass fed with the first's samples follows the same paths (the gather draws no
    // random numbers) and adds the sphere's light where they meet it: E can only grow.
    const second = await kernels.irradiance(scene, count, 64, 5, gpu.samples);
    let added = 0;
    for (let i = 0; i < count; i++)
      for (let c = 0; c < 3; c++) {
        const o = SAMPLE_FLOATS * i + 4 + c;
        expect(second.samples[o]!).toBeGreaterThanOrEqual(gpu.samples[o]! * (1 - 1e-5));
        added += second.samples[o]! - gpu.samples[o]!;
      }
    expect(added).toBeGreaterThan(0);

    const black = roomScene(skin, 2, 2, 8);
    const blackPass = await kernels.irradiance(black, count, 16, 5, zeros);
    expect(indirectShare(blackPass.samples).all).toBeCloseTo(0, 6);

    const options = { samples: 24, offset: 0, seed: 9 };
    const picture = await kernels.dipoleBatch(scene, gpu.samples, options);
    const twin = roomDipoleCpu(scene, gpu.samples, options);
    agree(imageMean(picture.sums, 24), imageMean(twin, 24));
  });
});
