// Issue 20: physics does not depend on the unit of length. Multiplying every coefficient
// (1/m) by k and dividing every length (m) by k must leave a dimensionless result unchanged
// and multiply a result of dimension m^-p by k^p. This file checks that law on the float64
// twins for k = 10^-30 … 10^30 with fast-check, for every library function of coefficients
// and lengths; tests/stability/unit-invariance-gpu.test.ts checks the WGSL library.
//
// A separately clamped factor (σ and d each clamped to 1e18, σs' and σa each to 1e9, radii to
// 1e15, Burley lengths to [1e-9, 1e9], a 1e-30 m threshold) breaks the law at some k in this
// range, which is what these properties catch. Base inputs are moderate (coefficients and
// lengths in [1e-3, 1e3]) so that every scaled input is a normal f32, inside the documented
// domains; a dimensioned result is compared only where k^p·f stays inside the f32 range,
// because beyond it the documented convention is saturation at the largest f32.
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
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
  gridMedium,
  homogeneousMedium,
  type Medium1D,
  mediumExtinction,
  mediumMajorant,
  mediumOpticalDepth,
  sineMedium,
} from '../../src/reference/medium.ts';
import {
  linearEmission,
  MARCH_JITTERED_RAY,
  MARCH_MIDPOINT,
  raymarchEmissionAbsorption,
  raymarchEmissionRiemann,
  raymarchLinearized,
  raymarchOpticalDepth,
} from '../../src/reference/raymarch.ts';
import { rngSeed } from '../../src/reference/rng.ts';
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
  transmittanceDeltaTracking,
  transmittanceRatioTracking,
  transmittanceResidualRatioTracking,
  transmittanceTrackLength,
  transmittanceUnbiasedRayMarching,
} from '../../src/reference/tracking.ts';
import {
  opticalThicknessGrid1D,
  opticalThicknessHomogeneous,
  opticalThicknessSine,
  transmittanceHomogeneous,
} from '../../src/reference/transmittance.ts';
import { F32_MAX, F32_MIN_NORMAL } from '../support/f32.ts';

/** The unit factor k = 10^e, e an integer in [−30, 30]. */
const unitFactor = fc.integer({ min: -30, max: 30 }).map((e) => 10 ** e);
const coefficient = fc.double({ min: 1e-3, max: 1e3, noNaN: true });
const length = fc.double({ min: 1e-3, max: 1e3, noNaN: true });
/** A random number as the library draws it: 24 bits, a multiple of 2^-24 in [0, 1). */
const unit = fc.integer({ min: 0, max: 2 ** 24 - 1 }).map((i) => i / 2 ** 24);
const eta = fc.double({ min: 1, max: 2, noNaN: true });
const RUNS = { numRuns: 300, seed: 20261202, endOnFailure: true };

/**
 * float64 rounding of the scaled inputs (σ·k, d/k are each rounded once) moves τ by a few
 * 1e-16 relatively, and exp(−τ) by τ times that; 1e-9 relative is far above that and far
 * below any effect of a clamp.
 */
const RELATIVE = 1e-9;

/**
 * f(scaled) against k^p·f(base), where k^p·f(base) is a representable f32 result. `magnitude`
 * is the size of the terms the result is a difference or partial sum of (e.g. a cell's σ times
 * the segment length when only a sliver of a cell is covered); the tolerance is relative to it.
 */
function expectScaled(
  scaled: number,
  base: number,
  kToP: number,
  label: string,
  magnitude = 0,
  relative = RELATIVE,
): void {
  expect(Number.isFinite(scaled), `${label}: ${scaled} is finite`).toBe(true);
  const expected = base * kToP;
  if (
    Math.abs(expected) > F32_MAX / 4 ||
    (expected !== 0 && Math.abs(expected) < F32_MIN_NORMAL * 1e6)
  ) {
    // Outside the f32 range of the result: the documented convention is saturation, never
    // NaN or Inf, and the sign is kept.
    expect(scaled >= 0 === expected >= 0, `${label}: sign`).toBe(true);
    return;
  }
  const tolerance = relative * Math.max(Math.abs(expected), magnitude * Math.abs(kToP)) + 1e-300;
  expect(
    Math.abs(scaled - expected) <= tolerance,
    `${label}: ${scaled} vs k^p·f = ${expected} (base ${base}, k^p ${kToP})`,
  ).toBe(true);
}

/** The same medium in units k times smaller: coefficients × k, lengths / k. */
function scaleMedium(medium: Medium1D, k: number): Medium1D {
  return {
    ...medium,
    sigma0: medium.sigma0 * k,
    frequency: medium.frequency * k,
    cellSize: medium.cellSize / k,
    cells: medium.cells.map((c) => c * k),
  };
}

