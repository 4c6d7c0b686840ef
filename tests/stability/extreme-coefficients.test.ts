// Hard cases of issue 20 ("clamp the product, not each factor"), in both implementations
// through the table harness: every input is rounded to f32, the WGSL function runs on Dawn,
// the float64 twin on the same inputs, and both must meet the stated expected value.
//
// The same medium in other units must give the same transmittance, albedo and reflectance:
// σ = 1e19 /m with d = 1e-19 m is σ = 1 /m with d = 1 m. Before the fix each factor was
// clamped on its own (σ and d to 1e18, σs' and σa to 1e9), so these gave e^{-0.1} for e^{-1},
// 1 for 0, 10 for 3.4e21, α' = 0.9091 for 0.9901; and the fuzzing of the issue found NaN or
// Inf in dipoleSourceTerm, sampleUniformSphere and truncatedExponentialPdf, and a negative
// distance from sampleTruncatedExponential.
import { describeShaderFunction } from '../support/shaderHarness.ts';
import {
  betterDipoleParameters,
  betterDipoleTotalReflectance,
  burleyProfile,
  burleyRadialCdf,
  dipoleParameters,
  dipoleProfile,
  dipoleSourceTerm,
  dipoleTotalReflectance,
} from '../../src/reference/dipole.ts';
import {
  sampleTruncatedExponential,
  transmittanceBeer,
  truncatedExponentialPdf,
} from '../../src/reference/integrator.ts';
import {
  homogeneousMedium,
  mediumExtinction,
  mediumMajorant,
  sineMedium,
} from '../../src/reference/medium.ts';
import { sampleUniformSphere } from '../../src/reference/directions.ts';
import {
  shadowTransmittanceExact,
  singleScatterHomogeneousSlab,
} from '../../src/reference/scatter.ts';
import { transmittanceResidualRatioTracking } from '../../src/reference/tracking.ts';
import {
  opticalThicknessHomogeneous,
  opticalThicknessSine,
  transmittanceHomogeneous,
} from '../../src/reference/transmittance.ts';
import { F32_MAX, F32_MIN_NORMAL } from '../support/f32.ts';

const E_MINUS_1 = 0.36787944117144233;
/** 1 − e^{-1}: single scattering of a slab of optical thickness 1, α = 1, p·E = 1, b = 0. */
const ONE_MINUS_E_MINUS_1 = 0.6321205588285577;

/**
 * f32 rounding of σ and d (each ≤ 2^-24 relative) moves τ ≈ 1 by ≤ 1.2e-7, and WGSL's exp
 * adds 3 + 2|x| ULP: 2e-6 relative. Values that are 0 must be exactly 0 or below the normal range.
 */
const EXP = {
  relative: 2e-6,
  absolute: F32_MIN_NORMAL,
  reason: 'f32-rounded σ and d (2^-24 each) and WGSL exp (3 + 2|x| ULP)',
};

describeShaderFunction({
  module: 'transmittance',
  fn: 'transmittanceHomogeneous',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: transmittanceHomogeneous,
  tolerance: EXP,
  cases: [
    {
      name: 'issue 20: σt = 1e19, d = 1e-19 → e^-1 (was e^-0.1 = 0.9048)',
      args: [1e19, 1e-19],
      expected: E_MINUS_1,
    },
    { name: 'issue 20: σt = 1e-30, d = 3e38 → 0 (was 1)', args: [1e-30, 3e38], expected: 0 },
    { name: 'σt = 1e30, d = 1e-30 → e^-1', args: [1e30, 1e-30], expected: E_MINUS_1 },
    { name: 'σt = 1e-30, d = 1e30 → e^-1', args: [1e-30, 1e30], expected: E_MINUS_1 },
    { name: 'σt = 1e-37, d = 1e37 → e^-1', args: [1e-37, 1e37], expected: E_MINUS_1 },
  ],
});

