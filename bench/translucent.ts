// Benchmark of <sb-translucent-render> (chapter 11): the three methods on the widget's default
// scene (skin 1, R = 5 mm, light 60° from the view axis), each with its GPU time and its error
// against the path-traced reference (RMSE relative to the mean, and the relative error of the
// mean brightness) over the pixels wholly on the sphere; then Jensen & Buhler's gather over a
// sweep of ε: nodes visited per pixel, GPU time, error against the exact (ε = 0) gather and
// against the reference. The reference's own noise (RMS standard error) is printed with it.
import type { BenchTable } from './table.ts';
import { median } from './table.ts';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import {
  buildOctree,
  imageError,
  interiorMask,
  irradianceSamples,
  type TranslucentScene,
} from '../src/subsurface/translucent.ts';
import { PathAccumulator, TranslucentKernels } from '../src/subsurface/translucentKernels.ts';
import {
  TRANSLUCENT_DEFAULTS,
  epsilonOf,
  sceneFromValues,
} from '../src/widgets/translucent-render/model.ts';

export async function benchTranslucent(
  device: GPUDevice,
  options: { size: number; spp: number; sppPerBatch: number; repeats: number },
): Promise<BenchTable[]> {
  const library = loadShaderLibrary(new URL('../shaders', import.meta.url).pathname);
  const kernels = new TranslucentKernels(device, library);
  const scene: TranslucentScene = { ...sceneFromValues(TRANSLUCENT_DEFAULTS), size: options.size };
  const mask = interiorMask(scene);
  const count = 2 ** Number(TRANSLUCENT_DEFAULTS['samples']);
  const epsilon = epsilonOf(TRANSLUCENT_DEFAULTS);

  const buildStart = performance.now();
  const octree = buildOctree(irradianceSamples(scene, count), scene.radius);
  const buildMs = performance.now() - buildStart;

  const accumulator = new PathAccumulator(scene.size * scene.size);
  for (let offset = 0; offset < options.spp; offset += options.sppPerBatch)
    accumulator.add(
      await kernels.pathBatch(scene, { samples: options.sppPerBatch, offset, seed: 1 }),
    );
  const reference = accumulator.mean();
  const se = accumulator.standardError();
  let seSquares = 0;
  let seCount = 0;
  let referenceSum = 0;
  mask.forEach((inside, p) => {
    if (!inside) return;
    for (let c = 0; c < 3; c++) {
      seSquares += se[3 * p + c]! ** 2;
      referenceSum += reference[3 * p + c]!;
      seCount += 1;
    }
  });
  const referenceNoise = Math.sqrt(seSquares / seCount) / (referenceSum / seCount);

  const timed = async <T extends { milliseconds: number }>(
    run: () => Promise<T>,
  ): Promise<{ result: T; ms: number }> => {
    const results: T[] = [];
    for (let k = 0; k < options.repeats; k++) results.push(await run());
    return { result: results[0]!, ms: median(results.map((r) => r.milliseconds)) };
  };
  const diffuse = await timed(() => kernels.diffuse(scene));
  const gather = await timed(() => kernels.gather(scene, octree, epsilon));
  const exact = await kernels.gather(scene, octree, 0);
  const row = (
    method: string,
    image: Float32Array,
    ms: number,
    extra: Record<string, string | number> = {},
  ) => {
    const error = imageError(image, reference, mask);
    return {
      method,
      'GPU ms': ms,
      'relative RMSE': error.relativeRmse,
      'mean brightness error': error.meanError,
      ...extra,
    };
  };
  const meanVisited = (v: Float32Array): number => {
    let sum = 0;
    let n = 0;
    mask.forEach((inside, p) => {
      if (inside) {
        sum += v[p]!;
        n += 1;
      }
    });
    return sum / n;
  };
  const methods: BenchTable = {
    title: `Translucent sphere: three methods on the default scene (${scene.size}² pixels)`,
    notes: [
      `Skin 1 (Jensen et al. 2001), R = ${scene.radius} mm, η = ${scene.eta}; errors over the ${mask.reduce((a, m) => a + m, 0)} pixels wholly on the sphere, against the path tracer.`,
      `Reference: ${accumulator.samples} samples per pixel (3 walks each) in ${accumulator.milliseconds.toFixed(1)} ms of GPU time; its RMS standard error is ${(100 * referenceNoise).toFixed(2)}% of the mean, the floor of every RMSE below. Walks capped: ${accumulator.capped}.`,
      `Octree: ${count} irradiance samples, ${octree.nodes.length} nodes, built on the CPU in ${buildMs.toFixed(1)} ms (TypeScript).`,
      'The reference holds multiple scattering only (two or more events), as the dipole does; times are medians of GPU timestamps (wall time where the device has none).',
    ],
    rows: [
      row('Lambert, albedo = dipole R_d', diffuse.result.image, diffuse.ms),
      row(`Dipole BSSRDF, Jensen–Buhler gather, ε = ${epsilon}`, gather.result.image, gather.ms, {
        'nodes visited / pixel': meanVisited(gather.result.visited),
      }),
      row('Dipole BSSRDF, direct sum (ε = 0)', exact.image, exact.milliseconds, {
        'nodes visited / pixel': meanVisited(exact.visited),
      }),
      row(
        `Path tracing (reference, ${accumulator.samples} spp)`,
        reference,
        accumulator.milliseconds,
        {
          'relative RMSE': referenceNoise,
        },
      ),
    ],
  };
  const sweepRows = [];
  for (const inverse of [1, 2, 4, 8, 16, 32, 64, 128, 256]) {
    const e = 1 / inverse;
    const run = await timed(() => kernels.gather(scene, octree, e));
    sweepRows.push({
      ε: e,
      'nodes visited / pixel': meanVisited(run.result.visited),
      'GPU ms': run.ms,
      'relative RMSE vs ε = 0': imageError(run.result.image, exact.image, mask).relativeRmse,
      'relative RMSE vs reference': imageError(run.result.image, reference, mask).relativeRmse,
    });
  }
  const sweep: BenchTable = {
    title: 'Jensen–Buhler gather over ε (default scene)',
    notes: [
      'ε is the largest solid angle ΔA/‖x − p̄‖² of a node used whole; ε = 0 is the direct sum over all samples.',
      'Against the reference the error levels off at the dipole’s own model error once the gather error is below it.',
    ],
    rows: sweepRows,
  };
  return [methods, sweep];
}
