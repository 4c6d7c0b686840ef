// Tolerances (physics.md §10) and harness pieces for shaders/phase.wesl, shared by
// tests/shaders/phase.test.ts (published values) and tests/stability/phase.test.ts
// (hard cases and fuzz): the budgets are derived once, here, and a function that
// needs a wrapper (vector arguments, struct results) is wrapped the same way in both.
// Direction convention: the one at the top of shaders/phase.wesl.
import { hgEvalDirections, hgSample, hgSampleMu, type Vec3 } from '../../src/reference/phase.ts';
import type { ShaderFunctionTable, Tolerance } from './shaderHarness.ts';

// ---------------------------------------------------------------------------
// Tolerances (physics.md §10). The robust HG forms meet 4e-7 relative in numpy
// float32, where / and sqrt are correctly rounded. WGSL only bounds x / y to
// 2.5 ULP and sqrt through 1/inverseSqrt (2 + 2.5 ULP). hgEvalTerms then has:
// d = (1 − |g|)² + 2|g|t to ≈ 2 ULP, √d to ≈ 5.5 ULP, d·√d to ≈ 8 ULP, the
// numerator (1 − |g|)(1 + |g|)/(4π) to ≈ 2.5 ULP and the division 2.5 ULP:
// ≈ 13 ULP ≈ 1.6e-6 relative. 4e-6 leaves a margin of 2.5 over that budget
// (SwiftShader measures ≤ 3 ULP) and still catches cancellation, which costs
// ≥ 8e-4 (naive f32 at g = 0.99; 10% at g = 0.999, μ = 1).
// ---------------------------------------------------------------------------
export const HG_VALUE: Tolerance = {
  relative: 4e-6,
  reason: '§10: 4e-7 in numpy f32; WGSL / (2.5 ULP) and sqrt (4.5 ULP) give a ≈ 13-ULP budget',
};
// Sampled μ: 2.7e-7 absolute in numpy f32 (§2.4). On the GPU each complement is
// 2·r²·(1 − x)·(1 + |g|x) with r = (1 − |g|)·(1/D): ≈ 4.5 ULP in r (a 2.5-ULP
// division), ≈ 12 ULP in the product ≈ 1.4e-6 relative, and μ is taken from the
// smaller complement (≤ 1), so |δμ| ≤ 1.4e-6 + ½ ULP. The published μ(ξ) are for
// decimal ξ and g; their f32 rounding moves μ by ≤ 2e-8 (|dμ/dξ|·|Δξ| ≤ 4·6e-9).
export const SAMPLED_MU: Tolerance = {
  absolute: 2e-6,
  reason: '§2.4: 2.7e-7 in numpy f32, + WGSL 1/D (2.5 ULP) on the smaller complement',
};
// Complements 1 ∓ μ: the ≈ 12-ULP (1.4e-6) budget of SAMPLED_MU, relative; 4e-6 as for HG values.
export const SAMPLED_COMPLEMENTS: Tolerance = {
  relative: 4e-6,
  reason: '§2.4: 4e-7 in numpy f32; ≈ 12 ULP with the WGSL 2.5-ULP division',
};
// Directions: WGSL bounds sin and cos only to an absolute 2^-11 on [−π, π] (the
// azimuth stays there). After (cos φ, sin φ) is renormalised the azimuth is off by
// ≤ √2·2^-11 ≈ 6.9e-4 rad, which moves each component of a unit vector by at
// most that much (SwiftShader is at ≈ 1.9e-4). Next to μ = ±1 a direction also
// inherits √(2|δμ|) from the absolute error δμ of its cosine: ≤ 5e-4 for the
// Rayleigh sampler's 1.2e-7 at ξ = 0 (the HG complements are exact there).
export const TRIG_DIRECTION: Tolerance = {
  absolute: 1e-3,
  reason: 'WGSL sin/cos: absolute 2^-11 each ⇒ azimuth error ≤ 6.9e-4 rad',
};
// What does not depend on the azimuth (μ = −wo·wi, |wi|², z of a sphere sample):
// a few roundings of O(1) quantities, a dot product of three terms and the
// 1/(s + n.z) of the basis: ≤ 8 ULP of 1 ≈ 1e-6.
export const AZIMUTH_FREE: Tolerance = {
  absolute: 2e-6,
  reason: 'f32 rounding of O(1) terms and 2.5-ULP division, azimuth-independent',
};

