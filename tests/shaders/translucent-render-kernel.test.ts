// The kernels of <sb-translucent-render> (shaders/kernels/translucent-*.wesl) against the
// float64 twin in src/subsurface/translucent.ts: Jensen & Buhler's pass 1 (ΣΔA = 4πR²),
// the octree gather (ε → 0 is the direct sum over all samples, on the CPU exactly and on the
// GPU to f32 rounding; the error falls as ε shrinks; GPU and twin visit the same nodes), the
// Lambertian kernel, and the path tracer's energy conservation (white furnace: a sphere that
// absorbs nothing, in an environment of radiance 1, looks exactly 1 at any η).
import { describe, expect, it } from 'vitest';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';
import {
  IMAGE_MARGIN,
  buildOctree,
  directSum,
  dipolesOf,
  gatherCpu,
  imageError,
  interiorMask,
  irradianceSamples,
  lightDirection,
  renderDiffuseCpu,
  renderGatherCpu,
  visiblePoint,
  type TranslucentScene,
} from '../../src/subsurface/translucent.ts';
import { TranslucentKernels, type BatchEstimate } from '../../src/subsurface/translucentKernels.ts';
import { findMaterial } from '../../src/subsurface/materials.ts';
import { chandrasekharH } from '../support/hFunction.ts';
import { PathAccumulator } from '../../src/subsurface/translucentKernels.ts';

const skin = findMaterial('skin1')!;
const scene = (extra: Partial<TranslucentScene> = {}): TranslucentScene => ({
  size: 16,
  radius: 5,
  view: IMAGE_MARGIN * 5,
  sigmaSPrime: skin.sigmaSPrime,
  sigmaA: skin.sigmaA,
  eta: skin.eta,
  g: 0,
  toLight: lightDirection(50),
  irradiance: 1,
  ...extra,
});

describe('irradiance samples and the octree (twin)', () => {
  it('the sample areas add up to 4πR² and the octree keeps every sample once', () => {
    const s = scene();
    const samples = irradianceSamples(s, 1000);
    expect(samples.area * samples.count).toBeCloseTo(4 * Math.PI * 25, 10);
    const octree = buildOctree(samples, s.radius);
    expect(octree.nodes[0]!.area).toBeCloseTo(4 * Math.PI * 25, 9);
    expect([...octree.sampleOrder].sort((a, b) => a - b)).toEqual([...Array(1000).keys()]);
    const lit = samples.irradiance.reduce((a, e) => a + e * samples.area, 0);
    expect(octree.nodes[0]!.power).toBeCloseTo(lit, 9);
    // The transmitted power is πR²(1 − F) averaged over the lit disc: below πR², above 0.9πR².
    expect(lit).toBeLessThan(Math.PI * 25);
    expect(lit).toBeGreaterThan(0.9 * Math.PI * 25);
  });

  it('ε = 0 gathers every sample: the direct sum exactly (float64)', () => {
    const s = scene();
    const samples = irradianceSamples(s, 2000);
    const octree = buildOctree(samples, s.radius);
    const dipoles = dipolesOf(s);
    for (const x of [
      [0, 0, 5],
      [3, 2, Math.sqrt(12)],
      [-4, 0, 3],
    ] as [number, number, number][]) {
      const gathered = gatherCpu(octree, dipoles, x, 0).exitance;
      const direct = directSum(samples, dipoles, x);
      for (let c = 0; c < 3; c++) expect(gathered[c]).toBeCloseTo(direct[c]!, 12);
    }
  });

  it('the gather error falls as ε shrinks, and so does the work saved', () => {
    const s = scene({ size: 12 });
    const octree = buildOctree(irradianceSamples(s, 4000), s.radius);
    const exact = renderGatherCpu(s, octree, 0);
    const mask = interiorMask(s);
    const rows = [1, 0.3, 0.1, 0.03, 0.01].map((epsilon) => {
      const r = renderGatherCpu(s, octree, epsilon);
      const visited = r.visited.reduce((a, v) => a + v, 0);
      return { epsilon, error: imageError(r.image, exact.image, mask).relativeRmse, visited };
    });
    for (let k = 1; k < rows.length; k++) {
      expect(rows[k]!.error).toBeLessThanOrEqual(rows[k - 1]!.error * 1.05);
      expect(rows[k]!.visited).toBeGreaterThan(rows[k - 1]!.visited);
    }
    expect(rows[0]!.error).toBeGreaterThan(3 * rows.at(-1)!.error);
    expect(rows.at(-1)!.error).toBeLessThan(0.01);
  });
});

