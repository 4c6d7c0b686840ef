// WGSL scatter module vs its float64 twin (physics.md §5): shadow transmittance,
// the homogeneous-slab closed form, marched single scattering (per seed for the
// jittered schemes) and equiangular sampling; then equiangular statistics on the
// GPU (normalization of the pdf, chi-square of 2·10⁵ samples).
import { describe, expect, it } from 'vitest';
import { linkKernel } from '../../src/gpu/link.ts';
import { runCompute } from '../../src/gpu/compute.ts';
import {
  gridMedium,
  homogeneousMedium,
  type Medium1D,
  sineMedium,
} from '../../src/reference/medium.ts';
import {
  MARCH_JITTERED_RAY,
  MARCH_JITTERED_STRATA,
  MARCH_LEFT,
  MARCH_MIDPOINT,
  marchStepCount,
} from '../../src/reference/raymarch.ts';
import {
  equiangularPdf,
  equiangularSample,
  shadowTransmittanceExact,
  singleScatterHomogeneousSlab,
} from '../../src/reference/scatter.ts';
import {
  describeShaderFunction,
  type ShaderCase,
  type Tolerance,
} from '../support/shaderHarness.ts';
import {
  SIN_ERROR,
  sigmaUpperBound,
  singleScatterArgs,
  singleScatterTable,
  sinErrorInSigma,
} from '../support/marchTables.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';
import { F32_MAX, F32_MIN_NORMAL } from '../support/f32.ts';

const F32_EPSILON = 2 ** -24;
const PHASE_ISOTROPIC = 1 / (4 * Math.PI);
const EXP_TOLERANCE: Tolerance = {
  relative: 2e-5,
  absolute: F32_MIN_NORMAL,
  reason: 'WGSL exp: 3 + 2|x| ULP for |x| ≤ 100; subnormals may flush to 0',
};

describeShaderFunction({
  module: 'scatter',
  fn: 'shadowTransmittanceExact',
  args: ['f32', 'f32', 'f32', 'f32'],
  result: 'f32',
  twin: shadowTransmittanceExact,
  tolerance: EXP_TOLERANCE,
  cases: [
    { name: 'σt = 1, ℓ = 0.3 + 0.5·2: e^{−1.3}', args: [1, 0.3, 0.5, 2], expected: Math.exp(-1.3) },
    { name: 'σt = 0: no shadow', args: [0, 5, 5, 5], expected: 1 },
    { name: 'negative a and b are clamped to 0', args: [2, -1, -1, 1], expected: 1 },
    { name: 'σt = 1e6 over ℓ = 2: exactly 0', args: [1e6, 1, 1, 1], expected: 0 },
    {
      name: 'f32 max everywhere stays finite: 0',
      args: [F32_MAX, F32_MAX, F32_MAX, F32_MAX],
      expected: 0,
    },
  ],
});

describeShaderFunction({
  module: 'scatter',
  fn: 'singleScatterHomogeneousSlab',
  args: ['f32', 'f32', 'f32', 'f32', 'f32', 'f32', 'f32'],
  result: 'f32',
  twin: singleScatterHomogeneousSlab,
  // α = σs/σt (2.5 ULP), e^{−σt a} (3 + 2σt·a ULP), x·oneMinusExpOverX(x) (≤ 8 ULP),
  // three products (1.5 ULP), ÷(1 + b) (2.5 ULP): ≤ 20 ULP ≈ 1.2e-6 for σt·a ≤ 1.
  // The published values use exact inputs; f32 inputs move them by ≤ 4 ULP more.
  tolerance: {
    relative: 2e-6,
    absolute: F32_MIN_NORMAL,
    reason: '≤ 20 ULP of f32 operations + f32-rounded inputs',
  },
  cases: [
    {
      name: '§5 example σs = 0.8, σa = 0.2, p = 1/(4π), E = 1, a = 0.3, b = 0.5, L = 2',
      args: [0.8, 0.2, PHASE_ISOTROPIC, 1, 0.3, 0.5, 2],
      expected: 0.02987593155873194,
    },
    {
      name: '§5 example with b = 0',
      args: [0.8, 0.2, PHASE_ISOTROPIC, 1, 0.3, 0, 2],
      expected: 0.04077927647475037,
    },
    {
      name: '§9 row 18 thin slab: σt(1 + b)L = 1e-9 gives σs·p·E·L = 5e-10 (naive f32: 0)',
      args: [5e-10, 5e-10, 1, 1, 0, 0, 1],
      expected: 5e-10,
    },
    {
      name: 'thin slab, x = 1e-7 (naive f32: −40%)',
      args: [5e-8, 5e-8, 1, 1, 0, 0, 1],
      expected: 5e-8,
    },
    { name: 'no medium: 0', args: [0, 0, 1, 1, 0, 0, 1], expected: 0 },
    { name: 'absorbing only: 0', args: [0, 2, 1, 1, 0, 0, 1], expected: 0 },
    {
      name: 'infinitely thick: α·p·E·e^{−σt a}/(1 + b)',
      args: [0.6, 0.4, PHASE_ISOTROPIC, 2, 0.1, 1, 1e6],
      expected: (0.6 * PHASE_ISOTROPIC * 2 * Math.exp(-0.1)) / 2,
    },
    { name: 'σt = 1e6 with a = 1: exactly 0', args: [5e5, 5e5, 1, 1, 1, 0.5, 1], expected: 0 },
    { name: 'b = 1e30 (grazing light): finite', args: [1, 0, 1, 1, 0, 1e30, 1] },
    {
      name: 'f32 max everywhere: finite',
      args: [F32_MAX, F32_MAX, F32_MAX, F32_MAX, 0, F32_MAX, F32_MAX],
    },
  ],
});