describeShaderFunction({
  module: 'transmittance',
  fn: 'opticalThicknessHomogeneous',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: opticalThicknessHomogeneous,
  tolerance: { relative: 3e-7, reason: 'one f32 product of f32-rounded inputs (2^-24 each)' },
  cases: [
    {
      name: 'issue 20: σt = 1e-17, d = FLT_MAX → 3.4e21 (was 10)',
      args: [1e-17, F32_MAX],
      expected: 1e-17 * F32_MAX,
    },
    { name: 'σt = 1e19, d = 1e-19 → 1 (was 0.1)', args: [1e19, 1e-19], expected: 1 },
    {
      name: 'FLT_MAX · FLT_MAX saturates at FLT_MAX, never Inf',
      args: [F32_MAX, F32_MAX],
      expected: F32_MAX,
    },
    { name: 'FLT_MAX · 2 saturates at FLT_MAX', args: [F32_MAX, 2], expected: F32_MAX },
    { name: 'FLT_MAX · 0 = 0', args: [F32_MAX, 0], expected: 0 },
  ],
});

describeShaderFunction({
  module: 'transmittance',
  fn: 'opticalThicknessSine',
  args: ['f32', 'f32', 'f32', 'f32', 'f32', 'f32'],
  result: 'f32',
  twin: opticalThicknessSine,
  tolerance: {
    relative: 1e-5,
    absolute: 3e-4,
    reason:
      'WGSL sin is good to 2^-11 absolute on [−π, π]; the oscillating term is 2(a/k)·sin·sin ≤ 1/3 here',
  },
  cases: [
    {
      name: 'σ0 = 1e19, k = 3e19 rad/m, s ∈ [0, 1e-19]: τ = 1 + (1/6)(1 − cos 3) as for σ0 = 1, k = 3, s ∈ [0, 1]',
      args: [1e19, 0.5, 3e19, 0, 0, 1e-19],
      expected: 1.3316654161000743,
    },
    {
      name: 'the same profile at σ0 = 1, k = 3 rad/m, s ∈ [0, 1]',
      args: [1, 0.5, 3, 0, 0, 1],
      expected: 1.3316654161000743,
    },
  ],
});

describeShaderFunction({
  module: 'medium',
  fn: 'mediumMajorant',
  args: ['f32', 'f32', 'f32'],
  result: 'vec2f',
  wrapper: {
    imports: ['Medium1D', 'mediumExtinction', 'mediumMajorant'],
    wgsl: `fn caseUnderTest(sigma0: f32, s0: f32, s1: f32) -> vec2f {
  let sine = Medium1D(1u, sigma0, 0.5, 0.0, 1.5707964, 0.0, 0u, array<f32, 16>());
  let homogeneous = Medium1D(0u, sigma0, 0.0, 0.0, 0.0, 0.0, 0u, array<f32, 16>());
  return vec2f(mediumMajorant(sine, s0, s1), mediumExtinction(homogeneous, s0));
}`,
  },
  twin: ((sigma0: number, s0: number, s1: number) => [
    mediumMajorant(sineMedium(sigma0, 0.5, 0, Math.fround(Math.PI / 2)), s0, s1),
    mediumExtinction(homogeneousMedium(sigma0), s0),
  ]) as never,
  tolerance: { relative: 3e-7, reason: 'one f32 product' },
  cases: [
    {
      name: 'σ0 = 1e20 /m is not clamped to 1e18: majorant σ0(1 + a) = 1.5e20, σt = 1e20',
      args: [1e20, 0, 1],
      expected: [1.5e20, 1e20],
    },
    {
      name: 'σ0 = FLT_MAX: σ0(1 + a) saturates at FLT_MAX',
      args: [F32_MAX, 0, 1],
      expected: [F32_MAX, F32_MAX],
    },
  ],
});

