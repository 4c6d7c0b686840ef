// WGSL dipole module vs its float64 twin (physics.md §6): the F_dr fit and boundary term
// against the §6.1 values, the derived quantities, profiles and totals of all twelve
// Jensen et al. 2001 materials (36 channels; their published values are checked on the
// twin in tests/reference/dipole.test.ts at the table's digits), the Skimmilk R profile,
// the better dipole of §6.2 and the Christensen–Burley functions of §6.3. Units: the
// table's, 1/mm and mm.
import { describeShaderFunction, type Tolerance } from '../support/shaderHarness.ts';
import {
  betterDipoleParameters,
  betterDipoleProfile,
  betterDipoleTotalReflectance,
  burleyProfile,
  burleyRadialCdf,
  burleyRadialDensity,
  burleyShapeDiffuse,
  burleyShapeDmfp,
  burleyShapeSearchlight,
  dipoleBoundary,
  dipoleParameters,
  dipoleProfile,
  dipoleReflectanceBeyond,
  dipoleSourceTerm,
  dipoleTotalReflectance,
  exponentialDifferenceOverRate,
  fresnelDiffuseReflectanceFit,
} from '../../src/reference/dipole.ts';
import {
  BURLEY_CDF_16D,
  BURLEY_MEDIAN_R_OVER_D,
  BURLEY_SHAPE_TABLE,
  CHANNEL_NAMES,
  DERIVED_DIPOLE_TABLE,
  FDR_TABLE,
  rowInputs,
  SKIMMILK_R_BETTER,
  SKIMMILK_R_PROFILE,
} from '../support/subsurfaceTables.ts';

// ---------------------------------------------------------------------------
// Tolerances (physics.md §10 ULP budgets)
// ---------------------------------------------------------------------------
// The fit is a sum of four terms of size ≤ 1 with partial cancellation (|terms| ≤ 1.5):
// a few ULP of 1.5, ≤ 3e-7 absolute. The table prints 6 decimals (±5e-7).
const FIT: Tolerance = {
  absolute: 1e-6,
  reason: 'four f32 terms up to 1.5 (≤ 3e-7) + the table’s 6 decimals (±5e-7)',
};
// Derived quantities: one sum, one division or one sqrt each, ≤ 3 ULP; z_v also carries
// A’s ≈ 5e-7 relative from the fit (1 − F_dr ≥ 0.4 amplifies its absolute error ≤ 2.5×).
const PARAMETERS: Tolerance = {
  relative: 2e-6,
  reason: 'one add/div/sqrt each (≤ 3 ULP), z_v also A’s ≈ 5e-7 from the fit',
};
// Profiles: exp has (3 + 2x) ULP with x = σtr·d ≤ 20 in these cases (≤ 43 ULP, 2.6e-6),
// and the two source terms add ≈ 10 ULP of sqrt and divisions.
// Far tails (Skin1 B at 100 mm: 7e-69) lie below f32's normal range and underflow to 0 (§1.2).
const PROFILE: Tolerance = {
  relative: 5e-6,
  absolute: 2 ** -126,
  reason:
    'WGSL exp (3 + 2σtr·d ULP, σtr·d ≤ 20 here) + sqrt and divisions (≈ 10 ULP); tails below 2^-126 flush to 0',
};
// Totals: two exps of arguments ≤ 8 (≤ 19 ULP) and a product; the twin evaluates the α' form.
const TOTAL: Tolerance = {
  relative: 3e-6,
  reason: 'two WGSL exps with arguments ≤ 8 (≤ 19 ULP) and a few products',
};
// Better dipole: as PROFILE, plus the Fresnel moments of the 16-point rule (≤ 2e-6 absolute,
// tests/shaders/fresnel.test.ts) in C_φ, C_E and A.
const BETTER: Tolerance = {
  relative: 1e-5,
  absolute: 2 ** -126,
  reason:
    'as the classic profile, plus the f32 Gauss–Legendre Fresnel moments (≤ 2e-6 abs); tails below 2^-126 flush to 0',
};

const f = Math.fround;
const label = (material: string, channel: number): string =>
  `${material} ${CHANNEL_NAMES[channel] ?? channel}`;