// pow(x, 1/3) = exp2(log2(x)/3) in WGSL: log2 has 2^-21 absolute error on
// [0.5, 2] and 3 ULP elsewhere, exp2 3 + 2|x| ULP; for |x| ≤ 5 (the range the
// Rayleigh sampler uses) that is ≤ 8 ULP ≈ 1e-6, and for |x| up to 1e30 the
// 3-ULP log2 error of ≈ 100 grows to ≈ 1e-5 relative.
export const CBRT_SMALL: Tolerance = {
  relative: 2e-6,
  reason: 'WGSL pow = exp2(log2 x / 3): ≤ 8 ULP for |x| ≤ 5',
};
// Rayleigh μ(ξ): two cube roots of magnitude ≤ 1.7 (≤ 1e-6 relative each, see
// CBRT_SMALL) summed: ≤ 4e-6 absolute near ξ = ½ where they cancel to μ ≈ 0.
export const RAYLEIGH_SAMPLED_MU: Tolerance = {
  absolute: 4e-6,
  reason: 'two WGSL cube roots (≤ 2e-6 each) of magnitude ≤ 1.7',
};

// ---------------------------------------------------------------------------
// Arguments and wrappers
// ---------------------------------------------------------------------------
/** A harness vector argument (array<f32, 3>) as the twin's Vec3. */
export const asVec3 = (v: readonly number[]): Vec3 => [v[0] ?? 0, v[1] ?? 0, v[2] ?? 0];
/** WGSL: the vec3f of the wrapper parameter `name` (the harness passes array<f32, 3>). */
export const vec = (name: string): string => `vec3f(${name}[0], ${name}[1], ${name}[2])`;

/** (g, ξ, 1 − ξ) with 1 − ξ the complement of the f32 ξ the GPU sees. */
export const sampleArgs = (g: number, xi: number): number[] => [g, xi, 1 - Math.fround(xi)];

type TableWithoutCases = Omit<ShaderFunctionTable, 'tolerance' | 'cases'>;

/** hgSampleMu(g, ξ, 1 − ξ).mu; arguments from sampleArgs. */
export const HG_SAMPLE_MU: TableWithoutCases = {
  module: 'phase',
  fn: 'hgSampleMu',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  wrapper: {
    imports: ['hgSampleMu'],
    wgsl: 'fn caseUnderTest(g: f32, xi: f32, oneMinusXi: f32) -> f32 { return hgSampleMu(g, xi, oneMinusXi).mu; }',
  },
  twin: (g: number, xi: number, oneMinusXi: number) => hgSampleMu(g, xi, oneMinusXi).mu,
};

/** hgEvalDirections(g, wo, wi) with wo, wi as f32[3] arguments. */
export const HG_EVAL_DIRECTIONS: TableWithoutCases = {
  module: 'phase',
  fn: 'hgEvalDirections',
  args: ['f32', 'f32[3]', 'f32[3]'],
  result: 'f32',
  wrapper: {
    imports: ['hgEvalDirections'],
    wgsl: `fn caseUnderTest(g: f32, wo: array<f32, 3>, wi: array<f32, 3>) -> f32 {
  return hgEvalDirections(g, ${vec('wo')}, ${vec('wi')});
}`,
  },
  twin: (g: number, wo: readonly number[], wi: readonly number[]) =>
    hgEvalDirections(g, asVec3(wo), asVec3(wi)),
};

/**
 * A wrapper of hgSample for arguments (g, wo: f32[3], u0, u1): `body` returns a
 * `result` from the sample `s` and the direction `w` = wo.
 */
export const hgSampleWrapper = (body: string, result: string) => ({
  imports: ['hgSample'],
  wgsl: `fn caseUnderTest(g: f32, wo: array<f32, 3>, u0: f32, u1: f32) -> ${result} {
  let w = ${vec('wo')};
  let s = hgSample(g, w, vec2f(u0, u1));
  ${body}
}`,
});
/** The twin's hgSample for the same arguments as hgSampleWrapper. */
export const twinHgSample = (g: number, wo: readonly number[], u0: number, u1: number) =>
  hgSample(g, asVec3(wo), [u0, u1]);