// ---- marched single scattering ----

interface ScatterCase {
  name: string;
  medium: Medium1D;
  albedo: number;
  phase: number;
  irradiance: number;
  a: number;
  b: number;
  length: number;
  steps: number;
  scheme: number;
  seed: number;
  expected?: readonly number[];
}

/**
 * Per step: exp (3 + 2x ULP) twice, x·oneMinusExpOverX (≤ 8 ULP), four products:
 * (4n + 2τ + 2τ_shadow + 16)·2^-24 relative. The sinusoidal medium adds WGSL sin's
 * 2^-11 in σt (δσ = σ0·a·2^-11), which moves L by at most δσ·(L + shadow path)·p·E·α
 * per unit: bounded here by 4·δσ·max(L, 1)·(1 + a + b·L)·p·E.
 */
function scatterTolerance(c: ScatterCase): Tolerance {
  const n = marchStepCount(c.steps);
  const shadowPath = c.a + c.b * c.length;
  const tau = Math.min(sigmaUpperBound(c.medium) * (c.length + shadowPath), 400);
  const deltaSigma = sinErrorInSigma(c.medium);
  return {
    relative: (4 * n + 2 * tau + 16) * F32_EPSILON,
    absolute: Math.max(
      4 * deltaSigma * Math.max(c.length, 1) * (1 + shadowPath) * c.phase * c.irradiance,
      F32_MIN_NORMAL,
    ),
    reason: `f32 march with shadow exp: (4n + 2τ + 16)·2^-24${deltaSigma > 0 ? '; WGSL sin 2^-11 in σt' : ''}`,
  };
}

const example = (
  name: string,
  steps: number,
  scheme: number,
  seed = 0,
  expected?: readonly number[],
): ScatterCase => ({
  name,
  medium: homogeneousMedium(1),
  albedo: 0.8,
  phase: PHASE_ISOTROPIC,
  irradiance: 1,
  a: 0.3,
  b: 0.5,
  length: 2,
  steps,
  scheme,
  seed,
  ...(expected ? { expected } : {}),
});

const SCATTER_CASES: ScatterCase[] = [
  example('§5 example, midpoint N = 8', 8, MARCH_MIDPOINT),
  example('§5 example, left N = 8', 8, MARCH_LEFT),
  example(
    '§5 example, midpoint N = 4096: the closed form 0.029875931558',
    4096,
    MARCH_MIDPOINT,
    0,
    [0.02987593155873194, Math.exp(-2), 4096, 0],
  ),
  example('§5 example, jittered ray N = 16, seed 31', 16, MARCH_JITTERED_RAY, 31),
  example('§5 example, jittered strata N = 16, seed 32', 16, MARCH_JITTERED_STRATA, 32),
  {
    ...example('§3 sinusoidal medium, midpoint N = 64', 64, MARCH_MIDPOINT),
    medium: sineMedium(1, 0.5, 3),
  },
  {
    ...example('layered grid, midpoint N = 8', 8, MARCH_MIDPOINT),
    medium: gridMedium([0.5, 2, 1, 0.1], 0.5),
  },
  {
    ...example('albedo 0 scatters nothing', 8, MARCH_MIDPOINT, 0, [0, Math.exp(-2), 8, 0]),
    albedo: 0,
  },
  {
    ...example(
      'σt = 1e6: the first step takes everything, the shadow is 0',
      64,
      MARCH_MIDPOINT,
      0,
      [0, 0, 64, 0],
    ),
    medium: homogeneousMedium(1e6),
  },
  {
    ...example('thin σt = 1e-7: L = α·σt·p·E·L_view = 8e-8·2/(4π)', 16, MARCH_MIDPOINT, 0, [
      (0.8 * 1e-7 * 2) / (4 * Math.PI),
      1,
      16,
      0,
    ]),
    medium: homogeneousMedium(1e-7),
  },
  example('steps beyond the cap are reported as 4096', 9000, MARCH_LEFT),
];