// ---------------------------------------------------------------------------
// Fresnel fit and boundary term (§6.1, §9 rows 22, 23)
// ---------------------------------------------------------------------------
describeShaderFunction({
  module: 'dipole',
  fn: 'fresnelDiffuseReflectanceFit',
  args: ['f32'],
  result: 'f32',
  twin: fresnelDiffuseReflectanceFit,
  tolerance: FIT,
  cases: [
    ...FDR_TABLE.map(([eta, fit]) => ({
      name: `η = ${eta}: the Jensen fit ${fit} (§6.1)`,
      args: [eta],
      expected: fit,
    })),
    {
      name: 'η = 1/1.3 < 1: pbrt-v2’s external-side branch, 0.06179 (§9 row 23)',
      args: [1 / 1.3],
      expected: 0.06179,
      tolerance: { absolute: 6e-6, reason: 'published to 5 decimals' },
    },
    { name: 'η = 0.2 is clamped to 0.5', args: [0.2], expected: fresnelDiffuseReflectanceFit(0.5) },
    { name: 'η = 4 is clamped to 2.5', args: [4], expected: fresnelDiffuseReflectanceFit(2.5) },
  ],
});

describeShaderFunction({
  module: 'dipole',
  fn: 'dipoleBoundary',
  args: ['f32'],
  result: 'f32',
  twin: dipoleBoundary,
  tolerance: { relative: 1e-6, reason: 'the fit’s ≤ 3e-7 over 1 − F_dr ≥ 0.4, and one division' },
  cases: [
    { name: 'A(1.3) = 2.60206439 (§6.1)', args: [1.3], expected: 2.60206439 },
    { name: 'A(1.5) = 3.95949744 (§6.1)', args: [1.5], expected: 3.95949744 },
    { name: 'A(1) = 1.003205 from the fit, not 1 (§9 row 22)', args: [1], expected: 1.003205 },
    { name: 'A(2)', args: [2] },
  ],
});

// ---------------------------------------------------------------------------
// Derived quantities, profile and total of every material channel (§6.1)
// ---------------------------------------------------------------------------
const PARAMETER_WRAPPER = {
  imports: ['dipoleParameters'],
  wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32) -> vec4f {
  let p = dipoleParameters(sp, sa, eta);
  return vec4f(p.sigmaTPrime, p.albedoPrime, p.sigmaTr, p.zr);
}`,
};
const SOURCES_WRAPPER = {
  imports: ['dipoleParameters'],
  wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32) -> vec2f {
  let p = dipoleParameters(sp, sa, eta);
  return vec2f(p.zv, p.boundaryA);
}`,
};
const materialCases = DERIVED_DIPOLE_TABLE.map((row) => ({
  name: label(row.material, row.channel),
  args: rowInputs(row),
}));

describeShaderFunction({
  module: 'dipole',
  fn: 'dipoleParameters',
  args: ['f32', 'f32', 'f32'],
  result: 'vec4f',
  wrapper: PARAMETER_WRAPPER,
  twin: (sp: number, sa: number, eta: number) => {
    const p = dipoleParameters(sp, sa, eta);
    return [p.sigmaTPrime, p.albedoPrime, p.sigmaTr, p.zr];
  },
  tolerance: PARAMETERS,
  cases: [
    ...materialCases.map((c) => ({ ...c, name: `(σt', α', σtr, z_r) of ${c.name}` })),
    {
      name: 'no medium, σs′ = σa = 0: all zero (§9 row 20)',
      args: [0, 0, 1.3],
      expected: [0, 0, 0, 0],
    },
    { name: 'α′ = 0 (σs′ = 0, σa = 1): α′ = 0, σtr = √3', args: [0, 1, 1.3] },
    { name: 'α′ = 1 (σa = 0): σtr = 0 (§9 row 21)', args: [5, 0, 1.3] },
    { name: 'σs′ = 1e12 is clamped to 1e9', args: [1e12, 1, 1.3] },
  ],
});

