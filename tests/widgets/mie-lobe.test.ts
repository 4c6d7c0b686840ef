// <sb-mie-lobe>'s float64 analysis (the worker job) and its GPU packing: the colour
// readout's physics (white cloud, blue molecule), the HG comparison's limits, and the
// table packed at the offsets the kernel's PhaseTable has (layouts.generated.ts).
import { describe, expect, it } from 'vitest';
import { mieLobeKernel } from '../../src/gpu/layouts.generated.ts';
import { phaseTableToF32, mieTabulatePhase, PHASE_TABLE_NODES } from '../../src/reference/mie.ts';
import { analyseSphere } from '../../src/widgets/mie-lobe/jobs.ts';
import { packComplements, packTable } from '../../src/widgets/mie-lobe/gpuBackend.ts';
import { plotAngles, sizeParameter } from '../../src/widgets/mie-lobe/model.ts';

const sphere = (radiusUm: number, n: number, kappa = 0) =>
  analyseSphere({ radiusUm, wavelengthNm: 550, n, kappa, x: sizeParameter(radiusUm, 550) });

describe('mie-lobe analysis', () => {
  it('a 10 µm cloud droplet scatters R, G, B within 6% of each other (white); a 10 nm particle as λ⁻⁴ (blue)', () => {
    const cloud = sphere(10, 1.33).rgbQsca;
    for (const q of cloud) expect(Math.abs(q / cloud[1] - 1)).toBeLessThan(0.06);
    const molecule = sphere(0.01, 1.01).rgbQsca;
    // Within 1%: x = 2π·10 nm/λ ≈ 0.1, and the first corrections to λ⁻⁴ are O(x²).
    expect(Math.abs(molecule[2] / molecule[1] / (550 / 440) ** 4 - 1)).toBeLessThan(0.01);
    expect(Math.abs(molecule[0] / molecule[1] / (550 / 680) ** 4 - 1)).toBeLessThan(0.01);
  });

  it('a tiny sphere: g ≈ 0, the HG fit is the isotropic lobe, 2/3 of Rayleigh straight back', () => {
    const a = sphere(0.01, 1.01);
    expect(Math.abs(a.g)).toBeLessThan(0.01);
    expect(a.hgBackscatterRatio).toBeCloseTo(2 / 3, 2);
    // The drawn table equals the series to the table's interpolation error.
    a.exact.forEach((p, i) => expect(Math.abs(a.tabulated[i]! / p - 1)).toBeLessThan(1e-4));
  });

  it('a fog droplet: HG with the same g misses the back by more than a factor 2', () => {
    const a = sphere(1, 1.33);
    expect(a.g).toBeGreaterThan(0.5);
    expect(a.hgBackscatterRatio).toBeLessThan(0.5);
    expect(a.hgL1).toBeGreaterThan(0.2);
  });

  it('soot absorbs: Q_abs > 0 and the albedo is below 0.5', () => {
    const a = sphere(0.1, 1.75, 0.44);
    expect(a.qAbs).toBeGreaterThan(0);
    expect(a.albedo).toBeLessThan(0.5);
  });
});

describe('mie-lobe GPU packing', () => {
  it('packs the table at the offsets of the kernel’s PhaseTable and the angles as (1 − μ, 1 + μ) pairs', () => {
    const layout = mieLobeKernel.PhaseTable;
    expect(layout.size).toBe(16 * PHASE_TABLE_NODES);
    const table = phaseTableToF32(mieTabulatePhase(5, { n: 1.33, kappa: 0 }));
    const floats = new Float32Array(packTable(table).buffer);
    expect(floats.length * 4).toBe(layout.size);
    const fields = [
      ['oneMinusMu', table.oneMinusMu],
      ['onePlusMu', table.onePlusMu],
      ['pdf', table.pdf],
      ['cdf', table.cdf],
    ] as const;
    for (const [name, values] of fields) {
      const offset = layout.members[name].offset / 4;
      expect(floats[offset + 7]).toBe(values[7]);
      expect(floats[offset + PHASE_TABLE_NODES - 1]).toBe(values[PHASE_TABLE_NODES - 1]);
    }
    const angles = plotAngles();
    const pairs = new Float32Array(packComplements(angles.oneMinusMu, angles.onePlusMu).buffer);
    expect(pairs[2 * 100]).toBe(Math.fround(angles.oneMinusMu[100]!));
    expect(pairs[2 * 100 + 1]).toBe(Math.fround(angles.onePlusMu[100]!));
  });
});
