// The power budget of <sb-translucent-room>'s sphere, independent of the camera: the power that
// enters the sphere and the power that leaves it, by light tracing in the reference's physics
// (roomPowerBudgetCpu) and by the dipole over irradiance samples (roomIrradianceCpu +
// roomDipolePowerBudget), black walls so that only the emitter's direct light counts. A scale
// bug in either renderer (a factor π, the area per sample 4πR²/n, mm against m, the
// 1/(π(1 − F_dr)) exit factor, R_d applied twice) moves one of these ratios by far more than
// the Monte Carlo error (fixed seeds; tolerances of 4 standard errors plus the dipole's model
// error). The entered power is known to about 2 % (a binomial count of 40 000 photons), so a
// missing (1 − F) on the transmitted irradiance (≈ 5 %) is left to tests/reference/room.test.ts,
// which checks E against a quadrature.
import { describe, expect, it } from 'vitest';
import { bssrdfExitFactor } from '../../src/reference/bssrdf.ts';
import { dipoleParameters, dipoleTotalReflectance } from '../../src/reference/dipole.ts';
import { findMaterial } from '../../src/subsurface/materials.ts';
import {
  roomDipolePowerBudget,
  roomIrradianceCpu,
  roomPowerBudgetCpu,
  roomScene,
} from '../../src/subsurface/translucentRoom.ts';

const PHOTONS = 40000;
const POINTS = 4096;

function budgets(material: string, radius: number) {
  const m = findMaterial(material)!;
  const scene = roomScene(m, radius, 2, 8);
  const reference = roomPowerBudgetCpu(scene, PHOTONS, 11);
  const samples = roomIrradianceCpu(scene, 1024, 16, 12, new Float32Array(0));
  const dipole = roomDipolePowerBudget(scene, samples, POINTS, 13);
  const rdTotal = [0, 1, 2].map((k) =>
    dipoleTotalReflectance(dipoleParameters(m.sigmaSPrime[k]!, m.sigmaA[k]!, m.eta)),
  );
  // Standard errors of the sums from their sums of squares: s² = (Σw² − (Σw)²/N).
  const se = (sum: number, squares: number, n: number): number =>
    Math.sqrt(Math.max(squares - (sum * sum) / n, 0));
  const referenceSe = reference.left.map((s, k) => se(s, reference.leftSquares[k]!, PHOTONS));
  const dipoleSe = dipole.left.map((s, k) => se(s, dipole.leftSquares[k]!, POINTS));
  // The entered power is Φ·(hits/N): a binomial count.
  const a = scene.lightHalf;
  const emitted = Math.PI * scene.emission * 4 * a * a;
  const p = reference.entered[0] / emitted;
  const enteredSe = emitted * Math.sqrt((p * (1 - p)) / PHOTONS);
  return { reference, dipole, rdTotal, referenceSe, dipoleSe, enteredSe };
}

describe('translucent-room: the sphere’s power budget', () => {
  it('the exit factor sends exactly the exitance M_o into the hemisphere (∫ L_o cos θ dω = M_o)', () => {
    // roomDipolePowerBudget counts M_o as the power out; this is what makes that true.
    for (const eta of [1.3, 1.5]) {
      const n = 2000;
      let integral = 0;
      for (let i = 0; i < n; i++) {
        const mu = (i + 0.5) / n;
        integral += (2 * Math.PI * bssrdfExitFactor(mu, eta) * mu) / n;
      }
      expect(integral).toBeCloseTo(1, 4);
    }
  });

  it('whole milk, R = 20 mm: the same power enters; the dipole returns its R_d total of it, within 10 % of the path tracer', () => {
    const b = budgets('wholemilk', 20);
    for (let k = 0; k < 3; k++) {
      // Pass 1's transmitted irradiance Σ E_i ΔA against the light-traced refracted power.
      expect(Math.abs(b.dipole.entered[k]! - b.reference.entered[k]!)).toBeLessThan(
        4 * b.enteredSe + 0.01 * b.reference.entered[k]!,
      );
      // The dipole sphere's albedo is its total diffuse reflectance R_d(α′, η) (Jensen et al.
      // 2001 eq. 6 with the 1/(1 − F_dr) exit normalization); the curved, finite surface keeps
      // up to 3 % of the profile's tail off the sphere.
      const albedo = b.dipole.left[k]! / b.dipole.entered[k]!;
      const albedoSe = b.dipoleSe[k]! / b.dipole.entered[k]!;
      expect(albedo).toBeLessThan(b.rdTotal[k]! + 4 * albedoSe);
      expect(albedo).toBeGreaterThan(0.97 * b.rdTotal[k]! - 4 * albedoSe);
      // Measured: dipole/reference 0.93, 0.94, 0.91 (the finite sphere absorbs less than the
      // half-space). A scale bug of a factor 1/(1 − F_dr) ≈ 1.7, π or η² would leave [0.8, 1.05].
      const ratio = b.dipole.left[k]! / b.reference.left[k]!;
      expect(ratio).toBeGreaterThan(0.8);
      expect(ratio).toBeLessThan(1.05);
    }
  }, 60000);

  it('Skin 1, R = 5 mm: the dipole’s deficit is in power, 42 % in red, from the finite sphere', () => {
    const b = budgets('skin1', 5);
    const ratios = [0, 1, 2].map((k) => b.dipole.left[k]! / b.reference.left[k]!);
    for (let k = 0; k < 3; k++) {
      expect(Math.abs(b.dipole.entered[k]! - b.reference.entered[k]!)).toBeLessThan(
        4 * b.enteredSe + 0.01 * b.reference.entered[k]!,
      );
      // The dipole's albedo is still its R_d total ...
      const albedo = b.dipole.left[k]! / b.dipole.entered[k]!;
      expect(Math.abs(albedo - b.rdTotal[k]!)).toBeLessThan(
        0.05 * b.rdTotal[k]! + (4 * b.dipoleSe[k]!) / b.dipole.entered[k]!,
      );
    }
    // ... while the path-traced sphere, 2.7 diffusion lengths across in red, returns far more:
    // measured 0.58, 0.70, 0.84 of the reference's power leaves the dipole's sphere.
    expect(ratios[0]).toBeGreaterThan(0.5);
    expect(ratios[0]).toBeLessThan(0.67);
    expect(ratios[0]).toBeLessThan(ratios[1]!);
    expect(ratios[1]).toBeLessThan(ratios[2]!);
  }, 60000);
});