describeShaderFunction({
  module: 'dipole',
  fn: 'dipoleParameters',
  args: ['f32', 'f32', 'f32'],
  result: 'vec2f',
  wrapper: SOURCES_WRAPPER,
  twin: (sp: number, sa: number, eta: number) => {
    const p = dipoleParameters(sp, sa, eta);
    return [p.zv, p.boundaryA];
  },
  tolerance: PARAMETERS,
  cases: materialCases.map((c) => ({ ...c, name: `(z_v, A) of ${c.name}` })),
});

describeShaderFunction({
  module: 'dipole',
  fn: 'dipoleSourceTerm',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: dipoleSourceTerm,
  tolerance: PROFILE,
  cases: [
    { name: 'z = 1, σ = 0, r = 0: 1/z² = 1', args: [1, 0, 0], expected: 1 },
    { name: 'z = 1e-9 (the smallest z_r), r = 0: finite 1e18', args: [1e-9, 0, 0] },
    { name: 'd = 1e9 (never forms d³ = 1e27 … 1e45)', args: [1, 0, 1e9] },
    { name: 'skim-milk-like z = 1.4, σ = 0.054, r = 3', args: [1.4, 0.054, 3] },
  ],
});

const PROFILE_WRAPPER = {
  imports: ['dipoleParameters', 'dipoleProfile'],
  wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32, r: f32) -> f32 {
  return dipoleProfile(dipoleParameters(sp, sa, eta), r);
}`,
};
const profileTwin = (sp: number, sa: number, eta: number, r: number): number =>
  dipoleProfile(dipoleParameters(sp, sa, eta), r);

describeShaderFunction({
  module: 'dipole',
  fn: 'dipoleProfile',
  args: ['f32', 'f32', 'f32', 'f32'],
  result: 'f32',
  wrapper: PROFILE_WRAPPER,
  twin: profileTwin,
  tolerance: PROFILE,
  cases: [
    ...SKIMMILK_R_PROFILE.map(([r, value]) => ({
      name: `Skimmilk R, R_d(${r} mm) = ${value} mm⁻² (§6.1)`,
      args: [0.7, 0.0014, 1.3, r],
      expected: value,
    })),
    ...materialCases.map((c) => ({ name: `R_d(0) of ${c.name}`, args: [...c.args, 0] })),
    ...[0.01, 0.3, 3, 30, 100].flatMap((r) =>
      [0, 1, 2].map((channel) => ({
        name: `Skin1 ${CHANNEL_NAMES[channel]} at r = ${r} mm`,
        args: [[0.74, 0.88, 1.01][channel]!, [0.032, 0.17, 0.48][channel]!, 1.3, r],
      })),
    ),
    { name: 'r < 0 is |r|', args: [0.7, 0.0014, 1.3, -1], expected: 2.31436913e-2 },
    { name: 'α′ = 0: R_d ≡ 0 (§9 row 20)', args: [0, 1, 1.3, 0], expected: 0 },
    { name: 'no medium: R_d ≡ 0 (§9 row 20)', args: [0, 0, 1.3, 1], expected: 0 },
  ],
});

const TOTAL_WRAPPER = {
  imports: ['dipoleParameters', 'dipoleTotalReflectance'],
  wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32) -> f32 {
  return dipoleTotalReflectance(dipoleParameters(sp, sa, eta));
}`,
};

describeShaderFunction({
  module: 'dipole',
  fn: 'dipoleTotalReflectance',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  wrapper: TOTAL_WRAPPER,
  twin: (sp: number, sa: number, eta: number) =>
    dipoleTotalReflectance(dipoleParameters(sp, sa, eta)),
  tolerance: TOTAL,
  cases: [
    ...materialCases.map((c) => ({ name: `total R_d of ${c.name}`, args: c.args })),
    {
      name: `Skimmilk R: ${SKIMMILK_R_BETTER.classicTotal} (§6.2)`,
      args: [0.7, 0.0014, 1.3],
      expected: SKIMMILK_R_BETTER.classicTotal,
    },
    { name: 'α′ = 1: exactly 1 (§9 row 21)', args: [11.6, 0, 1.3], expected: 1 },
    { name: 'α′ = 0: 0 (§9 row 20)', args: [0, 2, 1.3], expected: 0 },
  ],
});

