// The beer-law widget's compute kernel (shaders/kernels/beer-law.wesl), run
// through Dawn exactly as the widget dispatches it, against the float64 CPU path
// of the widget (its fallback and reference).
import { afterAll, describe, expect, it } from 'vitest';
import { runCompute } from '../../src/gpu/compute.ts';
import { linkLibraryKernel } from '../../src/gpu/link.ts';
import { packParams } from '../../src/widgets/beer-law/gpuBackend.ts';
import { computeCurveCpu } from '../../src/widgets/beer-law/cpuBackend.ts';
import { CURVE_SAMPLES, type BeerLawInputs } from '../../src/widgets/beer-law/model.ts';
import type { ProfileName } from '../../src/widgets/beer-law/profiles.ts';
import { nodeDevice, releaseNodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

afterAll(releaseNodeDevice);

async function gpuCurve(inputs: BeerLawInputs): Promise<Float32Array> {
  const device = await nodeDevice();
  const code = await linkLibraryKernel(SHADER_LIBRARY, 'kernels/beer-law.wesl');
  const { output } = await runCompute(device, {
    code,
    entryPoint: 'sampleTransmittance',
    inputs: [],
    outputWords: 2 * CURVE_SAMPLES + 3,
    workgroups: [Math.ceil(CURVE_SAMPLES / 64)],
    uniforms: packParams(inputs, 960, 360),
  });
  return new Float32Array(output.buffer);
}

function inputs(
  profile: ProfileName,
  sigmaA: number,
  sigmaS: number,
  thickness: number,
  split: number,
): BeerLawInputs {
  return { profile, sigmaA, sigmaS, sigmaT: sigmaA + sigmaS, thickness, split };
}

// Tolerance: the smooth profile's τ inherits WGSL sin's 2^-11 absolute error
// (≈ 5e-4 of τ); T = e^-τ then carries δT ≈ T·δτ ≤ 5e-4·τ·T ≤ 5e-4/e·… — bounded
// here by 2e-4 absolute plus 1e-3 relative.
const CASES: [string, BeerLawInputs][] = [
  ['homogeneous, chapter 2 defaults', inputs('homogeneous', 0.2, 0.8, 2, 1)],
  ['smooth, chapter 2 worked example', inputs('smooth', 0.2, 0.8, 2, 1)],
  ['layered, across ten layers', inputs('layered', 0.2, 0.6, 6, 2.5)],
  ['optically thick: τ = 100 (subnormal exit)', inputs('smooth', 5, 5, 10, 5)],
  ['no medium: σt = 0', inputs('layered', 0, 0, 4, 1)],
  ['zero thickness', inputs('homogeneous', 1, 1, 0, 0)],
];

describe('beer-law kernel vs the widget’s float64 path', () => {
  for (const [name, input] of CASES) {
    it(name, async () => {
      const gpu = await gpuCurve(input);
      const cpu = computeCurveCpu(input);
      const n = CURVE_SAMPLES;
      for (let i = 0; i < n; i++) {
        const reference = cpu.transmittance[i] ?? NaN;
        expect(Math.abs((gpu[i] ?? NaN) - reference), `T at sample ${i}`).toBeLessThanOrEqual(
          2e-4 + 1e-3 * reference,
        );
      }
      const exit = gpu[2 * n] ?? NaN;
      expect(Math.abs(exit - cpu.exit)).toBeLessThanOrEqual(2e-4 + 1e-3 * cpu.exit);
      // Multiplicative property on the GPU: T(0→d) = T(0→s0)·T(s0→d).
      const product = (gpu[2 * n + 1] ?? NaN) * (gpu[2 * n + 2] ?? NaN);
      expect(Math.abs(product - exit)).toBeLessThanOrEqual(1e-3 * exit + 1e-30);
      for (const value of gpu) expect(Number.isFinite(value)).toBe(true);
    });
  }
});
