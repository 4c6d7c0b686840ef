// WGSL fresnel module vs its float64 twin (physics.md §6.1, §6.2): the unpolarised
// reflectance at chosen angles and indices, including total internal reflection and the
// matched boundary, and the internal moments against the exact F_dr column of the §6.1
// table (F_dr = 2C₁) and the §6.2 values at η = 1.3. Convention: the one at the top of
// shaders/fresnel.wesl (eta = n_t/n_i; moments with the light inside).
import { describeShaderFunction, type Tolerance } from '../support/shaderHarness.ts';
import {
  fresnelDielectric,
  fresnelIntegerPower,
  fresnelMoment,
} from '../../src/reference/fresnel.ts';
import { FDR_TABLE, MOMENTS_AT_1_3 } from '../support/subsurfaceTables.ts';

// F = ½(r∥² + r⊥²): two WGSL divisions (2.5 ULP each), a sqrt and a few products give
// ≲ 12 ULP ≈ 1.5e-6 relative where F is not small. Near η = 1 or Brewster's angle F is a
// square of a small r whose absolute error is a few ULP of 1, hence the absolute part.
const REFLECTANCE: Tolerance = {
  relative: 2e-6,
  absolute: 1e-7,
  reason: '§10: two divisions and a sqrt (≲ 12 ULP); small F is the square of a small r (abs)',
};
// 16-point Gauss–Legendre in f32: 16 products of ≲ 12-ULP terms summed (≤ 2e-6 of the
// sum), and the rule's own error, ≤ 1e-7 except within 1e-3 of η = 1 (float64: 9e-8 at
// η = 1.001). The published digits are 6 (±5e-7); F_dr = 2C₁ halves that for C₁.
const MOMENT: Tolerance = {
  absolute: 2e-6,
  reason: '16-point Gauss–Legendre in f32 (≲ 2e-6) vs adaptive float64 quadrature; table ±5e-7',
};

describeShaderFunction({
  module: 'fresnel',
  fn: 'fresnelDielectric',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: fresnelDielectric,
  tolerance: REFLECTANCE,
  cases: [
    {
      name: 'normal incidence, η = 1.5: ((η − 1)/(η + 1))² = 0.04 (§7 B)',
      args: [1, 1.5],
      expected: 0.04,
    },
    {
      name: 'normal incidence from inside, η = 1/1.5: also 0.04',
      args: [1, 1 / 1.5],
      expected: 0.04,
    },
    { name: 'η = 1 reflects nothing (§9 row 22)', args: [0.3, 1], expected: 0 },
    { name: 'η = 1 at normal incidence', args: [1, 1], expected: 0 },
    { name: 'grazing incidence from outside: F = 1', args: [0, 1.3], expected: 1 },
    {
      name: 'beyond the critical angle from inside (μ = 0.5 < 0.639): total reflection',
      args: [0.5, 1 / 1.3],
      expected: 1,
    },
    {
      name: 'just inside the critical cosine of η = 1.3 (μ = 0.64, μc = 0.6390)',
      args: [0.64, 1 / 1.3],
      // cos θt = √(1 − sin²θt) with 1 − sin²θt ≈ 2.2e-3: its rounding is amplified ≈ 230×.
      tolerance: {
        relative: 5e-5,
        reason: 'near the critical angle cos θt is ill-conditioned (≈ 230× ε)',
      },
    },
    {
      name: 'Brewster angle, η = 1.5 (tan θ = 1.5): r∥ = 0',
      args: [Math.cos(Math.atan(1.5)), 1.5],
    },
    { name: 'η = 1.3, μ = 0.7', args: [0.7, 1.3] },
    { name: 'η = 1/1.5, μ = 0.9', args: [0.9, 1 / 1.5] },
    { name: 'η = 2, μ = 0.2', args: [0.2, 2] },
    { name: 'η = 1.001, μ = 0.5 (nearly matched)', args: [0.5, 1.001] },
    { name: 'cosθ = 1.5 is clamped to 1', args: [1.5, 1.5], expected: 0.04 },
    { name: 'η = 1000 is clamped to 64', args: [1, 1000] },
  ],
});

describeShaderFunction({
  module: 'fresnel',
  fn: 'fresnelIntegerPower',
  args: ['f32', 'u32'],
  result: 'f32',
  twin: fresnelIntegerPower,
  tolerance: { ulps: 4, reason: 'up to 8 rounded products' },
  cases: [
    { name: '0^0 = 1 (no log2(0))', args: [0, 0], expected: 1 },
    { name: '0^3 = 0', args: [0, 3], expected: 0 },
    { name: '0.5^2', args: [0.5, 2], expected: 0.25 },
    { name: '0.9^8', args: [0.9, 8] },
    { name: 'k = 12 is capped at 8', args: [0.9, 12], expected: 0.9 ** 8 },
  ],
});

const momentCases = [
  ...FDR_TABLE.map(([eta, , exactInternal]) => ({
    name: `C₁(${eta}) = F_dr/2 = ${exactInternal / 2} (§6.1 exact internal)`,
    args: [eta, 1],
    expected: exactInternal / 2,
  })),
  { name: `C₂(1.3) = ${MOMENTS_AT_1_3.c2} (§6.2)`, args: [1.3, 2], expected: MOMENTS_AT_1_3.c2 },
  { name: `C₁(1.3) = ${MOMENTS_AT_1_3.c1} (§6.2)`, args: [1.3, 1], expected: MOMENTS_AT_1_3.c1 },
  { name: 'C₂(1) = 0 exactly (§9 row 22)', args: [1, 2], expected: 0 },
  { name: 'C₀(1.5)', args: [1.5, 0] },
  { name: 'C₂(1.5)', args: [1.5, 2] },
  { name: 'C₃(1.33)', args: [1.33, 3] },
  { name: 'C₁(1.01), close to matched', args: [1.01, 1] },
  {
    name: 'C₁(1/1.3) = external F_dr(1.3)/2 (no total reflection)',
    args: [1 / 1.3, 1],
    expected: 0.061132 / 2,
  },
  { name: 'C₂(0.5)', args: [0.5, 2] },
  { name: 'C₁(3)', args: [3, 1] },
];

describeShaderFunction({
  module: 'fresnel',
  fn: 'fresnelMoment',
  args: ['f32', 'u32'],
  result: 'f32',
  twin: fresnelMoment,
  tolerance: MOMENT,
  cases: momentCases,
});
