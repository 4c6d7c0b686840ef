// Benchmark of <sb-chromatic-media> (chapter 12, colour in a medium): the three estimators
// on the widget's 64×64 picture at channel spreads 1, 16 and 100 (σt,g = 2/m, α = 0.9, g = 0),
// through the widget's own kernel and statistics: GPU time, per-channel standard error,
// colour noise (SE of the chromaticity ×1000), RMS error against a one-channel reference with
// 4× the samples (independent streams), variance × time and density lookups per sample.
// Fixed frames, so every number but the times is reproducible to the digit.
import type { BenchTable } from './table.ts';
import { linkLibraryKernel } from '../src/gpu/link.ts';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import { chromaticPassGpu, CHROMATIC_KERNEL } from '../src/widgets/chromatic-media/gpuBackend.ts';
import {
  ESTIMATORS,
  ESTIMATOR_INDEX,
  GPU_SIZE,
  REFERENCE_FACTOR,
  REFERENCE_FRAME_OFFSET,
  accumulate,
  emptyAccumulation,
  estimatorStats,
  means,
  type ChromaticInputs,
} from '../src/widgets/chromatic-media/model.ts';

export async function benchChromatic(
  device: GPUDevice,
  options: { spp: number; spreads: readonly number[] },
): Promise<BenchTable> {
  const library = loadShaderLibrary(new URL('../shaders', import.meta.url).pathname);
  const code = await linkLibraryKernel(library, CHROMATIC_KERNEL);
  const { spp } = options;
  const rows: BenchTable['rows'] = [];
  let timing = '';
  for (const spread of options.spreads) {
    const inputs: ChromaticInputs = {
      spread,
      density: 2,
      albedo: 0.9,
      g: 0,
      spp,
      target: spp,
      exposure: 0,
    };
    const reference = emptyAccumulation(GPU_SIZE);
    for (let k = 0; k < REFERENCE_FACTOR; k++) {
      const pass = await chromaticPassGpu(
        device,
        code,
        inputs,
        0,
        GPU_SIZE,
        spp,
        REFERENCE_FRAME_OFFSET + k,
      );
      accumulate(reference, pass.sums, spp, pass.milliseconds);
    }
    const referenceMeans = means(reference);
    for (const name of ESTIMATORS) {
      const a = emptyAccumulation(GPU_SIZE);
      const pass = await chromaticPassGpu(
        device,
        code,
        inputs,
        ESTIMATOR_INDEX[name],
        GPU_SIZE,
        spp,
        0,
      );
      timing = pass.timing;
      accumulate(a, pass.sums, spp, pass.milliseconds);
      const s = estimatorStats(a, referenceMeans);
      rows.push({
        spread,
        estimator: name,
        'GPU ms': Number(pass.milliseconds.toFixed(1)),
        'SE r/g/b': s.channelSe.map((x) => x.toExponential(2)).join('/'),
        'colour noise': Number(s.colourNoise.toFixed(2)),
        'RMS error': s.rmsError.toExponential(2),
        'var × time': s.varianceTime.toExponential(2),
        'lookups/sample': Number(s.lookupsPerSample.toFixed(2)),
        capped: s.capped,
      });
    }
  }
  return {
    title: `Chromatic media: three estimators on the ${GPU_SIZE}² sphere, ${spp} spp`,
    notes: [
      'σt = 2·(s^-½, 1, s^½)/m for spread s, α = 0.9, g = 0, directional light, multiple scattering.',
      `Reference: one channel at a time with ${REFERENCE_FACTOR}× the samples on independent streams.`,
      `Times: ${timing}; on SwiftShader they are CPU times, compare their ratios only.`,
    ],
    rows,
  };
}
