// Runs the chromatic free-flight walks of tests/support/chromaticWalks.ts on the Dawn device.
import { linkKernel } from '../../src/gpu/link.ts';
import { runCompute } from '../../src/gpu/compute.ts';
import type { ChromaticMedium } from '../../src/reference/chromatic.ts';
import { nodeDevice } from './nodeGpu.ts';
import { SHADER_LIBRARY } from './shaderLibrary.ts';
import {
  CHROMATIC_WALK_WGSL,
  CHROMATIC_WALK_WORDS,
  packChromaticSetup,
  type ChromaticEstimator,
  type ChromaticWalk,
} from './chromaticWalks.ts';

/** `walks` walks of one setup, walk i seeded with rngSeed(i, frame). */
export async function gpuChromaticWalks(
  estimator: ChromaticEstimator,
  medium: ChromaticMedium,
  d: number,
  frame: number,
  walks: number,
  maxSteps = 65536,
): Promise<ChromaticWalk[]> {
  const device = await nodeDevice();
  const code = await linkKernel(SHADER_LIBRARY, CHROMATIC_WALK_WGSL);
  const { output } = await runCompute(device, {
    code,
    inputs: [
      packChromaticSetup({ estimator, medium, d, maxSteps }),
      new Uint32Array([walks, frame]),
    ],
    outputWords: CHROMATIC_WALK_WORDS * walks,
    workgroups: [Math.ceil(walks / 64)],
  });
  const f = new Float32Array(output.buffer);
  const result: ChromaticWalk[] = [];
  for (let i = 0; i < walks; i++) {
    const o = CHROMATIC_WALK_WORDS * i;
    result.push({
      T: [f[o]!, f[o + 1]!, f[o + 2]!],
      S: [f[o + 3]!, f[o + 4]!, f[o + 5]!],
      lookups: output[o + 6]!,
      capped: output[o + 7]!,
    });
  }
  return result;
}