describeShaderFunction({
  module: 'scatter',
  fn: 'singleScatterHomogeneousSlab',
  args: ['f32', 'f32', 'f32', 'f32', 'f32', 'f32', 'f32'],
  result: 'f32',
  twin: singleScatterHomogeneousSlab,
  tolerance: EXP,
  cases: [
    {
      name: 'issue 20: σs = 1e19, L = 1e-19 → 1 − e^-1 = 0.6321 (was 0.0952)',
      args: [1e19, 0, 1, 1, 0, 0, 1e-19],
      expected: ONE_MINUS_E_MINUS_1,
    },
    {
      name: 'the same medium in other units: σs = 1, L = 1 → 0.6321',
      args: [1, 0, 1, 1, 0, 0, 1],
      expected: ONE_MINUS_E_MINUS_1,
    },
    {
      name: 'σs = 1e-25, L = 1e25 → 0.6321',
      args: [1e-25, 0, 1, 1, 0, 0, 1e25],
      expected: ONE_MINUS_E_MINUS_1,
    },
    {
      name: 'σs = σa = 1e19 (α = ½), a = 5e-20, L = 5e-20: ½·e^{-1}(1 − e^{-1}), as σs = σa = 1, a = L = ½',
      args: [1e19, 1e19, 1, 1, 5e-20, 0, 5e-20],
      expected: 0.5 * E_MINUS_1 * ONE_MINUS_E_MINUS_1,
    },
  ],
});

describeShaderFunction({
  module: 'scatter',
  fn: 'shadowTransmittanceExact',
  args: ['f32', 'f32', 'f32', 'f32'],
  result: 'f32',
  twin: shadowTransmittanceExact,
  tolerance: EXP,
  cases: [
    { name: 'σt = 1e19, a = 1e-19 → e^-1', args: [1e19, 1e-19, 0, 0], expected: E_MINUS_1 },
    {
      name: 'σt = 1e-20, b·t = 1e20 → e^-1 (t was clamped to 1e18)',
      args: [1e-20, 0, 1, 1e20],
      expected: E_MINUS_1,
    },
  ],
});

describeShaderFunction({
  module: 'integrator',
  fn: 'transmittanceBeer',
  args: ['f32', 'f32', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['transmittanceBeer'],
    wgsl: 'fn caseUnderTest(r: f32, g: f32, b: f32, d: f32) -> vec3f { return transmittanceBeer(vec3f(r, g, b), d); }',
  },
  twin: ((r: number, g: number, b: number, d: number) => transmittanceBeer([r, g, b], d)) as never,
  tolerance: EXP,
  cases: [
    {
      name: 'issue 20: σt = (1e19, 2e19, 0), d = 1e-19 → (e^-1, e^-2, 1)',
      args: [1e19, 2e19, 0, 1e-19],
      expected: [E_MINUS_1, E_MINUS_1 * E_MINUS_1, 1],
    },
  ],
});

describeShaderFunction({
  module: 'tracking',
  fn: 'transmittanceResidualRatioTracking',
  args: ['f32', 'f32', 'f32', 'u32'],
  result: 'f32',
  wrapper: {
    imports: ['transmittanceResidualRatioTracking'],
    wgsl: `fn caseUnderTest(sigma: f32, d: f32, sigmaResidual: f32, seed: u32) -> f32 {
  var state = seed;
  let medium = package::medium::Medium1D(0u, sigma, 0.0, 0.0, 0.0, 0.0, 0u, array<f32, 16>());
  return transmittanceResidualRatioTracking(medium, d, sigma, sigmaResidual, &state, 64u).estimate;
}`,
  },
  twin: ((sigma: number, d: number, sigmaResidual: number, seed: number) =>
    transmittanceResidualRatioTracking(
      homogeneousMedium(sigma),
      d,
      sigma,
      sigmaResidual,
      { value: seed },
      64,
    ).estimate) as never,
  tolerance: EXP,
  cases: [
    {
      name: 'issue 20: control term e^{-σc d} with σc = σt = 1e19, d = 1e-19 → e^-1 on every walk (zero variance)',
      args: [1e19, 1e-19, 1e19, 12345],
      expected: E_MINUS_1,
    },
    {
      name: 'σc = σt = 1e-30, d = 1e30 → e^-1',
      args: [1e-30, 1e30, 1e-30, 777],
      expected: E_MINUS_1,
    },
  ],
});

