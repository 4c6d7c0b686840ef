// The vre-ray widget's compute kernel (shaders/kernels/vre-ray.wesl), run through
// Dawn exactly as the widget dispatches it, against the widget's float64 march
// (its CPU fallback), and that march against the exact integral form of the VRE
// (chapter 4): with constant sources and albedo,
// L = (1 − α)Le(1 − T) + α L_in(1 − T) + T L_bg, T = T(0→d).
import { afterAll, describe, expect, it } from 'vitest';
import { runCompute } from '../../src/gpu/compute.ts';
import { linkLibraryKernel } from '../../src/gpu/link.ts';
import { MARCH_MIDPOINT, raymarchEmissionAbsorption } from '../../src/reference/raymarch.ts';
import { mediumOpticalDepth } from '../../src/reference/medium.ts';
import { marchRayCpu } from '../../src/widgets/vre-ray/cpuBackend.ts';
import { OUTPUT_WORDS, packParams, unpackMarch } from '../../src/widgets/vre-ray/gpuBackend.ts';
import {
  MARCH_STEPS,
  PROFILE_AMPLITUDE,
  PROFILE_FREQUENCY,
  exactRadiance,
  mediumFor,
  type VreRayInputs,
} from '../../src/widgets/vre-ray/model.ts';
import { nodeDevice, releaseNodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

afterAll(releaseNodeDevice);

async function gpuMarch(inputs: VreRayInputs): Promise<ReturnType<typeof unpackMarch>> {
  const device = await nodeDevice();
  const code = await linkLibraryKernel(SHADER_LIBRARY, 'kernels/vre-ray.wesl');
  const { output } = await runCompute(device, {
    code,
    entryPoint: 'marchRay',
    inputs: [],
    outputWords: OUTPUT_WORDS,
    workgroups: [1],
    uniforms: packParams(inputs, 960, 360),
  });
  return unpackMarch(inputs, output);
}

function ray(
  sigma: number,
  albedo: number,
  emission: number,
  inscatter: number,
  background: number,
  length: number,
): VreRayInputs {
  // Rounded to f32 as the uniform buffer rounds them, so both sides see the same medium.
  const f = Math.fround;
  return {
    sigma: f(sigma),
    albedo: f(albedo),
    emission: f(emission),
    inscatter: f(inscatter),
    background: f(background),
    length: f(length),
  };
}

const CASES: [string, VreRayInputs][] = [
  ['chapter 4 defaults', ray(1, 0.5, 0.5, 0.3, 1, 2)],
  ['preset 1, absorbing only: α = 0, L_in = 0', ray(1, 0, 0.5, 0, 1, 2)],
  ['preset 2, scattering only: α = 1, Le = 0', ray(1, 1, 0, 0.3, 1, 2)],
  ['preset 3, thick medium hides the background: σ0 = 3, d = 4', ray(3, 0.5, 0.5, 0.3, 1, 4)],
  ['preset 4, vacuum: σ0 = 0 gives L = L_bg', ray(0, 0.5, 0.5, 0.3, 1, 2)],
  ['the thickest ray: σ0 = 5, d = 5 (τ ≈ 25)', ray(5, 0.3, 2, 2, 2, 5)],
  ['the shortest ray: d = 0.1', ray(2, 0.7, 1.5, 0.2, 0.5, 0.1)],
];

/** Source per unit extinction, S = (1 − α)Le + α L_in: L = S(1 − T) + T L_bg. */
function sourceOf(inputs: VreRayInputs): number {
  return (1 - inputs.albedo) * inputs.emission + inputs.albedo * inputs.inscatter;
}

// GPU vs float64 twin. The two marches are the same sum; they differ by
// (1) WGSL sin, allowed 2^-11 absolute: each σt sample is off by ≤ 0.8·σ0·2^-11, so
//     τ̂ by δτ ≤ 0.8·σ0·d·2^-11, and every T(0→s) by the factor e^{±δτ};
// (2) f32 rounding over n = 1024 steps: per step ≤ 5 ULP (WGSL exp is 3 + 2|x| ULP
//     for the small x of a step, plus a product and a sum), so ≤ n·5·2^-24 ≈ 3e-4
//     of the largest quantity involved.
// Because the steps telescope, L̂ = S(1 − T̂) + T̂ L_bg, so (1) moves L by ≤ |S − L_bg|·T̂·(e^{δτ} − 1).
function gpuTolerance(inputs: VreRayInputs, T: number, scale: number, lever: number): number {
  const deltaTau = PROFILE_AMPLITUDE * inputs.sigma * inputs.length * 2 ** -11;
  return lever * T * Math.expm1(deltaTau) + MARCH_STEPS * 5 * 2 ** -24 * scale + 1e-30;
}

describe('vre-ray kernel vs the widget’s float64 march', () => {
  for (const [name, input] of CASES) {
    it(`${name}: every cumulative term and L within the sin + f32 budget`, async () => {
      const gpu = await gpuMarch(input);
      const cpu = marchRayCpu(input);
      const S = sourceOf(input);
      const Se = (1 - input.albedo) * input.emission;
      const Ss = input.albedo * input.inscatter;
      for (let j = 0; j <= MARCH_STEPS; j++) {
        const T = cpu.transmittance[j] ?? NaN;
        const at = `at step boundary ${j}`;
        expect(Math.abs((gpu.transmittance[j] ?? NaN) - T), `T ${at}`).toBeLessThanOrEqual(
          gpuTolerance(input, T, T, 1),
        );
        expect(
          Math.abs((gpu.emitted[j] ?? NaN) - (cpu.emitted[j] ?? NaN)),
          `emission ${at}`,
        ).toBeLessThanOrEqual(gpuTolerance(input, T, Se, Se));
        expect(
          Math.abs((gpu.inscattered[j] ?? NaN) - (cpu.inscattered[j] ?? NaN)),
          `in-scattering ${at}`,
        ).toBeLessThanOrEqual(gpuTolerance(input, T, Ss, Ss));
      }
      const T = cpu.transmittance[MARCH_STEPS] ?? NaN;
      expect(Math.abs(gpu.total - cpu.total)).toBeLessThanOrEqual(
        gpuTolerance(input, T, S + input.background, Math.abs(S - input.background)),
      );
      for (const curve of [gpu.emitted, gpu.inscattered, gpu.transmittance])
        for (const value of curve) expect(Number.isFinite(value)).toBe(true);
    });
  }
});

// Midpoint marching vs the exact identity. The march telescopes to
// L̂ = S(1 − T̂) + T̂ L_bg exactly, with τ̂ the midpoint sum of σt. For
// σt = σ0(1 + a sin ks), |σt''| ≤ σ0·a·k², so |τ̂ − τ| ≤ d·h²·σ0·a·k²/24 (the midpoint
// rule's error bound), and |L̂ − L| ≤ |S − L_bg|·max(T, T̂)·(e^{|τ̂−τ|} − 1), plus 1e-12 for
// float64 rounding of the 1024-term sums.
function midpointBound(inputs: VreRayInputs, steps: number): number {
  const h = inputs.length / steps;
  return (inputs.length * h * h * inputs.sigma * PROFILE_AMPLITUDE * PROFILE_FREQUENCY ** 2) / 24;
}

describe('the float64 march agrees with the exact integral form of the VRE', () => {
  for (const [name, input] of CASES) {
    it(`${name}: L = (1−α)Le(1−T) + αL_in(1−T) + T·L_bg within the midpoint-rule bound`, () => {
      const exact = exactRadiance(input);
      const S = sourceOf(input);
      for (const steps of [MARCH_STEPS, 8]) {
        const marched = marchRayCpu(input, steps);
        const That = marched.transmittance[steps] ?? NaN;
        const bound =
          Math.abs(S - input.background) *
            Math.max(exact.transmittance, That) *
            Math.expm1(midpointBound(input, steps)) +
          1e-12;
        expect(Math.abs(marched.total - exact.total), `${steps} steps`).toBeLessThanOrEqual(bound);
        // The cumulative parts at every boundary: (1 − α)Le·(1 − T(0→s)) and α L_in·(1 − T(0→s)).
        const medium = mediumFor(input);
        for (let j = 0; j <= steps; j += Math.max(1, steps / 64)) {
          const s = (input.length * j) / steps;
          const oneMinusT = -Math.expm1(-mediumOpticalDepth(medium, 0, s));
          const slack = Math.max(S, 1) * Math.expm1(midpointBound(input, steps)) + 1e-12;
          expect(
            Math.abs((marched.emitted[j] ?? NaN) - (1 - input.albedo) * input.emission * oneMinusT),
          ).toBeLessThanOrEqual(slack);
          expect(
            Math.abs((marched.inscattered[j] ?? NaN) - input.albedo * input.inscatter * oneMinusT),
          ).toBeLessThanOrEqual(slack);
        }
      }
    });
  }

  it('the coarse march (8 steps) is measurably off where σt varies, so the bound is not vacuous', () => {
    const input = ray(1, 0.5, 0.5, 0.3, 1, 2);
    const exact = exactRadiance(input);
    const error = Math.abs(marchRayCpu(input, 8).total - exact.total);
    // Measured: 2.0e-5, against the bound's 3.1e-3; 1024 steps bring it to ~1e-9.
    expect(error).toBeGreaterThan(1e-6);
  });

  it('equals the library’s raymarchEmissionAbsorption twin with emission S = (1−α)Le + αL_in and α = 0', () => {
    for (const [, input] of CASES) {
      const library = raymarchEmissionAbsorption(
        mediumFor(input),
        sourceOf(input),
        0,
        0,
        input.background,
        input.length,
        MARCH_STEPS,
        MARCH_MIDPOINT,
        { value: 0 },
      );
      // Same sum in float64, differently grouped: 1024 terms agree to ~1e-13.
      expect(Math.abs(library.radiance - marchRayCpu(input).total)).toBeLessThanOrEqual(1e-12);
    }
  });

  it('vacuum: σ0 = 0 leaves exactly the background, L = L_bg and T = 1', () => {
    const input = ray(0, 0.5, 0.5, 0.3, 1, 2);
    expect(exactRadiance(input).total).toBe(1);
    expect(marchRayCpu(input).total).toBe(1);
  });
});
