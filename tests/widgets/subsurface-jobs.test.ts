// The compute-worker jobs of translucent-render and dipole-profile (issue 23): the same
// numbers as the float64 functions the pages used to call, cache keys that hold only
// what each result depends on, and results whose buffers the page may take (the worker
// moves them) without spoiling the worker's own memo.
import { describe, expect, it } from 'vitest';
import {
  buildOctree,
  irradianceSamples,
  packOctree,
  renderDiffuseCpu,
  renderGatherCpu,
} from '../../src/subsurface/translucent.ts';
import {
  jobs as translucentJobs,
  sampleSceneOf,
} from '../../src/widgets/translucent-render/jobs.ts';
import {
  TRANSLUCENT_DEFAULTS,
  sceneFromValues,
} from '../../src/widgets/translucent-render/model.ts';
import { cacheKey } from '../../src/workers/compute.ts';
import {
  curveInputsOf,
  discInputsOf,
  jobs as dipoleJobs,
} from '../../src/widgets/dipole-profile/jobs.ts';
import {
  DISC_FRACTION,
  discColour,
  evaluateProfilesCpu,
  inputsFrom,
  slabRunFor,
} from '../../src/widgets/dipole-profile/model.ts';
import { DIPOLE_PROFILE } from '../../src/widgets/dipole-profile/schema.ts';
import { CPU_DISC_SIZE, monteCarloCpu } from '../../src/widgets/dipole-profile/cpuBackend.ts';
import { runSlabCpuBatches } from '../../src/subsurface/slabKernel.ts';

describe('translucent-render jobs', () => {
  const scene = { ...sceneFromValues(TRANSLUCENT_DEFAULTS), size: 12 };
  const count = 256;

  it('builds the same octree and packing as the page did', () => {
    const built = translucentJobs.octree(sampleSceneOf(scene), count);
    const expected = buildOctree(irradianceSamples(scene, count), scene.radius);
    expect(built.octree.nodes).toEqual(expected.nodes);
    expect([...built.octree.sampleOrder]).toEqual([...expected.sampleOrder]);
    expect([...built.octree.samples.irradiance]).toEqual([...expected.samples.irradiance]);
    const packed = packOctree(expected);
    expect([...built.packed.nodes]).toEqual([...packed.nodes]);
    expect([...built.packed.samples]).toEqual([...packed.samples]);
    expect(built.buildMs).toBeGreaterThanOrEqual(0);
  });

  it('keys pass 1 by the sphere and the light only', () => {
    const other = { ...scene, size: 64, sigmaA: [9, 9, 9] as const, g: 0.5 };
    expect(cacheKey('octree', [sampleSceneOf(other), count])).toBe(
      cacheKey('octree', [sampleSceneOf(scene), count]),
    );
    const moved = { ...scene, radius: scene.radius * 2 };
    expect(cacheKey('octree', [sampleSceneOf(moved), count])).not.toBe(
      cacheKey('octree', [sampleSceneOf(scene), count]),
    );
  });

  it('hands out copies: a result whose buffers were taken leaves the memo whole', () => {
    const first = translucentJobs.octree(sampleSceneOf(scene), count);
    // What postMessage's transfer does to the worker's side of a result.
    structuredClone(first, {
      transfer: [first.octree.samples.positions.buffer, first.octree.sampleOrder.buffer],
    });
    expect(first.octree.samples.positions.length).toBe(0);
    const again = translucentJobs.pictures(scene, count, 0.1);
    const expected = renderGatherCpu(
      scene,
      buildOctree(irradianceSamples(scene, count), scene.radius),
      0.1,
    );
    expect([...again.image]).toEqual([...expected.image]);
  });

  it('draws the fallback’s pictures as the twins do', () => {
    const drawn = translucentJobs.pictures(scene, count, 0.3);
    expect([...drawn.diffuse]).toEqual([...renderDiffuseCpu(scene)]);
    const octree = buildOctree(irradianceSamples(scene, count), scene.radius);
    const gather = renderGatherCpu(scene, octree, 0.3);
    expect([...drawn.image]).toEqual([...gather.image]);
    expect([...drawn.visited]).toEqual([...gather.visited]);
    expect(drawn.image.some((v) => v > 0)).toBe(true);
  });
});