const DIPOLE_WRAPPER = {
  imports: ['dipoleParameters', 'dipoleTotalReflectance', 'dipoleProfile'],
  wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32, r: f32) -> vec4f {
  let p = dipoleParameters(sp, sa, eta);
  return vec4f(p.albedoPrime, dipoleTotalReflectance(p), dipoleProfile(p, r), p.sigmaTPrime * p.zr);
}`,
};
/** The classic dipole at σs' = 1, σa = 0.01 per L, η = 1.3 (float64 twin, from §6.1's formulas). */
const UNIT_DIPOLE = {
  albedo: 0.9900990099009901,
  total: 0.6458266279762993,
  profileAtOne: 0.030312426479402372,
};
const DIPOLE = {
  relative: 2e-5,
  reason: 'f32 α′, the F_dr fit and A, sqrt and exp (a few ULP each, exp 3 + 2|x|)',
};

describeShaderFunction({
  module: 'dipole',
  fn: 'dipoleParameters',
  args: ['f32', 'f32', 'f32', 'f32'],
  result: 'vec4f',
  wrapper: DIPOLE_WRAPPER,
  twin: ((sp: number, sa: number, eta: number, r: number) => {
    const p = dipoleParameters(sp, sa, eta);
    return [p.albedoPrime, dipoleTotalReflectance(p), dipoleProfile(p, r), p.sigmaTPrime * p.zr];
  }) as never,
  tolerance: DIPOLE,
  cases: [
    {
      name: "issue 20: σs' = 1e10, σa = 1e8 /mm, η = 1.3: α' = 0.990099, R_d = 0.645827 (was 0.9091, 0.3137), R_d(1e-10) = 1e20 × R_d(1) at unit scale",
      args: [1e10, 1e8, 1.3, 1e-10],
      expected: [UNIT_DIPOLE.albedo, UNIT_DIPOLE.total, 1e20 * UNIT_DIPOLE.profileAtOne, 1],
    },
    {
      name: "the same medium 10^6 larger (σs' = 1e4, σa = 1e2): the same α' and R_d",
      args: [1e4, 1e2, 1.3, 1e-4],
      expected: [UNIT_DIPOLE.albedo, UNIT_DIPOLE.total, 1e8 * UNIT_DIPOLE.profileAtOne, 1],
    },
    {
      name: "σs' = 1e-15, σa = 1e-17 (was no medium below 1e-9): the same α' and R_d",
      args: [1e-15, 1e-17, 1.3, 1e15],
      expected: [UNIT_DIPOLE.albedo, UNIT_DIPOLE.total, 1e-30 * UNIT_DIPOLE.profileAtOne, 1],
    },
    {
      name: "σs' = 1e37, σa = 1e35 (σt' past 2^120: both scaled by one factor): the same α' and R_d, R_d(1) = 0",
      args: [1e37, 1e35, 1.3, 1],
      expected: [UNIT_DIPOLE.albedo, UNIT_DIPOLE.total, 0, 1],
      tolerance: {
        relative: 2e-5,
        absolute: F32_MIN_NORMAL,
        reason: 'as above; e^{-σtr·r} underflows to 0',
      },
    },
    {
      name: "σs' = 1e30, σa = 1e28: the same α' and R_d (R_d(r) would be 1e60: saturates, finite)",
      args: [1e30, 1e28, 1.3, 1e-30],
      expected: [
        UNIT_DIPOLE.albedo,
        UNIT_DIPOLE.total,
        F32_MAX * (UNIT_DIPOLE.albedo / (4 * Math.PI)),
        1,
      ],
      tolerance: {
        relative: 1e-4,
        reason: 'saturated profile: (α′/4π)·FLT_MAX, FLT_MAX within the 2^-18 guard',
      },
    },
  ],
});

describeShaderFunction({
  module: 'dipole',
  fn: 'betterDipoleParameters',
  args: ['f32', 'f32', 'f32'],
  result: 'vec2f',
  wrapper: {
    imports: ['betterDipoleParameters', 'betterDipoleTotalReflectance'],
    wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32) -> vec2f {
  let p = betterDipoleParameters(sp, sa, eta);
  return vec2f(p.albedoPrime, betterDipoleTotalReflectance(p));
}`,
  },
  twin: ((sp: number, sa: number, eta: number) => {
    const p = betterDipoleParameters(sp, sa, eta);
    return [p.albedoPrime, betterDipoleTotalReflectance(p)];
  }) as never,
  tolerance: {
    relative: 1e-4,
    reason: 'f32 Fresnel moments (quadrature) and the fluence quotient',
  },
  cases: [
    {
      name: "better dipole, σs' = 1e10, σa = 1e8: α' and R as at σs' = 1, σa = 0.01 (0.990099, 0.643352)",
      args: [1e10, 1e8, 1.3],
      expected: [UNIT_DIPOLE.albedo, 0.6433515015759868],
    },
    {
      name: "better dipole, σs' = 1e-25, σa = 1e-27: the same",
      args: [1e-25, 1e-27, 1.3],
      expected: [UNIT_DIPOLE.albedo, 0.6433515015759868],
    },
  ],
});

