// The float64 twins of shaders/dipole.wesl and shaders/fresnel.wesl against physics.md
// §6: the F_dr table (fit, exact internal, exact external), the derived table of all
// twelve Jensen et al. 2001 materials at its printed digits, the Skimmilk R profile,
// the better dipole and Christensen–Burley values; then the analytic facts behind
// them: each closed-form total equals the radial integral of its profile, the tail
// formula equals the integral beyond R, Burley integrates to A, and unit changes
// scale the profile by the square of the length unit.
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  betterDipoleParameters,
  betterDipoleProfile,
  betterDipoleTotalReflectance,
  burleyProfile,
  burleyRadialCdf,
  burleyRadialDensity,
  burleyShapeSearchlight,
  dipoleParameters,
  dipoleProfile,
  dipoleReflectanceBeyond,
  dipoleTotalReflectance,
  fresnelDiffuseReflectanceFit,
} from '../../src/reference/dipole.ts';
import {
  adaptiveSimpson,
  fresnelDiffuseReflectanceExact,
  fresnelDiffuseReflectanceExternal,
  fresnelMoment,
} from '../../src/reference/fresnel.ts';
import {
  findMaterial,
  JENSEN_2001_MATERIALS,
  materialInUnit,
} from '../../src/subsurface/materials.ts';
import {
  BURLEY_CDF_16D,
  BURLEY_MEDIAN_R_OVER_D,
  CHANNEL_NAMES,
  DERIVED_DIPOLE_TABLE,
  FDR_TABLE,
  MOMENTS_AT_1_3,
  rowInputs,
  SKIMMILK_R_BETTER,
  SKIMMILK_R_PROFILE,
} from '../support/subsurfaceTables.ts';

/**
 * Half a unit in the last printed place of a table entry: the tables print six
 * significant digits or six decimals, whichever is coarser (physics.md §6.1).
 */
function printedTolerance(value: number): number {
  const sixSignificant =
    value === 0 ? 0 : 0.5 * 10 ** (Math.floor(Math.log10(Math.abs(value))) - 5);
  return Math.max(sixSignificant, 5e-7) * 1.0001;
}

function expectPrinted(actual: number, printed: number, what: string): void {
  expect(
    Math.abs(actual - printed),
    `${what}: ${actual} vs printed ${printed}`,
  ).toBeLessThanOrEqual(printedTolerance(printed));
}

/** ∫₀^∞ f(r) 2πr dr in r = z·t/(1 − t), t ∈ [0, 1), which maps the slow tail to a finite interval. */
function radialIntegral(f: (r: number) => number, scale: number): number {
  return adaptiveSimpson(
    (t) => {
      if (t >= 1) return 0;
      const r = (scale * t) / (1 - t);
      return f(r) * 2 * Math.PI * r * (scale / (1 - t) ** 2);
    },
    0,
    1,
    1e-12,
    50,
  );
}

describe('Fresnel diffuse reflectance (physics.md §6.1 table)', () => {
  for (const [eta, fit, internal, external] of FDR_TABLE) {
    it(`η = ${eta}: fit ${fit}, exact internal ${internal}, exact external ${external}`, () => {
      expectPrinted(fresnelDiffuseReflectanceFit(eta), fit, 'fit');
      expectPrinted(fresnelDiffuseReflectanceExact(eta), internal, 'exact internal');
      expectPrinted(fresnelDiffuseReflectanceExternal(eta), external, 'exact external');
    });
  }
  it('the internal moments at η = 1.3 give the better dipole’s A = 2.340532 (§6.2)', () => {
    const c1 = fresnelMoment(1.3, 1);
    const c2 = fresnelMoment(1.3, 2);
    expectPrinted(c1, MOMENTS_AT_1_3.c1, 'C₁');
    expectPrinted(c2, MOMENTS_AT_1_3.c2, 'C₂');
    expectPrinted((1 + 3 * c2) / (1 - 2 * c1), MOMENTS_AT_1_3.boundaryA, 'A');
  });
  it('η < 1: internal reflectance of η is the external one of 1/η (no total reflection)', () => {
    expect(fresnelDiffuseReflectanceExact(1 / 1.3)).toBeCloseTo(0.061132, 6);
    // pbrt-v2's η < 1 branch approximates it: 0.06179 (physics.md §6.1).
    expect(fresnelDiffuseReflectanceFit(1 / 1.3)).toBeCloseTo(0.06179, 5);
  });
});