const BEYOND_WRAPPER = {
  imports: ['dipoleParameters', 'dipoleReflectanceBeyond'],
  wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32, radius: f32) -> f32 {
  return dipoleReflectanceBeyond(dipoleParameters(sp, sa, eta), radius);
}`,
};

describeShaderFunction({
  module: 'dipole',
  fn: 'dipoleReflectanceBeyond',
  args: ['f32', 'f32', 'f32', 'f32'],
  result: 'f32',
  wrapper: BEYOND_WRAPPER,
  twin: (sp: number, sa: number, eta: number, radius: number) =>
    dipoleReflectanceBeyond(dipoleParameters(sp, sa, eta), radius),
  tolerance: TOTAL,
  cases: [
    {
      name: 'Spectralon R beyond 10 mm: 2.36% (§6.1, §9 row 21)',
      args: [11.6, 0, 1.3, 10],
      expected: 0.0236,
      tolerance: { absolute: 5e-5, relative: 3e-6, reason: 'published as 2.36%' },
    },
    {
      name: 'Spectralon R beyond 1 mm: 22.3% (§6.1)',
      args: [11.6, 0, 1.3, 1],
      expected: 0.223,
      tolerance: { absolute: 5e-4, relative: 3e-6, reason: 'published as 22.3%' },
    },
    {
      name: 'radius 0 is the total (Skimmilk R)',
      args: [0.7, 0.0014, 1.3, 0],
      expected: SKIMMILK_R_BETTER.classicTotal,
    },
    { name: 'Skin1 B beyond 2 mm', args: [1.01, 0.48, 1.3, 2] },
    { name: 'Ketchup R beyond 20 mm', args: [0.18, 0.061, 1.3, 20] },
  ],
});

describeShaderFunction({
  module: 'dipole',
  fn: 'exponentialDifferenceOverRate',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: exponentialDifferenceOverRate,
  tolerance: {
    relative: 2e-6,
    reason: 'exp (3 + 2x ULP, x ≤ 5) times oneMinusExpOverX (≤ 2 ULP, raymarch tests)',
  },
  cases: [
    {
      name: 'σ = 1e-7, a = 1, b = 5: 3.9999988, not the naive 4.17 (§6.2)',
      args: [1e-7, 1, 5],
      expected: 3.9999988,
    },
    { name: 'σ = 0: the limit b − a', args: [0, 1, 5], expected: 4 },
    { name: 'σ = 1, a = 1, b = 5', args: [1, 1, 5], expected: Math.exp(-1) - Math.exp(-5) },
    { name: 'σ = 1e-3, a = 0.5, b = 3', args: [1e-3, 0.5, 3] },
    { name: 'a = b: 0', args: [2, 3, 3], expected: 0 },
  ],
});

// ---------------------------------------------------------------------------
// Better dipole (§6.2)
// ---------------------------------------------------------------------------
const BETTER_INPUTS: readonly { name: string; args: [number, number, number] }[] = [
  { name: 'Skimmilk R', args: [0.7, 0.0014, 1.3] },
  { name: 'Skin1 R', args: [0.74, 0.032, 1.3] },
  { name: 'Skin1 B', args: [1.01, 0.48, 1.3] },
  { name: 'Marble G (η = 1.5)', args: [2.62, 0.0041, 1.5] },
  { name: 'Ketchup B (α′ = 0.02)', args: [0.03, 1.45, 1.3] },
  { name: 'Skimmilk R at η = 1 (C₁ = C₂ = 0)', args: [0.7, 0.0014, 1] },
  { name: 'Spectralon R (α′ = 1)', args: [11.6, 0, 1.3] },
];

describeShaderFunction({
  module: 'dipole',
  fn: 'betterDipoleParameters',
  args: ['f32', 'f32', 'f32'],
  result: 'vec4f',
  wrapper: {
    imports: ['betterDipoleParameters'],
    wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32) -> vec4f {
  let p = betterDipoleParameters(sp, sa, eta);
  return vec4f(p.albedoPrime, p.sigmaTr, p.diffusion, p.zr);
}`,
  },
  twin: (sp: number, sa: number, eta: number) => {
    const p = betterDipoleParameters(sp, sa, eta);
    return [p.albedoPrime, p.sigmaTr, p.diffusion, p.zr];
  },
  tolerance: PARAMETERS,
  cases: [
    ...BETTER_INPUTS.map((c) => ({ name: `(α′, σtr, D, z_r) of ${c.name}`, args: c.args })),
    { name: 'no medium: zeros (§9 row 20)', args: [0, 0, 1.3], expected: [0, 0, 0, 0] },
  ],
});