describeShaderFunction(
  singleScatterTable(
    SCATTER_CASES.map((c): ShaderCase => ({
      name: c.name,
      args: singleScatterArgs(
        c.medium,
        c.albedo,
        c.phase,
        c.irradiance,
        c.a,
        c.b,
        c.length,
        c.steps,
        c.scheme,
        c.seed,
      ),
      ...(c.expected ? { expected: c.expected } : {}),
      tolerance: scatterTolerance(c),
    })),
    { relative: 1e-5, reason: 'overridden per case' },
  ),
);

// ---- equiangular sampling ----

/**
 * WGSL tan inherits sin/cos's 2^-11 absolute error: |δ tan θ| ≤ 2^-11(1 + |tan θ|)/|cos θ|,
 * so t = h·tan θ is off by h·that, and the pdf h/(Δθ(h² + t²)) by 2|t|·δt/(h² + t²)
 * relatively (+ ≈ 10 ULP of its own operations).
 */
function equiangularTolerance(h: number, thetaA: number, thetaB: number, xi: number): Tolerance {
  const theta = thetaA + xi * (thetaB - thetaA);
  const deltaTan = (SIN_ERROR * (1 + Math.abs(Math.tan(theta)))) / Math.abs(Math.cos(theta));
  const t = h * Math.tan(theta);
  const deltaT = h * deltaTan;
  const pdfRelative = (2 * Math.abs(t) * deltaT) / (h * h + t * t) + 1e-6;
  return {
    relative: Math.max(pdfRelative, deltaT / Math.max(Math.abs(t), 1e-30)),
    absolute: deltaT,
    reason: 'WGSL tan = sin/cos with 2^-11 absolute errors, propagated to t and the pdf',
  };
}

const H = 0.7;
const THETA_A = Math.atan(-1.2 / H);
const THETA_B = Math.atan(3 / H);

describeShaderFunction({
  module: 'scatter',
  fn: 'equiangularSample',
  args: ['f32', 'f32', 'f32', 'f32'],
  result: 'vec2f',
  twin: equiangularSample,
  tolerance: { relative: 1e-6, reason: 'overridden per case' },
  cases: [
    ...[0, 0.1, 0.25, 0.5, 0.75, 0.9, 1].map((xi) => ({
      name: `segment [−1.2, 3] at h = 0.7, ξ = ${xi}`,
      args: [H, THETA_A, THETA_B, xi],
      tolerance: equiangularTolerance(H, THETA_A, THETA_B, xi),
    })),
    {
      name: 'ξ = 0 gives the segment start t = −1.2',
      args: [H, THETA_A, THETA_B, 0],
      expected: [-1.2, H / ((THETA_B - THETA_A) * (H * H + 1.44))],
      tolerance: equiangularTolerance(H, THETA_A, THETA_B, 0),
    },
    {
      name: 'far light h = 100, short segment',
      args: [100, Math.atan(-0.5 / 100), Math.atan(0.5 / 100), 0.3],
      tolerance: equiangularTolerance(100, Math.atan(-0.5 / 100), Math.atan(0.5 / 100), 0.3),
    },
    {
      name: 'h = 0 (light on the ray): pdf 0, t = 0',
      args: [0, -1, 1, 0.5],
      expected: [0, 0],
      tolerance: { absolute: 0, reason: 'exact: degenerate branch' },
    },
    {
      name: 'θb = θa (empty segment): pdf 0',
      args: [1, 0.3, 0.3, 0.5],
      tolerance: { relative: 2e-3, absolute: 0, reason: 'WGSL tan at 0.3; pdf exactly 0' },
    },
  ],
});