describe('dipole-profile jobs', () => {
  const values = Object.fromEntries(DIPOLE_PROFILE.parameters.map((p) => [p.name, p.default]));
  const inputs = inputsFrom(values);

  it('computes the curves of the twin', () => {
    const { curves } = dipoleJobs.curves(curveInputsOf(inputs));
    const expected = evaluateProfilesCpu(inputs);
    expect(curves.dipoleTotal).toEqual(expected.dipoleTotal);
    expect([...curves.better[1]!]).toEqual([...expected.better[1]!]);
  });

  it('keys the curves by the medium only, the disc by the medium and the picture', () => {
    const brighter = { ...inputs, exposure: inputs.exposure * 4, g: 0.5, photonTarget: 1 };
    expect(cacheKey('curves', [curveInputsOf(brighter)])).toBe(
      cacheKey('curves', [curveInputsOf(inputs)]),
    );
    expect(cacheKey('disc', [discInputsOf(brighter)])).not.toBe(
      cacheKey('disc', [discInputsOf(inputs)]),
    );
  });

  it('paints the lit disc brightest at the beam and dark outside the rim', () => {
    const disc = dipoleJobs.disc(discInputsOf(inputs));
    expect(disc.size).toBe(CPU_DISC_SIZE);
    expect(disc.pixels.length).toBe(4 * CPU_DISC_SIZE * CPU_DISC_SIZE);
    const at = (x: number, y: number) => {
      const o = 4 * (y * disc.size + x);
      return disc.pixels[o]! + disc.pixels[o + 1]! + disc.pixels[o + 2]!;
    };
    const centre = at(disc.size / 2, disc.size / 2);
    const halfway = at(disc.size / 2 + disc.size / 5, disc.size / 2);
    expect(centre).toBeGreaterThan(halfway);
    expect(at(0, 0)).toBeLessThan(halfway);
  });

  it('paints each pixel the colour of its ring, as a pixel-by-pixel evaluation does', () => {
    // The disc by the definition: every pixel evaluates discColour at its ring's radius
    // (half a pixel wide) and blends the rim line; the job caches per ring as bytes.
    for (const view of [2, inputs.view]) {
      const disc = { ...discInputsOf(inputs), view };
      const drawn = dipoleJobs.disc(disc);
      const pixel = (2 * view) / CPU_DISC_SIZE;
      const rim = DISC_FRACTION * view;
      const background = [0.018, 0.02, 0.026].map((v) => Math.round(255 * v ** (1 / 2.2)));
      for (let y = 0; y < CPU_DISC_SIZE; y += 5) {
        for (let x = 0; x < CPU_DISC_SIZE; x++) {
          const px = ((x + 0.5) / CPU_DISC_SIZE - 0.5) * 2 * view;
          const py = ((y + 0.5) / CPU_DISC_SIZE - 0.5) * 2 * view;
          const r = Math.sqrt(px * px + py * py);
          let rgb =
            r <= rim
              ? discColour(disc, (Math.round((2 * r) / pixel) * pixel) / 2).map((v) =>
                  Math.round(255 * v),
                )
              : background;
          if (Math.abs(r - rim) < 0.75 * pixel)
            rgb = rgb.map((v) => Math.round(0.3 * v + 0.7 * 182));
          const o = 4 * (y * CPU_DISC_SIZE + x);
          expect([...drawn.pixels.subarray(o, o + 4)]).toEqual([...rgb, 255]);
        }
      }
    }
  });
});

describe('dipole-profile Monte Carlo in chunks', () => {
  const values = Object.fromEntries(DIPOLE_PROFILE.parameters.map((p) => [p.name, p.default]));
  const run = slabRunFor(inputsFrom(values), 8 * 64, 0);
  const chunk = (r: typeof run, first: number, last: number) =>
    Promise.resolve(dipoleJobs.slabChunk(r, first, last));

  it('adds up to the same batches as one replay of the whole run', async () => {
    expect(run.batches).toBe(8);
    const sizes: number[] = [];
    const result = await monteCarloCpu(
      run,
      (r, first, last) => {
        sizes.push(last - first);
        return chunk(r, first, last);
      },
      () => false,
    );
    expect(result.complete).toBe(true);
    expect(sizes.reduce((a, b) => a + b, 0)).toBe(run.batches);
    expect(result.batches).toEqual(runSlabCpuBatches(run, 0, run.batches));
    expect(result.milliseconds).toBeGreaterThanOrEqual(0);
  });

  it('stops at an aborted chunk with the batches done before it', async () => {
    let calls = 0;
    const result = await monteCarloCpu(
      run,
      (r, first, last) => {
        calls += 1;
        if (calls === 3) return Promise.reject(new DOMException('input', 'AbortError'));
        return chunk(r, first, last);
      },
      () => false,
    );
    expect(result.complete).toBe(false);
    const done = result.batches.channels[0]!.walks.length;
    expect(done).toBeGreaterThan(0);
    expect(done).toBeLessThan(run.batches);
    expect(result.batches).toEqual(runSlabCpuBatches(run, 0, done));
  });

  it('passes on a chunk that failed for another reason', async () => {
    await expect(
      monteCarloCpu(
        run,
        () => Promise.reject(new Error('worker crashed')),
        () => false,
      ),
    ).rejects.toThrow('worker crashed');
  });
});
