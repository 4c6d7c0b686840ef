// The photon-map CPU fallback's worker job (src/widgets/photon-map/jobs.ts) against the
// float64 twin it wraps: the same photon-map image as tracing, sorting and gathering by
// hand, the path tracer's passes honoured (a fixed target, or equal time capped by
// maxSpp), and the camera view's photons with their glass flag. Run through workerJobs
// (in the page under Vitest), as the view calls it, so the arguments are cloneable.
import { describe, expect, it } from 'vitest';
import {
  DEFAULT_INPUTS,
  buildGridCpu,
  gridFor,
  pathTraceCpu,
  photonMapImageCpu,
  tracePhotonsCpu,
} from '../../src/widgets/photon-map/model.ts';
import type { jobs } from '../../src/widgets/photon-map/jobs.ts';
import { workerJobs } from '../../src/workers/compute.ts';

const inputs = { ...DEFAULT_INPUTS, photons: 2048, radius: 0.08 };
const WIDTH = 8;
const HEIGHT = 6;

describe('photon-map renderCpuImages job', () => {
  const cpuJobs = workerJobs<typeof jobs>('photon-map');

  it('renders the twin’s photon map and path-traced image', async () => {
    const result = await cpuJobs.run('renderCpuImages', [inputs, WIDTH, HEIGHT, 1, 3, 64, 100]);
    const set = tracePhotonsCpu(inputs);
    const expected = photonMapImageCpu(
      inputs,
      set,
      buildGridCpu(set, gridFor(inputs.radius)),
      WIDTH,
      HEIGHT,
      1,
      inputs.seed,
    );
    expect(Array.from(result.photonMap)).toEqual(Array.from(expected));
    expect(result.stored).toBe(set.count);
    expect(result.overflow).toBe(set.overflow);
    // Three passes of one path per pixel, streams seed + 7919·pass, averaged.
    expect(result.ptSpp).toBe(3);
    const sum = new Float64Array(WIDTH * HEIGHT);
    for (let pass = 0; pass < 3; pass++) {
      const r = pathTraceCpu(inputs, WIDTH, HEIGHT, 1, inputs.seed + 7919 * pass);
      for (let i = 0; i < sum.length; i++) sum[i]! += r.sum[i]!;
    }
    result.pathTraced.forEach((v, i) => expect(v).toBeCloseTo(sum[i]! / 3, 12));
    // The camera view: the first 100 stored photons, position and glass flag.
    expect(result.view.length).toBe(4 * Math.min(100, set.count));
    expect(result.view[0]).toBeCloseTo(set.positions[0]!, 5);
    expect(result.view[3]).toBe(set.glass[0]);
  });

  it('path traces in equal time but stops at maxSpp', async () => {
    const result = await cpuJobs.run('renderCpuImages', [inputs, WIDTH, HEIGHT, 1, null, 2, 0]);
    expect(result.ptSpp).toBeGreaterThanOrEqual(1);
    expect(result.ptSpp).toBeLessThanOrEqual(2);
    expect(result.pmMs).toBeGreaterThan(0);
    expect(result.view.length).toBe(0);
  });
});
