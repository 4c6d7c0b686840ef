// Issue 20 on the GPU (Dawn): the WGSL library does not depend on the unit of length.
// For every library function of coefficients and lengths that the table harness can call,
// base inputs are drawn with fast-check (fixed seed), each is rescaled by k = 10^e for
// e ∈ {−30, −20, −10, −5, 0, 5, 10, 20, 30} (coefficients × k, lengths / k; every scaled
// input is a normal f32), all cases run in one dispatch, and the GPU result at scale k is held
// to k^p times the GPU result at k = 1 (p the dimension of the result in 1/m).
//
// Tolerance: the scaled inputs are rounded to f32 separately (σk and d/k each by ≤ 2^-24), so
// an optical thickness τ moves by ≈ 2^-23·τ, and WGSL's exp adds 3 + 2|x| ULP (physics.md §10);
// with τ ≤ 40 in these tables that is below 1e-5 relative. 1e-4 relative (plus 1e-7·k^p
// absolute for results that are ≤ 1 at k = 1) leaves room for sqrt and divisions and is four
// orders of magnitude below the errors a separate clamp made (e^{-0.1} for e^{-1}). Where k^p
// times the result leaves the normal f32 range (or comes within 10^3 of its top, where a
// profile's intermediate terms saturate first), only finiteness is required: the documented
// convention there is saturation at the largest f32.
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  evaluateTable,
  type Argument,
  type ArgumentType,
  type ResultType,
} from '../support/shaderHarness.ts';
import {
  betterDipoleParameters,
  betterDipoleProfile,
  betterDipoleTotalReflectance,
  burleyProfile,
  burleyRadialCdf,
  burleyRadialDensity,
  dipoleParameters,
  dipoleProfile,
  dipoleReflectanceBeyond,
  dipoleSourceTerm,
  dipoleTotalReflectance,
  exponentialDifferenceOverRate,
} from '../../src/reference/dipole.ts';
import {
  sampleTruncatedExponential,
  transmittanceBeer,
  truncatedExponentialPdf,
} from '../../src/reference/integrator.ts';
import {
  mediumExtinction,
  mediumMajorant,
  mediumOpticalDepth,
} from '../../src/reference/medium.ts';
import {
  linearEmission,
  MARCH_MIDPOINT,
  raymarchEmissionAbsorption,
  raymarchOpticalDepth,
} from '../../src/reference/raymarch.ts';
import {
  equiangularPdf,
  equiangularSample,
  shadowTransmittanceExact,
  singleScatterHomogeneousSlab,
  singleScatterMarched,
} from '../../src/reference/scatter.ts';
import {
  nullCollisionWeight,
  sampleFreeFlight,
  transmittanceTrackLength,
} from '../../src/reference/tracking.ts';
import {
  opticalThicknessGrid1D,
  opticalThicknessHomogeneous,
  opticalThicknessSine,
  transmittanceHomogeneous,
} from '../../src/reference/transmittance.ts';
import { F32_MAX, F32_MIN_NORMAL } from '../support/f32.ts';
import {
  MEDIUM_ARGUMENTS,
  MEDIUM_PARAMETERS,
  MEDIUM_VALUE,
  mediumFromArguments,
} from '../support/medium1d.ts';

const EXPONENTS = [-30, -20, -10, -5, 0, 5, 10, 20, 30];
const RELATIVE = 1e-4;
const BASE_CASES = 10;

/** How an argument scales: +1 a coefficient (1/m), −1 a length (m), 0 dimensionless. */
type Dimension = -1 | 0 | 1;

interface InvarianceTable {
  name: string;
  module: string;
  fn: string;
  args: readonly ArgumentType[];
  result: ResultType;
  twin: (...args: never[]) => number | readonly number[];
  wrapper?: { wgsl: string; imports: readonly string[] };
  /** Dimension of each argument (an array argument scales element-wise). */
  dimensions: readonly Dimension[];
  /** Dimension of each result component: f(scaled) = k^p·f(base). */
  resultDimensions: readonly number[];
  /** Base arguments (moderate, so that every scaled one is a normal f32). */
  base: fc.Arbitrary<Argument[]>;
}