const medium1D: fc.Arbitrary<Medium1D> = fc.oneof(
  coefficient.map((s) => homogeneousMedium(s)),
  fc
    .tuple(coefficient, fc.double({ min: 0, max: 1, noNaN: true }), coefficient, unit)
    .map(([s, a, f, p]) => sineMedium(s, a, f, 6 * p)),
  fc
    .tuple(fc.array(coefficient, { minLength: 1, maxLength: 16 }), length)
    .map(([cells, h]) => gridMedium(cells, h)),
);

describe('unit invariance of the float64 twins (σ → kσ, lengths → ·/k, k = 10^-30 … 10^30)', () => {
  it('transmittance: opticalThicknessHomogeneous, transmittanceHomogeneous, transmittanceBeer', () => {
    fc.assert(
      fc.property(coefficient, length, unitFactor, (s, d, k) => {
        expectScaled(
          opticalThicknessHomogeneous(s * k, d / k),
          opticalThicknessHomogeneous(s, d),
          1,
          'τ',
        );
        expectScaled(
          transmittanceHomogeneous(s * k, d / k),
          transmittanceHomogeneous(s, d),
          1,
          'T',
        );
        const rgb = transmittanceBeer([s * k, 2 * s * k, 0.5 * s * k], d / k);
        transmittanceBeer([s, 2 * s, 0.5 * s], d).forEach((value, c) =>
          expectScaled(rgb[c]!, value, 1, `Beer channel ${c}`),
        );
      }),
      RUNS,
    );
  });

  it('transmittance: opticalThicknessSine and opticalThicknessGrid1D', () => {
    fc.assert(
      fc.property(
        coefficient,
        unit,
        coefficient,
        unit,
        length,
        length,
        unitFactor,
        (s, a, f, p, s0, span, k) => {
          const base = opticalThicknessSine(s, a, f, 6 * p, s0, s0 + span);
          expectScaled(
            opticalThicknessSine(s * k, a, f * k, 6 * p, s0 / k, (s0 + span) / k),
            base,
            1,
            'sine τ',
          );
        },
      ),
      RUNS,
    );
    fc.assert(
      fc.property(
        fc.array(coefficient, { minLength: 1, maxLength: 16 }),
        length,
        length,
        length,
        unitFactor,
        (cells, h, s0, span, k) => {
          const base = opticalThicknessGrid1D(cells, cells.length, h, s0, s0 + span);
          const scaled = opticalThicknessGrid1D(
            cells.map((c) => c * k),
            cells.length,
            h / k,
            s0 / k,
            (s0 + span) / k,
          );
          // A cell edge that falls next to s0 or s1 leaves a sliver whose width is a
          // difference of nearby lengths: compare against the size of a whole cell's τ.
          expectScaled(scaled, base, 1, 'grid τ', Math.max(...cells) * (span + h));
        },
      ),
      RUNS,
    );
  });

  it('medium: mediumExtinction (1/m), mediumOpticalDepth, mediumMajorant (1/m)', () => {
    fc.assert(
      fc.property(medium1D, length, length, unitFactor, (medium, s0, span, k) => {
        const scaled = scaleMedium(medium, k);
        expectScaled(mediumExtinction(scaled, s0 / k), mediumExtinction(medium, s0), k, 'σt(s)');
        expectScaled(
          mediumOpticalDepth(scaled, s0 / k, (s0 + span) / k),
          mediumOpticalDepth(medium, s0, s0 + span),
          1,
          'τ(s0, s1)',
          mediumMajorant(medium, -Infinity, Infinity) * (span + medium.cellSize),
        );
        expectScaled(
          mediumMajorant(scaled, s0 / k, (s0 + span) / k),
          mediumMajorant(medium, s0, s0 + span),
          k,
          'σ̄',
        );
      }),
      RUNS,
    );
  });

  it('scatter: shadowTransmittanceExact and singleScatterHomogeneousSlab', () => {
    fc.assert(
      fc.property(
        coefficient,
        coefficient,
        length,
        fc.double({ min: 0, max: 10, noNaN: true }),
        length,
        length,
        unitFactor,
        (sigmaS, sigmaA, a, b, t, L, k) => {
          expectScaled(
            shadowTransmittanceExact(sigmaS * k, a / k, b, t / k),
            shadowTransmittanceExact(sigmaS, a, b, t),
            1,
            'T_shadow',
          );
          // a/1e3 keeps e^{−σt a} away from 0, so the radiance itself is compared.
          expectScaled(
            singleScatterHomogeneousSlab(sigmaS * k, sigmaA * k, 0.3, 2, a / 1e3 / k, b, L / k),
            singleScatterHomogeneousSlab(sigmaS, sigmaA, 0.3, 2, a / 1e3, b, L),
            1,
            'L_ss',
          );
        },
      ),
      RUNS,
    );
  });

  it('scatter: equiangularSample (t in m, pdf in 1/m) and equiangularPdf', () => {
    fc.assert(
      fc.property(length, unit, unit, unit, unitFactor, (h, u0, u1, xi, k) => {
        const thetaA = -1.5 + 1.5 * u0;
        const thetaB = thetaA + 1.5 * u1;
        const [t, pdf] = equiangularSample(h, thetaA, thetaB, xi);
        const [tk, pdfk] = equiangularSample(h / k, thetaA, thetaB, xi);
        expectScaled(tk, t, 1 / k, 'equiangular t');
        expectScaled(pdfk, pdf, k, 'equiangular pdf');
        expectScaled(
          equiangularPdf(h / k, thetaA, thetaB, t / k),
          equiangularPdf(h, thetaA, thetaB, t),
          k,
          'pdf(t)',
        );
      }),
      RUNS,
    );
  });

  it('raymarch: linearEmission and the four marches (midpoint and jittered schemes)', () => {
    fc.assert(
      fc.property(
        medium1D,
        fc.double({ min: -5, max: 5, noNaN: true }),
        length,
        unit,
        fc.integer({ min: 1, max: 64 }),
        fc.boolean(),
        unitFactor,
        (medium, slope, d, albedo, steps, jittered, k) => {
          const scheme = jittered ? MARCH_JITTERED_RAY : MARCH_MIDPOINT;
          const scaled = scaleMedium(medium, k);
          // A length of at most 1/σ̄-ish keeps T and L away from underflow.
          const dd = d / 1e3;
          expectScaled(
            linearEmission(1, slope * k, dd / k),
            linearEmission(1, slope, dd),
            1,
            'L_e',
          );
          const runs = [
            [raymarchEmissionAbsorption, 'emission-absorption'],
            [raymarchLinearized, 'linearized'],
            [raymarchEmissionRiemann, 'Riemann'],
          ] as const;
          for (const [march, name] of runs) {
            const base = march(medium, 1, slope, albedo, 0.5, dd, steps, scheme, { value: 7 });
            const other = march(scaled, 1, slope * k, albedo, 0.5, dd / k, steps, scheme, {
              value: 7,
            });
            expectScaled(other.radiance, base.radiance, 1, `${name} L`);
            expectScaled(other.transmittance, base.transmittance, 1, `${name} T`);
          }
          expectScaled(
            raymarchOpticalDepth(scaled, dd / k, steps, scheme, { value: 7 }),
            raymarchOpticalDepth(medium, dd, steps, scheme, { value: 7 }),
            1,
            'marched τ',
          );
          const single = singleScatterMarched(medium, albedo, 0.3, 2, dd, 0.5, dd, steps, scheme, {
            value: 9,
          });
          const singleScaled = singleScatterMarched(
            scaled,
            albedo,
            0.3,
            2,
            dd / k,
            0.5,
            dd / k,
            steps,
            scheme,
            {
              value: 9,
            },
          );
          expectScaled(singleScaled.radiance, single.radiance, 1, 'marched L_ss');
          expectScaled(singleScaled.transmittance, single.transmittance, 1, 'marched T');
        },
      ),
      RUNS,
    );
  });

  it('tracking: free flights (m), the track-length and null-collision weights, and the four estimators', () => {
    fc.assert(
      fc.property(
        medium1D,
        length,
        unit,
        fc.integer({ min: 0, max: 1000 }),
        unitFactor,
        (medium, d, xi, seed, k) => {
          const sigmaMaj = mediumMajorant(medium, 0, d / 1e3);
          const dd = d / 1e3;
          expectScaled(
            sampleFreeFlight(sigmaMaj * k, xi),
            sampleFreeFlight(sigmaMaj, xi),
            1 / k,
            'free flight',
          );
          expectScaled(
            nullCollisionWeight(0.3 * sigmaMaj * k, sigmaMaj * k),
            nullCollisionWeight(0.3 * sigmaMaj, sigmaMaj),
            1,
            'null weight',
          );
          // The binary estimator compares a free flight with d: both scale alike, so only a
          // tie within float64 rounding could differ; the fixed seed has none.
          expect(transmittanceTrackLength(sigmaMaj * k, dd / k, xi)).toBe(
            transmittanceTrackLength(sigmaMaj, dd, xi),
          );
          const scaled = scaleMedium(medium, k);
          const estimators = [
            [
              'delta',
              (m: Medium1D, s: number, kk: number) =>
                transmittanceDeltaTracking(m, dd / kk, s, { value: rngSeed(seed, 1) }, 4096),
            ],
            [
              'ratio',
              (m: Medium1D, s: number, kk: number) =>
                transmittanceRatioTracking(m, dd / kk, s, { value: rngSeed(seed, 2) }, 4096),
            ],
            [
              'residual ratio',
              (m: Medium1D, s: number, kk: number) =>
                transmittanceResidualRatioTracking(
                  m,
                  dd / kk,
                  0.5 * s,
                  0.5 * s,
                  { value: rngSeed(seed, 3) },
                  4096,
                ),
            ],
            [
              'unbiased ray marching',
              (m: Medium1D, s: number, kk: number) =>
                transmittanceUnbiasedRayMarching(m, dd / kk, s, { value: rngSeed(seed, 4) }, 4096),
            ],
          ] as const;
          for (const [name, run] of estimators) {
            const base = run(medium, sigmaMaj, 1);
            const other = run(scaled, sigmaMaj * k, k);
            // A walk multiplies up to thousands of weights, each from a position that carries
            // the rounding of a sum of scaled free flights: 1e-6 relative (a clamp moves it by O(1)).
            expectScaled(other.estimate, base.estimate, 1, `${name} estimate`, 0, 1e-6);
            expect(other.lookups, `${name} lookups`).toBe(base.lookups);
          }
        },
      ),
      RUNS,
    );
  });

  it('integrator: sampleTruncatedExponential (m) and truncatedExponentialPdf (1/m)', () => {
    fc.assert(
      fc.property(coefficient, length, unit, unitFactor, (rate, L, u, k) => {
        const s = sampleTruncatedExponential(rate, L, u);
        expectScaled(sampleTruncatedExponential(rate * k, L / k, u), s, 1 / k, 'truncated s');
        expectScaled(
          truncatedExponentialPdf(rate * k, L / k, s / k),
          truncatedExponentialPdf(rate, L, s),
          k,
          'pdf',
        );
      }),
      RUNS,
    );
  });

  it("dipole: α', σt', σtr (1/m), z_r, z_v (m), A and the totals; profiles scale as k²", () => {
    fc.assert(
      fc.property(coefficient, coefficient, eta, length, unitFactor, (sp, sa, n, r, k) => {
        const base = dipoleParameters(sp, sa, n);
        const other = dipoleParameters(sp * k, sa * k, n);
        expectScaled(other.albedoPrime, base.albedoPrime, 1, "α'");
        expectScaled(other.sigmaTPrime, base.sigmaTPrime, k, "σt'");
        expectScaled(other.sigmaTr, base.sigmaTr, k, 'σtr');
        expectScaled(other.zr, base.zr, 1 / k, 'z_r');
        expectScaled(other.zv, base.zv, 1 / k, 'z_v');
        expectScaled(other.boundaryA, base.boundaryA, 1, 'A');
        expectScaled(dipoleTotalReflectance(other), dipoleTotalReflectance(base), 1, 'R_d');
        expectScaled(dipoleProfile(other, r / k), dipoleProfile(base, r), k * k, 'R_d(r)');
        expectScaled(
          dipoleReflectanceBeyond(other, r / k),
          dipoleReflectanceBeyond(base, r),
          1,
          'R_d beyond r',
        );
        expectScaled(
          dipoleSourceTerm(r / k, sa * k, r / (2 * k)),
          dipoleSourceTerm(r, sa, r / 2),
          k * k,
          'source term',
        );
        expectScaled(
          exponentialDifferenceOverRate(sa * k, r / k, (2 * r) / k),
          exponentialDifferenceOverRate(sa, r, 2 * r),
          1 / k,
          '(e^{−σa} − e^{−σb})/σ',
        );
        const better = betterDipoleParameters(sp, sa, n);
        const betterScaled = betterDipoleParameters(sp * k, sa * k, n);
        expectScaled(betterScaled.albedoPrime, better.albedoPrime, 1, "better α'");
        expectScaled(betterScaled.diffusion, better.diffusion, 1 / k, 'better D');
        expectScaled(betterScaled.sigmaTr, better.sigmaTr, k, 'better σtr');
        expectScaled(
          betterDipoleTotalReflectance(betterScaled),
          betterDipoleTotalReflectance(better),
          1,
          'better R',
        );
        expectScaled(
          betterDipoleProfile(betterScaled, r / k),
          betterDipoleProfile(better, r),
          k * k,
          'better R(r)',
        );
      }),
      RUNS,
    );
  });

  it('dipole: the Christensen–Burley profile (1/m²), radial density (1/m) and CDF', () => {
    fc.assert(
      fc.property(unit, length, length, unitFactor, (albedo, d, r, k) => {
        expectScaled(
          burleyProfile(albedo, d / k, r / k),
          burleyProfile(albedo, d, r),
          k * k,
          'R(r)',
        );
        expectScaled(
          burleyRadialDensity(albedo, d / k, r / k),
          burleyRadialDensity(albedo, d, r),
          k,
          '2πrR',
        );
        expectScaled(burleyRadialCdf(r / k, d / k), burleyRadialCdf(r, d), 1, 'CDF');
      }),
      RUNS,
    );
  });
});