describeShaderFunction({
  module: 'scatter',
  fn: 'equiangularPdf',
  args: ['f32', 'f32', 'f32', 'f32'],
  result: 'f32',
  twin: equiangularPdf,
  // Three divisions (2.5 ULP each), three products, one sum: ≤ 12 ULP.
  tolerance: {
    relative: 1e-6,
    absolute: F32_MIN_NORMAL,
    reason: '≤ 12 ULP of divisions and products',
  },
  cases: [
    {
      name: 'closest point t = 0: 1/(h·Δθ)',
      args: [H, THETA_A, THETA_B, 0],
      expected: 1 / (H * (THETA_B - THETA_A)),
    },
    { name: 't = 3 (segment end)', args: [H, THETA_A, THETA_B, 3] },
    {
      name: 't = 1e30: h² + t² would overflow f32; the scaled form stays finite',
      args: [1, -1.5, 1.5, 1e30],
    },
    { name: 'h = 1e-20, t = 1: tiny h', args: [1e-20, -1.5, 1.5, 1] },
    { name: 'h = 0: pdf 0', args: [0, -1, 1, 0.5], expected: 0 },
    { name: 'θb = θa: pdf 0', args: [1, 0.3, 0.3, 0.3], expected: 0 },
    { name: 'θb < θa: pdf 0, never negative', args: [1, 0.5, 0.3, 0.3], expected: 0 },
    { name: 'f32 max everywhere: finite', args: [F32_MAX, -F32_MAX, F32_MAX, F32_MAX] },
  ],
});

describe('equiangular sampling statistics on the GPU (Kulla & Fajardo 2012)', () => {
  const samples = 200_000;

  async function gpu(body: string, count: number): Promise<Float32Array> {
    const device = await nodeDevice();
    const code = await linkKernel(
      SHADER_LIBRARY,
      `import package::scatter::{equiangularPdf, equiangularSample};
import package::rng::{rngNextFloat, rngSeed};
@group(0) @binding(0) var<storage, read_write> outputs: array<f32>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= ${count}u) { return; }
${body}
}`,
    );
    const { output } = await runCompute(device, {
      code,
      inputs: [],
      outputWords: 2 * count,
      workgroups: [Math.ceil(count / 64)],
    });
    return new Float32Array(output.buffer);
  }

  it('the GPU pdf integrates to 1 over the segment (Simpson on 4001 GPU values, 1e-5)', async () => {
    const intervals = 4000;
    const step = 4.2 / intervals;
    const values = await gpu(
      `  let t = -1.2 + f32(i) * ${step};
  outputs[i] = equiangularPdf(${H}, ${Math.fround(THETA_A)}, ${Math.fround(THETA_B)}, t);`,
      intervals + 1,
    );
    let sum = (values[0] ?? NaN) + (values[intervals] ?? NaN);
    for (let i = 1; i < intervals; i++) sum += (i % 2 ? 4 : 2) * (values[i] ?? NaN);
    // Simpson's error is < 1e-9 here; the f32 pdf values carry ≤ 1e-6.
    expect(Math.abs((sum * step) / 3 - 1)).toBeLessThan(1e-5);
  });

  it('GPU samples follow the pdf: chi-square over 40 equiprobable bins, 2·10⁵ samples, α = 0.01; returned pdf = equiangularPdf(t)', async () => {
    const values = await gpu(
      `  var state = rngSeed(i, 17u);
  let sample = equiangularSample(${H}, ${Math.fround(THETA_A)}, ${Math.fround(THETA_B)}, rngNextFloat(&state));
  outputs[2u * i] = sample.x;
  outputs[2u * i + 1u] = sample.y - equiangularPdf(${H}, ${Math.fround(THETA_A)}, ${Math.fround(THETA_B)}, sample.x);`,
      samples,
    );
    const bins = 40;
    const counts = new Array<number>(bins).fill(0);
    const thetaA = Math.fround(THETA_A);
    const thetaB = Math.fround(THETA_B);
    const h = Math.fround(H);
    for (let i = 0; i < samples; i++) {
      const t = values[2 * i] ?? NaN;
      expect(values[2 * i + 1]).toBe(0);
      // CDF of the equiangular density: (atan(t/h) − θa)/(θb − θa).
      const cdf = (Math.atan2(t, h) - thetaA) / (thetaB - thetaA);
      const bin = Math.min(bins - 1, Math.max(0, Math.floor(cdf * bins)));
      counts[bin] = (counts[bin] ?? 0) + 1;
    }
    const expected = samples / bins;
    const chiSquare = counts.reduce((sum, c) => sum + (c - expected) ** 2 / expected, 0);
    // Upper 1% point of chi-square with 39 degrees of freedom (one test in this file).
    expect(chiSquare).toBeLessThan(62.428);
  });
});