describeShaderFunction({
  module: 'dipole',
  fn: 'betterDipoleParameters',
  args: ['f32', 'f32', 'f32'],
  result: 'vec3f',
  wrapper: {
    imports: ['betterDipoleParameters'],
    wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32) -> vec3f {
  let p = betterDipoleParameters(sp, sa, eta);
  return vec3f(p.zv, p.cPhi, p.cE);
}`,
  },
  twin: (sp: number, sa: number, eta: number) => {
    const p = betterDipoleParameters(sp, sa, eta);
    return [p.zv, p.cPhi, p.cE];
  },
  tolerance: BETTER,
  cases: [
    ...BETTER_INPUTS.map((c) => ({ name: `(z_v, C_φ, C_E) of ${c.name}`, args: c.args })),
    {
      name: 'η = 1: C_φ = ¼, C_E = ½ (§9 row 22)',
      args: [0.7, 0.0014, 1],
      expected: [betterDipoleParameters(0.7, 0.0014, 1).zv, 0.25, 0.5],
    },
  ],
});

const BETTER_PROFILE_WRAPPER = {
  imports: ['betterDipoleParameters', 'betterDipoleProfile'],
  wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32, r: f32) -> f32 {
  return betterDipoleProfile(betterDipoleParameters(sp, sa, eta), r);
}`,
};

describeShaderFunction({
  module: 'dipole',
  fn: 'betterDipoleProfile',
  args: ['f32', 'f32', 'f32', 'f32'],
  result: 'f32',
  wrapper: BETTER_PROFILE_WRAPPER,
  twin: (sp: number, sa: number, eta: number, r: number) =>
    betterDipoleProfile(betterDipoleParameters(sp, sa, eta), r),
  tolerance: BETTER,
  cases: [
    ...SKIMMILK_R_BETTER.profile.map(([r, value]) => ({
      name: `Skimmilk R at ${r} mm: ${value} mm⁻² (§6.2)`,
      args: [0.7, 0.0014, 1.3, r],
      expected: value,
      tolerance: {
        relative: 1e-5,
        reason: 'published to 7 significant digits; f32 as for the other profiles',
      },
    })),
    ...BETTER_INPUTS.flatMap((c) =>
      [0, 0.1, 2, 20, 200].map((r) => ({
        name: `${c.name} at r = ${r} mm${r === 200 ? ' (r ≫ |z_v|: the stable fluence difference)' : ''}`,
        args: [...c.args, r],
      })),
    ),
    { name: 'α′ = 0: 0', args: [0, 1, 1.3, 1], expected: 0 },
  ],
});

describeShaderFunction({
  module: 'dipole',
  fn: 'betterDipoleTotalReflectance',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  wrapper: {
    imports: ['betterDipoleParameters', 'betterDipoleTotalReflectance'],
    wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32) -> f32 {
  return betterDipoleTotalReflectance(betterDipoleParameters(sp, sa, eta));
}`,
  },
  twin: (sp: number, sa: number, eta: number) =>
    betterDipoleTotalReflectance(betterDipoleParameters(sp, sa, eta)),
  tolerance: BETTER,
  cases: [
    {
      name: `Skimmilk R: ${SKIMMILK_R_BETTER.total} (§6.2)`,
      args: [0.7, 0.0014, 1.3],
      expected: SKIMMILK_R_BETTER.total,
    },
    {
      name: 'α′ = 1 (σtr = 0): the 0/0 limit gives exactly 1 (§6.2, §9 row 21)',
      args: [11.6, 0, 1.3],
      expected: 1,
    },
    { name: 'α′ = 1 at η = 1.5', args: [2, 0, 1.5], expected: 1 },
    { name: 'σa = 1e-9 (σtr·|z_v| ≈ 1e-4): next to the limit', args: [1, 1e-9, 1.3] },
    ...BETTER_INPUTS.slice(1, 6).map((c) => ({ name: `total of ${c.name}`, args: c.args })),
  ],
});

// ---------------------------------------------------------------------------
// Christensen–Burley (§6.3)
// ---------------------------------------------------------------------------
const SHAPE: Tolerance = {
  absolute: 2e-6,
  relative: 4e-7,
  reason: 'a cubic or quartic of A ≤ 1 in f32 (a few ULP of s ≤ 24); the table’s decimals',
};
for (const [fn, twin, column] of [
  ['burleyShapeSearchlight', burleyShapeSearchlight, 1],
  ['burleyShapeDiffuse', burleyShapeDiffuse, 2],
  ['burleyShapeDmfp', burleyShapeDmfp, 3],
] as const) {
  describeShaderFunction({
    module: 'dipole',
    fn,
    args: ['f32'],
    result: 'f32',
    twin,
    tolerance: SHAPE,
    cases: [
      ...BURLEY_SHAPE_TABLE.map((row) => ({
        name: `A = ${row[0]}: s = ${row[column]} (§6.3)`,
        args: [row[0]],
        expected: row[column],
        // The A = 0.2 … 1 rows print exact decimals of A; f32(A) moves s by ≤ 1e-6·|s′(A)|.
        tolerance: {
          absolute: fn === 'burleyShapeDmfp' ? 2e-5 : 2e-6,
          reason: 'f32(A) moves s by ≤ |s′(A)|·3e-8 (|s′| ≤ 270 for the dmfp quartic)',
        },
      })),
      { name: 'A = 1.5 is clamped to 1', args: [1.5], expected: twin(1) },
    ],
  });
}

describeShaderFunction({
  module: 'dipole',
  fn: 'burleyProfile',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: burleyProfile,
  tolerance: { relative: 4e-6, reason: 'two exps (x ≤ 30: ≤ 63 ULP) and a division' },
  cases: [
    { name: 'A = 0.8, d = 1, r = 1', args: [0.8, 1, 1] },
    { name: 'A = 0.5, d = 0.3, r = 2', args: [0.5, 0.3, 2] },
    { name: 'r = 0 is raised to 1e-6·d (singular at 0, §9 row 19)', args: [1, 1, 0] },
    { name: 'A = 1, d = 2, r = 10', args: [1, 2, 10] },
  ],
});

describeShaderFunction({
  module: 'dipole',
  fn: 'burleyRadialDensity',
  args: ['f32', 'f32', 'f32'],
  result: 'f32',
  twin: burleyRadialDensity,
  tolerance: { relative: 4e-6, reason: 'two exps and a division' },
  cases: [
    { name: 'r = 0: A/(2d), finite (§9 row 19)', args: [0.8, 2, 0], expected: 0.2 },
    { name: 'A = 0.6, d = 1, r = 1.5', args: [0.6, 1, 1.5] },
  ],
});

describeShaderFunction({
  module: 'dipole',
  fn: 'burleyRadialCdf',
  args: ['f32', 'f32'],
  result: 'f32',
  twin: burleyRadialCdf,
  tolerance: {
    absolute: 3e-7,
    reason: '1 − ¼e^{−x} − ¾e^{−x/3} in f32: a few ULP of 1 (absolute)',
  },
  cases: [
    {
      name: `P(16d) = ${BURLEY_CDF_16D} (§6.3, §9 row 26)`,
      args: [16, 1],
      expected: BURLEY_CDF_16D,
    },
    {
      name: `median at r/d = ${BURLEY_MEDIAN_R_OVER_D} (§6.3)`,
      args: [BURLEY_MEDIAN_R_OVER_D * 2, 2],
      expected: 0.5,
    },
    { name: 'P(0) = 0', args: [0, 1], expected: 0 },
    { name: 'r = 3, d = 0.5', args: [3, 0.5] },
    { name: 'f32 of 1.55218326·2', args: [f(3.1), 2] },
  ],
});