const coefficient = fc.double({ min: 0.1, max: 10, noNaN: true });
const length = fc.double({ min: 0.1, max: 2, noNaN: true });
const unit = fc.integer({ min: 0, max: 2 ** 24 - 1 }).map((i) => i / 2 ** 24);

function scaleArgument(value: Argument, dimension: Dimension, k: number): Argument {
  const factor = dimension === 1 ? k : dimension === -1 ? 1 / k : 1;
  return typeof value === 'number' ? value * factor : value.map((v) => v * factor);
}

function describeInvariance(table: InvarianceTable, index: number): void {
  it(`${table.name}: f(kσ, d/k) = k^p f(σ, d) on the GPU`, async () => {
    const bases = fc.sample(table.base, { numRuns: BASE_CASES, seed: 2026 + index });
    const cases = bases.flatMap((base, b) =>
      EXPONENTS.map((e) => ({
        name: `base ${b}, k = 1e${e}`,
        args: base.map((value, a) => scaleArgument(value, table.dimensions[a] ?? 0, 10 ** e)),
      })),
    );
    const outcomes = await evaluateTable({
      module: table.module,
      fn: table.fn,
      args: table.args,
      result: table.result,
      twin: table.twin,
      wrapper: table.wrapper,
      tolerance: { relative: RELATIVE, reason: 'unit invariance' },
      cases,
    });
    const unscaled = EXPONENTS.indexOf(0);
    bases.forEach((base, b) => {
      const reference = outcomes[b * EXPONENTS.length + unscaled]?.gpu ?? [];
      EXPONENTS.forEach((e, i) => {
        const gpu = outcomes[b * EXPONENTS.length + i]?.gpu ?? [];
        const k = 10 ** e;
        gpu.forEach((value, c) => {
          const label = `${table.name}, base ${JSON.stringify(base)}, k = 1e${e}, component ${c}`;
          expect(Number.isFinite(value), `${label}: ${value} is finite`).toBe(true);
          const kToP = k ** (table.resultDimensions[c] ?? 0);
          const expected = (reference[c] ?? NaN) * kToP;
          // 1e-3·F32_MAX: a profile's intermediate terms are up to 4π/α' times the result,
          // and they saturate first.
          if (
            Math.abs(expected) > 1e-3 * F32_MAX ||
            (expected !== 0 && Math.abs(expected) < F32_MIN_NORMAL * 1e6)
          )
            return;
          const tolerance = RELATIVE * Math.abs(expected) + 1e-7 * kToP;
          expect(
            Math.abs(value - expected) <= tolerance,
            `${label}: GPU ${value} vs k^p·GPU(k = 1) = ${expected}`,
          ).toBe(true);
        });
      });
    });
  }, 120_000);
}

const MEDIUM_DIMENSIONS: Dimension[] = [0, 1, 0, 1, 0, -1, 0, 1];
/** A Medium1D as the eight harness arguments: homogeneous, sine or grid. */
const medium = fc.oneof(
  coefficient.map((s): Argument[] => [0, s, 0, 0, 0, 0, 0, Array(16).fill(0)]),
  fc
    .tuple(coefficient, unit, coefficient, unit)
    .map(([s, a, f, p]): Argument[] => [1, s, a, f, 6 * p, 0, 0, Array(16).fill(0)]),
  fc
    .tuple(
      fc.array(coefficient, { minLength: 16, maxLength: 16 }),
      fc.integer({ min: 1, max: 16 }),
      length,
    )
    .map(([cells, n, h]): Argument[] => [2, 0, 0, 0, 0, h / 4, n, cells]),
);