describe('derived dipole quantities of the Jensen et al. 2001 materials (physics.md §6.1)', () => {
  for (const row of DERIVED_DIPOLE_TABLE) {
    it(`${row.material} ${CHANNEL_NAMES[row.channel]}: σt′, α′, σtr, z_r, z_v, total, R_d(0)`, () => {
      const p = dipoleParameters(...rowInputs(row));
      expectPrinted(p.sigmaTPrime, row.sigmaTPrime, 'σt′');
      expectPrinted(p.albedoPrime, row.albedoPrime, 'α′');
      expectPrinted(p.sigmaTr, row.sigmaTr, 'σtr');
      expectPrinted(p.zr, row.zr, 'z_r');
      expectPrinted(p.zv, row.zv, 'z_v');
      expectPrinted(dipoleTotalReflectance(p), row.total, 'total R_d');
      expectPrinted(dipoleProfile(p, 0), row.atZero, 'R_d(0)');
    });
  }
  it('every material of the table is a preset, with η = 1.3 except marble (1.5)', () => {
    expect(JENSEN_2001_MATERIALS.map((m) => m.name)).toEqual([
      ...new Set(DERIVED_DIPOLE_TABLE.map((r) => r.material)),
    ]);
    for (const m of JENSEN_2001_MATERIALS) expect(m.eta).toBe(m.name === 'marble' ? 1.5 : 1.3);
  });
});

describe('profiles against their totals (physics.md §6.1–6.3)', () => {
  it('Skimmilk R profile samples (§6.1)', () => {
    const p = dipoleParameters(0.7, 0.0014, 1.3);
    for (const [r, value] of SKIMMILK_R_PROFILE)
      expect(dipoleProfile(p, r) / value - 1, `r = ${r}`).toBeLessThan(5e-9);
  });

  it('the classic dipole’s closed-form total equals ∫R_d 2πr dr to 1e-10 (§6.1), for every material channel', () => {
    for (const row of DERIVED_DIPOLE_TABLE) {
      const p = dipoleParameters(...rowInputs(row));
      const integral = radialIntegral((r) => dipoleProfile(p, r), p.zv);
      expect(Math.abs(integral - dipoleTotalReflectance(p)), `${row.material}`).toBeLessThan(1e-9);
      // And the σtr·z form of the shader: (α′/2)(e^{−σtr z_r} + e^{−σtr z_v}).
      const sourceForm =
        (p.albedoPrime / 2) * (Math.exp(-p.sigmaTr * p.zr) + Math.exp(-p.sigmaTr * p.zv));
      expect(sourceForm).toBeCloseTo(dipoleTotalReflectance(p), 12);
    }
  });

  it('the tail beyond R equals ∫_R^∞ R_d 2πr dr; Spectralon R loses 2.36% beyond 10 mm (§9 row 21)', () => {
    const spectralon = dipoleParameters(11.6, 0, 1.3);
    expect(dipoleReflectanceBeyond(spectralon, 10)).toBeCloseTo(0.0236, 4);
    expect(dipoleReflectanceBeyond(spectralon, 1)).toBeCloseTo(0.223, 3);
    for (const [sp, sa, eta, R] of [
      [0.7, 0.0014, 1.3, 3],
      [1.01, 0.48, 1.3, 0.5],
      [11.6, 0, 1.3, 10],
    ] as const) {
      const p = dipoleParameters(sp, sa, eta);
      const tail = adaptiveSimpson(
        (t) => {
          if (t >= 1) return 0;
          const r = R + (p.zv * t) / (1 - t);
          return dipoleProfile(p, r) * 2 * Math.PI * r * (p.zv / (1 - t) ** 2);
        },
        0,
        1,
        1e-13,
        50,
      );
      expect(dipoleReflectanceBeyond(p, R)).toBeCloseTo(tail, 9);
    }
  });

  it('the better dipole: Skimmilk R profile and total (§6.2), and its total is ∫R 2πr dr', () => {
    const p = betterDipoleParameters(0.7, 0.0014, 1.3);
    for (const [r, value] of SKIMMILK_R_BETTER.profile)
      expect(Math.abs(betterDipoleProfile(p, r) / value - 1), `r = ${r}`).toBeLessThan(4e-7);
    expect(betterDipoleTotalReflectance(p)).toBeCloseTo(SKIMMILK_R_BETTER.total, 8);
    for (const [sp, sa, eta] of [
      [0.7, 0.0014, 1.3],
      [1.01, 0.48, 1.3],
      [0.03, 1.45, 1.3],
      [2.62, 0.0041, 1.5],
    ] as const) {
      const q = betterDipoleParameters(sp, sa, eta);
      const integral = radialIntegral((r) => betterDipoleProfile(q, r), Math.abs(q.zv));
      expect(integral).toBeCloseTo(betterDipoleTotalReflectance(q), 9);
    }
  });

  it('at α′ = 1 both dipoles reflect everything (§9 row 21)', () => {
    expect(dipoleTotalReflectance(dipoleParameters(11.6, 0, 1.3))).toBe(1);
    expect(betterDipoleTotalReflectance(betterDipoleParameters(11.6, 0, 1.3))).toBeCloseTo(1, 14);
    expect(betterDipoleTotalReflectance(betterDipoleParameters(3, 0, 1.5))).toBeCloseTo(1, 14);
  });

  it('Christensen–Burley integrates to A, has the published CDF at 16d and median 1.55218326·d (§6.3)', () => {
    for (const [A, d] of [
      [0.8, 1],
      [0.3, 0.2],
    ] as const) {
      const integral = adaptiveSimpson(
        (t) => {
          if (t >= 1) return 0;
          const r = (d * t) / (1 - t);
          return burleyRadialDensity(A, d, r) * (d / (1 - t) ** 2);
        },
        0,
        1,
        1e-13,
        50,
      );
      expect(integral).toBeCloseTo(A, 10);
      expect(burleyProfile(A, d, 0.7) * 2 * Math.PI * 0.7).toBeCloseTo(
        burleyRadialDensity(A, d, 0.7),
        14,
      );
    }
    expect(burleyRadialCdf(16, 1)).toBeCloseTo(BURLEY_CDF_16D, 15);
    expect(burleyRadialCdf(BURLEY_MEDIAN_R_OVER_D, 1)).toBeCloseTo(0.5, 8);
    expect(burleyRadialDensity(0.8, 2, 0)).toBe(0.2);
    expect(burleyShapeSearchlight(0.8)).toBeCloseTo(1.05, 14);
  });
});