describeShaderFunction({
  module: 'dipole',
  fn: 'dipoleSourceTerm',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: dipoleSourceTerm,
  tolerance: {
    relative: 1e-5,
    absolute: F32_MIN_NORMAL,
    reason: 'sqrt, exp and two divisions; results below the normal range may flush to 0',
  },
  cases: [
    {
      name: 'issue 20: r = 1e30 (r² overflowed: NaN) → 1e-90, i.e. 0 in f32',
      args: [1, 0, 1e30],
      expected: 0,
    },
    { name: 'r = FLT_MAX → 0', args: [1, 1, F32_MAX], expected: 0 },
    {
      name: 'issue 20: z = 1e-20, r = 0 (z² underflowed: Inf) → 1/z² = 1e40 saturates at FLT_MAX',
      args: [1e-20, 1, 0],
      expected: F32_MAX,
      tolerance: { relative: 1e-5, reason: 'the saturation guard sits 2^-18 below FLT_MAX' },
    },
    {
      name: 'z = 1e-15, r = 0, σ = 0: d³ = 1e-45 underflows, 1/z² = 1e30',
      args: [1e-15, 0, 0],
      expected: 1e30,
    },
    {
      name: 'z = 1e-15, r = 1e-15: z/(√2 z)³ = 3.5355e29',
      args: [1e-15, 0, 1e-15],
      expected: 1 / (2 * Math.SQRT2 * 1e-30),
    },
    { name: 'z = 0 (source on the surface) → 0', args: [0, 1, 1], expected: 0 },
    { name: 'σ = FLT_MAX: e^{-σd} = 0 → 0', args: [1, F32_MAX, 1], expected: 0 },
  ],
});

describeShaderFunction({
  module: 'dipole',
  fn: 'burleyProfile',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: burleyProfile,
  tolerance: { relative: 1e-5, reason: 'exp and three f32 divisions' },
  cases: [
    {
      name: 'd = r = 1e-10 (d was clamped to 1e-9): 1e20 × R(d = r = 1)',
      args: [0.8, 1e-10, 1e-10],
      expected: 1e20 * 0.03451786629645036,
    },
    {
      name: 'd = r = 1e12 (d was clamped to 1e9): 1e-24 × R(d = r = 1)',
      args: [0.8, 1e12, 1e12],
      expected: 1e-24 * 0.03451786629645036,
    },
    { name: 'd = 0: no spread, 0', args: [0.8, 0, 1], expected: 0 },
  ],
});