describe('translucent kernels on the GPU (Dawn)', () => {
  it('gather: ε = 0 equals the direct sum to f32 rounding, ε = 0.2 visits the twin’s nodes', async () => {
    const kernels = new TranslucentKernels(await nodeDevice(), SHADER_LIBRARY);
    const s = scene();
    const samples = irradianceSamples(s, 1500);
    const octree = buildOctree(samples, s.radius);
    const exact = await kernels.gather(s, octree, 0);
    const twin = renderGatherCpu(s, octree, 0);
    const mask = interiorMask(s);
    expect(imageError(exact.image, twin.image, mask).relativeRmse).toBeLessThan(2e-5);
    const coarse = await kernels.gather(s, octree, 0.2);
    const coarseTwin = renderGatherCpu(s, octree, 0.2);
    let differing = 0;
    coarse.visited.forEach((v, p) => (differing += v === coarseTwin.visited[p] ? 0 : 1));
    // A node whose criterion sits within f32 rounding of ε may flip; almost none do.
    expect(differing).toBeLessThanOrEqual(2);
    expect(imageError(coarse.image, coarseTwin.image, mask).relativeRmse).toBeLessThan(1e-3);
    expect(Math.max(...coarse.visited)).toBeLessThan(Math.max(...exact.visited));
  });

  it('gather in bands: every row of the image written once, and an input stops it with an AbortError', async () => {
    const kernels = new TranslucentKernels(await nodeDevice(), SHADER_LIBRARY);
    const s = scene();
    const octree = buildOctree(irradianceSamples(s, 600), s.radius);
    // Bands are at least 4 rows apart from the first; the scene's image has more rows.
    expect(s.size).toBeGreaterThan(8);
    const gpu = await kernels.gather(s, octree, 0.1);
    const twin = renderGatherCpu(s, octree, 0.1);
    // Every pixel written by its own row's band: the visited counts match the twin's rows.
    let wrongRows = 0;
    for (let row = 0; row < s.size; row++) {
      let differing = 0;
      for (let i = 0; i < s.size; i++)
        differing += gpu.visited[row * s.size + i] === twin.visited[row * s.size + i] ? 0 : 1;
      if (differing > 1) wrongRows += 1;
    }
    expect(wrongRows).toBe(0);
    // In one dispatch (a preview's `whole`): the same image, bit for bit.
    const whole = await kernels.gather(s, octree, 0.1, undefined, undefined, true);
    expect(Array.from(whole.image)).toEqual(Array.from(gpu.image));
    expect(Array.from(whole.visited)).toEqual(Array.from(gpu.visited));
    const controller = new AbortController();
    controller.abort();
    await expect(
      kernels.gather(s, octree, 0.1, undefined, controller.signal),
    ).rejects.toMatchObject({ name: 'AbortError' });
  });

  it('path batches in bands: the same sums whatever the cut, and an input stops them with an AbortError', async () => {
    const s = scene({ size: 16 });
    // A fresh instance cuts its first batch into a first band of 2 rows and the rest by
    // the budget; the second batch is cut by the time per row the first measured.
    const kernels = new TranslucentKernels(await nodeDevice(), SHADER_LIBRARY);
    const options = { samples: 2, offset: 0, seed: 11 };
    const first = await kernels.pathBatch(s, options);
    const again = await kernels.pathBatch(s, options);
    // Bit for bit: each pixel draws its own random stream, whatever band it is in.
    expect(Array.from(again.sums)).toEqual(Array.from(first.sums));
    // Every row of the sphere was traced (a band that ignored its first row leaves zeros).
    for (let row = 2; row < 14; row++) {
      const centre = 7 * (row * s.size + s.size / 2);
      expect(
        first.sums[centre]! + first.sums[centre + 1]! + first.sums[centre + 2]!,
      ).toBeGreaterThan(0);
    }
    // A third instance cut into single rows (a huge time per row) gives the same sums.
    const rows = new TranslucentKernels(await nodeDevice(), SHADER_LIBRARY);
    (rows as unknown as { pathEstimate: BatchEstimate }).pathEstimate.msPerRowSample = 1e6;
    expect(Array.from((await rows.pathBatch(s, options)).sums)).toEqual(Array.from(first.sums));
    const controller = new AbortController();
    controller.abort();
    await expect(
      kernels.pathBatch(s, { ...options, signal: controller.signal }),
    ).rejects.toMatchObject({ name: 'AbortError' });
  });

  it('the Lambertian kernel matches its twin', async () => {
    const kernels = new TranslucentKernels(await nodeDevice(), SHADER_LIBRARY);
    const s = scene();
    const gpu = await kernels.diffuse(s);
    const cpu = renderDiffuseCpu(s);
    gpu.image.forEach((v, k) => expect(Math.abs(v - cpu[k]!)).toBeLessThan(2e-6));
  });

  it('white furnace: no absorption, ambient 1, no light: every sphere pixel is exactly 1', async () => {
    const kernels = new TranslucentKernels(await nodeDevice(), SHADER_LIBRARY);
    for (const eta of [1, 1.3]) {
      const s = scene({
        size: 8,
        radius: 1,
        view: 1.08,
        sigmaA: [0, 0, 0],
        sigmaSPrime: [2, 3, 4],
        eta,
        irradiance: 0,
      });
      const batch = await kernels.pathBatch(s, { samples: 4, offset: 0, seed: 7, ambient: 1 });
      for (let p = 0; p < 64; p++) {
        for (let c = 0; c < 3; c++) expect(batch.sums[7 * p + c]! / 4).toBeCloseTo(1, 4);
        expect(batch.sums[7 * p + 6]).toBe(0);
      }
    }
  });

  it('a sphere of 100 mean free paths seen head-on, lit head-on, reflects what Chandrasekhar’s half-space does', async () => {
    // Isotropic half-space of albedo ϖ = 0.9, matched boundary, collimated beam of unit
    // irradiance at μ0, seen at μ: L = ϖ/(4π) μ0 H(μ)H(μ0)/(μ + μ0) (Chandrasekhar 1960, §48;
    // physics.md §7 C), of which ϖ/(4π) μ0/(μ + μ0) is single scattering; the kernel's reference
    // holds the rest. Near the centre of a 100 mm sphere with σt = 1/mm, μ0 = μ = n_z ≥ 0.96.
    const kernels = new TranslucentKernels(await nodeDevice(), SHADER_LIBRARY);
    const albedo = 0.9;
    const H = chandrasekharH(albedo);
    const s = scene({
      size: 16,
      radius: 100,
      view: IMAGE_MARGIN * 100,
      sigmaSPrime: [albedo, albedo, albedo],
      sigmaA: [1 - albedo, 1 - albedo, 1 - albedo],
      eta: 1,
      toLight: [0, 0, 1],
    });
    const accumulator = new PathAccumulator(256);
    for (let offset = 0; offset < 128; offset += 64)
      accumulator.add(await kernels.pathBatch(s, { samples: 64, offset, seed: 3 }));
    const mean = accumulator.mean();
    const se = accumulator.standardError();
    let measured = 0;
    let expected = 0;
    let variance = 0;
    for (let j = 5; j < 11; j++)
      for (let i = 5; i < 11; i++) {
        const mu = visiblePoint(s, i, j)![2] / s.radius;
        expected += (3 * ((albedo / (4 * Math.PI)) * mu * (H(mu) * H(mu) - 1))) / (2 * mu);
        for (let c = 0; c < 3; c++) {
          measured += mean[3 * (j * 16 + i) + c]!;
          variance += se[3 * (j * 16 + i) + c]! ** 2;
        }
      }
    // 4 standard errors, plus 2% for the sphere's curvature and the pixel footprint.
    expect(Math.abs(measured - expected)).toBeLessThan(4 * Math.sqrt(variance) + 0.02 * expected);
    expect(Math.sqrt(variance) / expected).toBeLessThan(0.02);
  });
});
