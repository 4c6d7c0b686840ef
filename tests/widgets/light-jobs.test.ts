// The compute-worker jobs of rayleigh-sky, hg-lobe and raymarch-steps (issue 23)
// against the float64 twins they wrap: the worker must compute the same numbers as
// the page did, and a cost it reports must be a measurement (never 0 from a clock
// step: the issue-17 defect "probes in 0.0 µs"). No timing values are asserted.
import { describe, expect, it } from 'vitest';
import { jobs as skyJobs, timeProbes } from '../../src/widgets/rayleigh-sky/jobs.ts';
import { shadeSky } from '../../src/widgets/rayleigh-sky/cpuBackend.ts';
import {
  REFERENCE_STEPS,
  computeProbes,
  inputsFrom as skyInputsFrom,
  sunTransmittance,
} from '../../src/widgets/rayleigh-sky/model.ts';
import { jobs as hgJobs } from '../../src/widgets/hg-lobe/jobs.ts';
import {
  polarPixels,
  sampleHistogramCpu,
  shadeLobe,
} from '../../src/widgets/hg-lobe/cpuBackend.ts';
import { inputsFrom as hgInputsFrom, polarLayout } from '../../src/widgets/hg-lobe/model.ts';
import { jobs as marchJobs } from '../../src/widgets/raymarch-steps/jobs.ts';
import {
  inputsFrom as marchInputsFrom,
  referenceImageCpu,
  renderImageCpu,
} from '../../src/widgets/raymarch-steps/model.ts';
import { CPU_HEIGHT, CPU_WIDTH } from '../../src/widgets/raymarch-steps/cpuBackend.ts';
import { cacheKey } from '../../src/workers/compute.ts';

const sky = skyInputsFrom({ 'sun-elevation': 20, scattering: 'on', steps: 16, exposure: 0 });

describe('rayleigh-sky jobs', () => {
  it('the panorama job is the twin of skyFragment pixel by pixel, at the stage resolution', () => {
    const { pixels, width, height } = skyJobs.panorama(sky, 40, 30);
    expect([width, height]).toEqual([40, 30]);
    expect(pixels.length).toBe(4 * 40 * 30);
    const sun = sunTransmittance(sky.sinSun, sky.sunSteps, sky.scattering);
    for (const [column, row] of [
      [0, 0],
      [17, 9],
      [39, 29],
      [20, 27],
    ] as const) {
      const rgb = shadeSky(column + 0.5, row + 0.5, 40, 30, sky, sun);
      const offset = 4 * (row * 40 + column);
      for (let c = 0; c < 3; c++) expect(pixels[offset + c]).toBe(Math.round(255 * rgb[c]!));
      expect(pixels[offset + 3]).toBe(255);
    }
  });

  it('the reference job is the converged integral and depends only on the sun and the air', () => {
    const reference = skyJobs.reference(sky.sinSun, sky.cosSun, sky.scattering);
    expect(reference).toEqual(computeProbes(sky, REFERENCE_STEPS, REFERENCE_STEPS));
    // N and the exposure are not arguments: one cache entry per sun elevation.
    expect(cacheKey('reference', [sky.sinSun, sky.cosSun, true])).toBe(
      cacheKey('reference', [
        skyInputsFrom({ 'sun-elevation': 20, scattering: 'on', steps: 64, exposure: 2 }).sinSun,
        sky.cosSun,
        true,
      ]),
    );
  });

  it('the CPU probes are timed over repeats, so their cost is never a clock step of 0', () => {
    const timed = timeProbes(sky, 1, 3);
    expect(timed.probes).toEqual(computeProbes(sky));
    // At least one evaluation per batch, and a positive mean: a batch runs until the
    // clock has moved by at least batchMs.
    expect(timed.repeats).toBeGreaterThanOrEqual(3);
    expect(timed.milliseconds).toBeGreaterThan(0);
    expect(Number.isFinite(timed.milliseconds)).toBe(true);
  });
});

describe('hg-lobe jobs', () => {
  const inputs = hgInputsFrom({
    g: 0.6,
    compare: 'isotropic',
    scale: 'linear',
    samples: 12,
    seed: 3,
  });

  it('the histogram job is the twin’s replay of the same streams, with a measured time', () => {
    const histogram = hgJobs.histogram(inputs.g, 1024, inputs.seed);
    const twin = sampleHistogramCpu(inputs.g, 1024, inputs.seed);
    expect(Array.from(histogram.bins)).toEqual(Array.from(twin.bins));
    expect(histogram.sumMu).toBe(twin.sumMu);
    expect(histogram.sampleCount).toBe(1024);
    // 1024 samples take µs: timed over repeats, never the clock's 0.
    expect(histogram.milliseconds).toBeGreaterThan(0);
  });

  it('a preview’s first 2ᵏ samples are a prefix of the full streams', () => {
    const small = hgJobs.histogram(inputs.g, 1024, inputs.seed);
    const full = hgJobs.histogram(inputs.g, 4096, inputs.seed);
    for (let k = 0; k < small.bins.length; k++)
      expect(full.bins[k]!).toBeGreaterThanOrEqual(small.bins[k]!);
  });

  it('the polar job is the twin of lobeFragment at half resolution', () => {
    const image = hgJobs.polar(inputs, 96, 48, 2);
    expect([image.width, image.height]).toEqual([48, 24]);
    const direct = polarPixels(inputs, 96, 48, 2);
    expect(Array.from(image.pixels)).toEqual(Array.from(direct.pixels));
    const layout = polarLayout(inputs, 96, 48);
    const rgb = shadeLobe(10 * 2 + 1, 7 * 2 + 1, inputs, layout, 2);
    const offset = 4 * (7 * 48 + 10);
    expect(image.pixels[offset]).toBe(Math.round(255 * rgb[0]));
  });
});

describe('raymarch-steps jobs', () => {
  const inputs = marchInputsFrom({
    steps: 8,
    placement: 'midpoint',
    update: 'exact',
    density: 1,
    seed: 0,
  });

  it('the render and reference jobs are the float64 twins at the fallback’s resolution', () => {
    const { image } = marchJobs.render(inputs, 8);
    const twin = renderImageCpu(CPU_WIDTH, CPU_HEIGHT, inputs, 8);
    expect(Array.from(image.radiance)).toEqual(Array.from(twin.radiance));
    expect(Array.from(marchJobs.reference(inputs.density))).toEqual(
      Array.from(referenceImageCpu(CPU_WIDTH, CPU_HEIGHT, inputs.density)),
    );
  });
});