describeShaderFunction({
  module: 'dipole',
  fn: 'burleyRadialCdf',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: burleyRadialCdf,
  tolerance: { relative: 1e-5, reason: 'exp and one f32 division' },
  cases: [
    {
      name: 'r = d = 1e-20: P = 0.370632 as at r = d = 1',
      args: [1e-20, 1e-20],
      expected: 0.37063165677679744,
    },
    { name: 'r = d = 1e30: the same', args: [1e30, 1e30], expected: 0.37063165677679744 },
  ],
});

describeShaderFunction({
  module: 'directions',
  fn: 'sampleUniformSphere',
  args: ['f32', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['sampleUniformSphere'],
    wgsl: 'fn caseUnderTest(u0: f32, u1: f32) -> vec3f { return sampleUniformSphere(vec2f(u0, u1)); }',
  },
  twin: ((u0: number, u1: number) => sampleUniformSphere([u0, u1])) as never,
  tolerance: { absolute: 2e-3, reason: 'WGSL sin and cos: 2^-11 absolute on [−π, π]' },
  cases: [
    {
      name: 'issue 20: u = (0.5, 1e38) (NaN: u.y was not clamped) → u.y = 1, (−1, 0, 0)',
      args: [0.5, 1e38],
      expected: [-1, 0, 0],
    },
    { name: 'u = (0.5, −1e38) → u.y = 0, (−1, 0, 0)', args: [0.5, -1e38], expected: [-1, 0, 0] },
    {
      name: 'u = (−FLT_MAX, FLT_MAX) → the north pole',
      args: [-F32_MAX, F32_MAX],
      expected: [0, 0, 1],
    },
  ],
});

describeShaderFunction({
  module: 'integrator',
  fn: 'truncatedExponentialPdf',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: truncatedExponentialPdf,
  tolerance: { relative: 1e-5, reason: 'exp, oneMinusExpOverX and one division' },
  cases: [
    {
      name: 'issue 20: subnormal L = 1e-40 (Inf) → an empty segment, 0',
      args: [1, 1e-40, 0],
      expected: 0,
    },
    {
      name: 'k = 1e30, L = 1e-30, s = 0: k/(1 − e^-1) = 1.582e30',
      args: [1e30, 1e-30, 0],
      expected: 1.5819767068693265 * 1e30,
    },
    {
      name: 'k = 1, L = 1, s = 0: 1/(1 − e^-1) = 1.582',
      args: [1, 1, 0],
      expected: 1.5819767068693265,
    },
    { name: 'L = −1 → 0', args: [0, -1, 0], expected: 0 },
    { name: 's > L (outside the support) → 0', args: [1, 1, 2], expected: 0 },
  ],
});

describeShaderFunction({
  module: 'integrator',
  fn: 'sampleTruncatedExponential',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: sampleTruncatedExponential,
  tolerance: { relative: 1e-5, absolute: 1e-45, reason: 'log, exp and one division' },
  cases: [
    { name: 'issue 20: k = 0, L = −1 (returned −1) → 0', args: [0, -1, 0.5], expected: 0 },
    { name: 'k = 0, L = 2, u = ½ → uniform, 1', args: [0, 2, 0.5], expected: 1 },
    {
      name: 'k = 1e30, L = 1e-30, u = ½ → −ln(1 − ½(1 − e^-1))/k = 3.7989e-31',
      args: [1e30, 1e-30, 0.5],
      expected: 0.3798854930417225 * 1e-30,
    },
    { name: 'u = 1 (clamped to 1 − 2^-24) → within [0, L]', args: [5, 1, 1] },
  ],
});