const DIPOLE_PARAMETERS = {
  imports: ['dipoleParameters'],
  wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32) -> vec4f {
  let p = dipoleParameters(sp, sa, eta);
  return vec4f(p.albedoPrime, p.sigmaTPrime, p.sigmaTr, p.zr);
}`,
};
const DIPOLE_TOTALS = {
  imports: [
    'dipoleParameters',
    'dipoleTotalReflectance',
    'dipoleReflectanceBeyond',
    'dipoleProfile',
  ],
  wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32, r: f32) -> vec4f {
  let p = dipoleParameters(sp, sa, eta);
  return vec4f(dipoleTotalReflectance(p), dipoleReflectanceBeyond(p, r), dipoleProfile(p, r), p.zv);
}`,
};
const BETTER_DIPOLE = {
  imports: ['betterDipoleParameters', 'betterDipoleTotalReflectance', 'betterDipoleProfile'],
  wgsl: `fn caseUnderTest(sp: f32, sa: f32, eta: f32, r: f32) -> vec4f {
  let p = betterDipoleParameters(sp, sa, eta);
  return vec4f(p.albedoPrime, p.diffusion, betterDipoleTotalReflectance(p), betterDipoleProfile(p, r));
}`,
};

const TABLES: InvarianceTable[] = [
  {
    name: 'opticalThicknessHomogeneous',
    module: 'transmittance',
    fn: 'opticalThicknessHomogeneous',
    args: ['f32', 'f32'],
    result: 'f32',
    twin: opticalThicknessHomogeneous,
    dimensions: [1, -1],
    resultDimensions: [0],
    base: fc.tuple(coefficient, length),
  },
  {
    name: 'transmittanceHomogeneous',
    module: 'transmittance',
    fn: 'transmittanceHomogeneous',
    args: ['f32', 'f32'],
    result: 'f32',
    twin: transmittanceHomogeneous,
    dimensions: [1, -1],
    resultDimensions: [0],
    base: fc.tuple(coefficient, length),
  },
  {
    name: 'opticalThicknessSine',
    module: 'transmittance',
    fn: 'opticalThicknessSine',
    args: ['f32', 'f32', 'f32', 'f32', 'f32', 'f32'],
    result: 'f32',
    twin: opticalThicknessSine,
    dimensions: [1, 0, 1, 0, -1, -1],
    resultDimensions: [0],
    base: fc
      .tuple(coefficient, unit, coefficient, unit, length, length)
      .map(([s, a, f, p, s0, span]) => [s, a, f, 6 * p, s0, s0 + span]),
  },
  {
    name: 'opticalThicknessGrid1D',
    module: 'transmittance',
    fn: 'opticalThicknessGrid1D',
    args: ['f32[16]', 'u32', 'f32', 'f32', 'f32'],
    result: 'f32',
    twin: opticalThicknessGrid1D as never,
    dimensions: [1, 0, -1, -1, -1],
    resultDimensions: [0],
    // Cell edges on a grid of h/4 and segment ends away from them, so that no sliver of a
    // cell comes from a difference of nearly equal lengths.
    base: fc
      .tuple(
        fc.array(coefficient, { minLength: 16, maxLength: 16 }),
        fc.integer({ min: 1, max: 16 }),
        length,
        fc.integer({ min: 0, max: 20 }),
        fc.integer({ min: 1, max: 40 }),
      )
      .map(([cells, n, h, i0, m]) => [
        cells,
        n,
        h,
        (h * (i0 + 0.37)) / 4,
        (h * (i0 + m + 0.61)) / 4,
      ]),
  },
  {
    name: 'mediumExtinction, mediumOpticalDepth, mediumMajorant',
    module: 'medium',
    fn: 'mediumExtinction',
    args: [...MEDIUM_ARGUMENTS, 'f32', 'f32'],
    result: 'vec3f',
    wrapper: {
      imports: ['mediumExtinction', 'mediumOpticalDepth', 'mediumMajorant'],
      wgsl: `fn caseUnderTest(${MEDIUM_PARAMETERS}, s0: f32, s1: f32) -> vec3f {
  let medium = ${MEDIUM_VALUE};
  return vec3f(mediumExtinction(medium, s0), mediumOpticalDepth(medium, s0, s1), mediumMajorant(medium, s0, s1));
}`,
    },
    twin: ((...args: Argument[]) => {
      const m = mediumFromArguments(args);
      const s0 = args[8] as number;
      const s1 = args[9] as number;
      return [mediumExtinction(m, s0), mediumOpticalDepth(m, s0, s1), mediumMajorant(m, s0, s1)];
    }) as never,
    dimensions: [...MEDIUM_DIMENSIONS, -1, -1],
    resultDimensions: [1, 0, 1],
    base: fc
      .tuple(medium, length, length)
      .map(([m, s0, span]) => [...m, s0 + 0.013, s0 + 0.013 + span]),
  },
  {
    name: 'shadowTransmittanceExact',
    module: 'scatter',
    fn: 'shadowTransmittanceExact',
    args: ['f32', 'f32', 'f32', 'f32'],
    result: 'f32',
    twin: shadowTransmittanceExact,
    dimensions: [1, -1, 0, -1],
    resultDimensions: [0],
    base: fc.tuple(coefficient, length, unit, length),
  },
  {
    name: 'singleScatterHomogeneousSlab',
    module: 'scatter',
    fn: 'singleScatterHomogeneousSlab',
    args: ['f32', 'f32', 'f32', 'f32', 'f32', 'f32', 'f32'],
    result: 'f32',
    twin: singleScatterHomogeneousSlab,
    dimensions: [1, 1, 0, 0, -1, 0, -1],
    resultDimensions: [0],
    base: fc
      .tuple(coefficient, coefficient, unit, length, unit, length)
      .map(([s, a, b, L, p, x]) => [s, a, 0.05 + p, 3, x / 10, b, L]),
  },
  {
    name: 'equiangularSample (t, pdf)',
    module: 'scatter',
    fn: 'equiangularSample',
    args: ['f32', 'f32', 'f32', 'f32'],
    result: 'vec2f',
    twin: equiangularSample as never,
    dimensions: [-1, 0, 0, 0],
    resultDimensions: [-1, 1],
    base: fc
      .tuple(length, unit, unit, unit)
      .map(([h, u0, u1, xi]) => [h, -1.4 + 1.4 * u0, 0.1 + 1.3 * u1, xi]),
  },
  {
    name: 'equiangularPdf',
    module: 'scatter',
    fn: 'equiangularPdf',
    args: ['f32', 'f32', 'f32', 'f32'],
    result: 'f32',
    twin: equiangularPdf,
    dimensions: [-1, 0, 0, -1],
    resultDimensions: [1],
    base: fc
      .tuple(length, unit, unit, length)
      .map(([h, u0, u1, t]) => [h, -1.4 + 1.4 * u0, 0.1 + 1.3 * u1, t - 1]),
  },
  {
    name: 'linearEmission',
    module: 'raymarch',
    fn: 'linearEmission',
    args: ['f32', 'f32', 'f32'],
    result: 'f32',
    twin: linearEmission,
    dimensions: [0, 1, -1],
    resultDimensions: [0],
    base: fc.tuple(coefficient, coefficient, length).map(([e0, e1, t]) => [e0, e1 - 5, t]),
  },
  {
    name: 'raymarchEmissionAbsorption, raymarchOpticalDepth and singleScatterMarched (midpoint)',
    module: 'raymarch',
    fn: 'raymarchEmissionAbsorption',
    args: [...MEDIUM_ARGUMENTS, 'f32', 'f32', 'u32'],
    result: 'vec4f',
    wrapper: {
      imports: ['raymarchEmissionAbsorption', 'raymarchOpticalDepth'],
      wgsl: `fn caseUnderTest(${MEDIUM_PARAMETERS}, slope: f32, d: f32, steps: u32) -> vec4f {
  let medium = ${MEDIUM_VALUE};
  var state = 7u;
  let march = raymarchEmissionAbsorption(medium, 1.0, slope, 0.3, 0.5, d, steps, 1u, &state);
  let tau = raymarchOpticalDepth(medium, d, steps, 1u, &state);
  let single = package::scatter::singleScatterMarched(medium, 0.7, 0.2, 3.0, d, 0.5, d, steps, 1u, &state);
  return vec4f(march.radiance, march.transmittance, tau, single.radiance);
}`,
    },
    twin: ((...args: Argument[]) => {
      const m = mediumFromArguments(args);
      const [slope, d, steps] = args.slice(8) as [number, number, number];
      const march = raymarchEmissionAbsorption(m, 1, slope, 0.3, 0.5, d, steps, MARCH_MIDPOINT, {
        value: 7,
      });
      const tau = raymarchOpticalDepth(m, d, steps, MARCH_MIDPOINT, { value: 7 });
      const single = singleScatterMarched(m, 0.7, 0.2, 3, d, 0.5, d, steps, MARCH_MIDPOINT, {
        value: 7,
      });
      return [march.radiance, march.transmittance, tau, single.radiance];
    }) as never,
    dimensions: [...MEDIUM_DIMENSIONS, 1, -1, 0],
    resultDimensions: [0, 0, 0, 0],
    base: fc
      .tuple(medium, coefficient, length, fc.integer({ min: 1, max: 32 }))
      .map(([m, slope, d, steps]) => [...m, slope - 5, d, steps]),
  },
  {
    name: 'sampleFreeFlight',
    module: 'tracking',
    fn: 'sampleFreeFlight',
    args: ['f32', 'f32'],
    result: 'f32',
    twin: sampleFreeFlight,
    dimensions: [1, 0],
    resultDimensions: [-1],
    base: fc.tuple(coefficient, unit),
  },
  {
    name: 'nullCollisionWeight',
    module: 'tracking',
    fn: 'nullCollisionWeight',
    args: ['f32', 'f32'],
    result: 'f32',
    twin: nullCollisionWeight,
    dimensions: [1, 1],
    resultDimensions: [0],
    base: fc.tuple(coefficient, coefficient),
  },
  {
    name: 'transmittanceTrackLength',
    module: 'tracking',
    fn: 'transmittanceTrackLength',
    args: ['f32', 'f32', 'f32'],
    result: 'f32',
    twin: transmittanceTrackLength,
    dimensions: [1, -1, 0],
    resultDimensions: [0],
    // Keep the free flight −ln(1 − ξ)/σ away from d, where f32 rounding of the scaled inputs
    // could flip the comparison: ξ from the 24-bit grid, d at 0.4 or 2.5 mean free paths.
    base: fc
      .tuple(coefficient, unit, fc.boolean())
      .map(([s, xi, far]) => [s, (far ? 2.5 : 0.4) / s + 1e-3 / s, xi]),
  },
  {
    name: 'sampleTruncatedExponential',
    module: 'integrator',
    fn: 'sampleTruncatedExponential',
    args: ['f32', 'f32', 'f32'],
    result: 'f32',
    twin: sampleTruncatedExponential,
    dimensions: [1, -1, 0],
    resultDimensions: [-1],
    base: fc.tuple(coefficient, length, unit),
  },
  {
    name: 'truncatedExponentialPdf',
    module: 'integrator',
    fn: 'truncatedExponentialPdf',
    args: ['f32', 'f32', 'f32'],
    result: 'f32',
    twin: truncatedExponentialPdf,
    dimensions: [1, -1, -1],
    resultDimensions: [1],
    base: fc.tuple(coefficient, length, unit).map(([k, L, u]) => [k, L, u * L]),
  },
  {
    name: 'transmittanceBeer',
    module: 'integrator',
    fn: 'transmittanceBeer',
    args: ['f32', 'f32', 'f32', 'f32'],
    result: 'vec3f',
    wrapper: {
      imports: ['transmittanceBeer'],
      wgsl: 'fn caseUnderTest(r: f32, g: f32, b: f32, d: f32) -> vec3f { return transmittanceBeer(vec3f(r, g, b), d); }',
    },
    twin: ((r: number, g: number, b: number, d: number) =>
      transmittanceBeer([r, g, b], d)) as never,
    dimensions: [1, 1, 1, -1],
    resultDimensions: [0, 0, 0],
    base: fc.tuple(coefficient, coefficient, coefficient, length),
  },
  {
    name: "dipoleParameters (α', σt', σtr, z_r)",
    module: 'dipole',
    fn: 'dipoleParameters',
    args: ['f32', 'f32', 'f32'],
    result: 'vec4f',
    wrapper: DIPOLE_PARAMETERS,
    twin: ((sp: number, sa: number, eta: number) => {
      const p = dipoleParameters(sp, sa, eta);
      return [p.albedoPrime, p.sigmaTPrime, p.sigmaTr, p.zr];
    }) as never,
    dimensions: [1, 1, 0],
    resultDimensions: [0, 1, 1, -1],
    base: fc.tuple(coefficient, coefficient, unit).map(([sp, sa, u]) => [sp, sa / 10, 1 + u]),
  },
  {
    name: 'dipole totals, tail beyond r, R_d(r) (1/m²) and z_v',
    module: 'dipole',
    fn: 'dipoleTotalReflectance',
    args: ['f32', 'f32', 'f32', 'f32'],
    result: 'vec4f',
    wrapper: DIPOLE_TOTALS,
    twin: ((sp: number, sa: number, eta: number, r: number) => {
      const p = dipoleParameters(sp, sa, eta);
      return [dipoleTotalReflectance(p), dipoleReflectanceBeyond(p, r), dipoleProfile(p, r), p.zv];
    }) as never,
    dimensions: [1, 1, 0, -1],
    resultDimensions: [0, 0, 2, -1],
    base: fc
      .tuple(coefficient, coefficient, unit, length)
      .map(([sp, sa, u, r]) => [sp, sa / 10, 1 + u, r / 5]),
  },
  {
    name: 'dipoleSourceTerm (1/m²)',
    module: 'dipole',
    fn: 'dipoleSourceTerm',
    args: ['f32', 'f32', 'f32'],
    result: 'f32',
    twin: dipoleSourceTerm,
    dimensions: [-1, 1, -1],
    resultDimensions: [2],
    base: fc.tuple(length, coefficient, length),
  },
  {
    name: 'exponentialDifferenceOverRate (m)',
    module: 'dipole',
    fn: 'exponentialDifferenceOverRate',
    args: ['f32', 'f32', 'f32'],
    result: 'f32',
    twin: exponentialDifferenceOverRate,
    dimensions: [1, -1, -1],
    resultDimensions: [-1],
    base: fc.tuple(coefficient, length, length).map(([s, a, span]) => [s / 4, a, a + span]),
  },
  {
    name: "betterDipole (α', D, total, R(r))",
    module: 'dipole',
    fn: 'betterDipoleParameters',
    args: ['f32', 'f32', 'f32', 'f32'],
    result: 'vec4f',
    wrapper: BETTER_DIPOLE,
    twin: ((sp: number, sa: number, eta: number, r: number) => {
      const p = betterDipoleParameters(sp, sa, eta);
      return [
        p.albedoPrime,
        p.diffusion,
        betterDipoleTotalReflectance(p),
        betterDipoleProfile(p, r),
      ];
    }) as never,
    dimensions: [1, 1, 0, -1],
    resultDimensions: [0, -1, 0, 2],
    base: fc
      .tuple(coefficient, coefficient, unit, length)
      .map(([sp, sa, u, r]) => [sp, sa / 10, 1 + u, r / 5]),
  },
  {
    name: 'burleyProfile (1/m²)',
    module: 'dipole',
    fn: 'burleyProfile',
    args: ['f32', 'f32', 'f32'],
    result: 'f32',
    twin: burleyProfile,
    dimensions: [0, -1, -1],
    resultDimensions: [2],
    base: fc.tuple(unit, length, length),
  },
  {
    name: 'burleyRadialDensity (1/m)',
    module: 'dipole',
    fn: 'burleyRadialDensity',
    args: ['f32', 'f32', 'f32'],
    result: 'f32',
    twin: burleyRadialDensity,
    dimensions: [0, -1, -1],
    resultDimensions: [1],
    base: fc.tuple(unit, length, length),
  },
  {
    name: 'burleyRadialCdf',
    module: 'dipole',
    fn: 'burleyRadialCdf',
    args: ['f32', 'f32'],
    result: 'f32',
    twin: burleyRadialCdf,
    dimensions: [-1, -1],
    resultDimensions: [0],
    base: fc.tuple(length, length),
  },
];

describe('unit invariance of the WGSL library (Dawn; σ → kσ, lengths → ·/k, k = 10^-30 … 10^30)', () => {
  TABLES.forEach((table, index) => describeInvariance(table, index));
});