describe('units (physics.md §6.1 hazards)', () => {
  it('the same skin in metres: σ × 1000, r ÷ 1000, R_d(r) × 10⁶, totals unchanged', () => {
    const skin = findMaterial('skin1')!;
    const inMetres = materialInUnit(skin, 1000);
    for (let c = 0; c < 3; c++) {
      const mm = dipoleParameters(skin.sigmaSPrime[c]!, skin.sigmaA[c]!, skin.eta);
      const m = dipoleParameters(inMetres.sigmaSPrime[c]!, inMetres.sigmaA[c]!, inMetres.eta);
      for (const r of [0, 0.5, 4])
        expect(dipoleProfile(m, r / 1000) / (dipoleProfile(mm, r) * 1e6)).toBeCloseTo(1, 12);
      expect(dipoleTotalReflectance(m)).toBeCloseTo(dipoleTotalReflectance(mm), 14);
      expect(m.zr * 1000).toBeCloseTo(mm.zr, 12);
    }
  });
});

describe('properties for all media', () => {
  const medium = fc.record({
    sp: fc.double({ min: 1e-3, max: 50, noNaN: true }),
    sa: fc.double({ min: 0, max: 5, noNaN: true }),
    eta: fc.double({ min: 1, max: 2, noNaN: true }),
  });
  it('R_d(r) ≥ 0 and decreasing in r; totals in [0, 1]; the better dipole total too', () => {
    fc.assert(
      fc.property(medium, fc.double({ min: 0, max: 100, noNaN: true }), ({ sp, sa, eta }, r) => {
        const p = dipoleParameters(sp, sa, eta);
        const a = dipoleProfile(p, r);
        const b = dipoleProfile(p, r * 1.1 + 1e-6);
        const total = dipoleTotalReflectance(p);
        const better = betterDipoleTotalReflectance(betterDipoleParameters(sp, sa, eta));
        return a >= 0 && b <= a && total >= 0 && total <= 1 && better >= 0 && better <= 1 + 1e-12;
      }),
    );
  });
  it('the total depends on the medium only through α′ and η (scaling σs′ and σa together)', () => {
    fc.assert(
      fc.property(medium, fc.double({ min: 0.01, max: 100, noNaN: true }), ({ sp, sa, eta }, k) => {
        const a = dipoleTotalReflectance(dipoleParameters(sp, sa, eta));
        const b = dipoleTotalReflectance(dipoleParameters(sp * k, sa * k, eta));
        return Math.abs(a - b) < 1e-12;
      }),
    );
  });
});
