// The kernel of <sb-dipole-profile> (shaders/kernels/dipole-profile.wesl) against its
// float64 twin (src/widgets/dipole-profile/model.ts): the three profiles per channel
// on the plot's grid and their totals, for three materials of Jensen et al. 2001, and
// the published totals of physics.md §6.1 in the kernel's output. The widget's model:
// presets, the similarity relation of its Monte Carlo run and the sizing of its first
// run.
import { beforeAll, describe, expect, it } from 'vitest';
import { linkKernel } from '../../src/gpu/link.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';
import { evaluateProfilesGpu } from '../../src/widgets/dipole-profile/profileKernel.ts';
import {
  discColour,
  evaluateProfilesCpu,
  firstRunPhotons,
  inputsFrom,
  materialValues,
  monteCarloKey,
  slabRunFor,
  type ProfileCurves,
  type ProfileInputs,
} from '../../src/widgets/dipole-profile/model.ts';
import { DERIVED_DIPOLE_TABLE } from '../support/subsurfaceTables.ts';

const inputsFor = (material: string, extra: Record<string, number> = {}): ProfileInputs =>
  inputsFrom({
    material,
    ...materialValues(material)!,
    g: 0,
    photons: 16,
    exposure: 0,
    view: 10,
    seed: 0,
    ...extra,
  });

// Profiles: the dipole tolerances of tests/shaders/dipole.test.ts (PROFILE 5e-6, BETTER 1e-5;
// Burley 4e-6), rounded up to 1e-5, plus the grid radius: r_i = r_min·exp(t·ln 1e4) in WGSL has
// ≈ 21 ULP (1.3e-6) of exp and log, which the profile's log–log slope s = |d ln R/d ln r|
// multiplies (s ≈ σtr·r in the tail, up to 35 here), and the profile's own exp of x ≈ s adds
// (3 + 2s) ULP: together 1e-5 + 2e-6·s. Values below f32's normal range flush to 0.
const RELATIVE = 1e-5;
const PER_UNIT_SLOPE = 2e-6;
const FLOOR = 2 ** -126;

/** |d ln R/d ln r| of the twin's curve at grid point i (central differences). */
function logSlope(values: Float64Array, radii: Float64Array, i: number): number {
  const lo = Math.max(i - 1, 0);
  const hi = Math.min(i + 1, values.length - 1);
  const ratio = Math.log(values[hi]! / values[lo]!) / Math.log(radii[hi]! / radii[lo]!);
  return Number.isFinite(ratio) ? Math.abs(ratio) : 0;
}

describe('the dipole-profile kernel matches its twin', () => {
  const materials = ['skin1', 'marble', 'ketchup'];
  const results: { gpu: ProfileCurves; cpu: ProfileCurves }[] = [];
  beforeAll(async () => {
    const device = await nodeDevice();
    const code = await linkKernel(SHADER_LIBRARY, SHADER_LIBRARY['kernels/dipole-profile.wesl']!);
    for (const material of materials) {
      const inputs = inputsFor(material);
      results.push({
        gpu: (await evaluateProfilesGpu(device, code, inputs)).curves,
        cpu: evaluateProfilesCpu(inputs),
      });
    }
  }, 60_000);

  materials.forEach((material, m) => {
    it(`${material}: 3 models × 3 channels × 160 radii and the totals, within 1e-5 + 2e-6 × log slope`, () => {
      const { gpu, cpu } = results[m]!;
      for (const model of ['dipole', 'better', 'burley'] as const)
        for (let c = 0; c < 3; c++)
          gpu[model][c]!.forEach((value, i) => {
            const twin = cpu[model][c]![i]!;
            const slope = logSlope(cpu[model][c]!, cpu.radii, i);
            expect(
              Math.abs(value - twin) <= Math.max((RELATIVE + PER_UNIT_SLOPE * slope) * twin, FLOOR),
              `${model} channel ${c} at r = ${cpu.radii[i]}: ${value} vs ${twin}`,
            ).toBe(true);
          });
      for (const key of [
        'dipoleTotal',
        'betterTotal',
        'burleyLength',
        'dipoleAtZero',
        'betterAtZero',
      ] as const)
        gpu[key].forEach((value, c) => expect(value / cpu[key][c]! - 1).toBeLessThan(RELATIVE));
    });
  });

  it('the kernel’s totals are the published ones (physics.md §6.1, 6 digits)', () => {
    materials.forEach((material, m) => {
      const rows = DERIVED_DIPOLE_TABLE.filter((row) => row.material === material);
      rows.forEach((row) => {
        expect(Math.abs(results[m]!.gpu.dipoleTotal[row.channel]! - row.total)).toBeLessThan(2e-6);
        expect(results[m]!.gpu.dipoleAtZero[row.channel]! / row.atZero - 1).toBeLessThan(2e-5);
      });
    });
  });
});

describe('the widget’s model', () => {
  it('a preset sets all coefficients and η; "manual" reads the sliders', () => {
    const marble = inputsFor('marble');
    expect(marble.sigmaSPrime).toEqual([2.19, 2.62, 3.0]);
    expect(marble.eta).toBe(1.5);
    const manual = inputsFrom({
      material: 'manual',
      ...materialValues('skin1')!,
      'sigma-a-r': 0.5,
      eta: 1.4,
      g: 0.5,
      photons: 14,
      exposure: 1,
      view: 5,
      seed: 3,
    });
    expect(manual.sigmaA).toEqual([0.5, 0.17, 0.48]);
    expect(manual.eta).toBe(1.4);
    expect(manual.photonTarget).toBe(16384);
    expect(manual.exposure).toBe(400);
    // A preset ignores the sliders, whatever they say.
    expect(inputsFrom({ ...manual, material: 'skin1', 'sigma-a-r': 9 } as never).sigmaA[0]).toBe(
      0.032,
    );
  });

  it('the Monte Carlo keeps σs′ = σs(1 − g) (similarity) and restarts when the medium changes', () => {
    const run = slabRunFor(inputsFor('skin1', { g: 0.8 }), 4096, 0);
    run.channels.forEach((channel, c) =>
      expect(channel.sigmaS * (1 - run.g)).toBeCloseTo([0.74, 0.88, 1.01][c]!, 12),
    );
    expect(run.thickness).toBe(Infinity);
    expect(run.eta).toBe(1.3);
    expect(monteCarloKey(inputsFor('skin1'))).toBe(
      monteCarloKey(inputsFor('skin1', { exposure: 3 })),
    );
    expect(monteCarloKey(inputsFor('skin1'))).not.toBe(
      monteCarloKey(inputsFor('skin1', { g: 0.5 })),
    );
  });

  it('the first run is smaller for media with long walks (marble) than for short ones (ketchup), but has ≥ 16 batches', () => {
    expect(firstRunPhotons(inputsFor('ketchup'))).toBe(4096);
    expect(firstRunPhotons(inputsFor('marble'))).toBe(1024);
    expect(firstRunPhotons(inputsFor('skin1'))).toBe(1024);
  });

  it('the disc glows redder than it glows blue away from the beam in skin, and is brightest at the centre', () => {
    const skin = inputsFor('skin1');
    const [r, g, b] = discColour(skin, 3);
    expect(r).toBeGreaterThan(g);
    expect(g).toBeGreaterThan(b);
    const centre = discColour(skin, 0);
    centre.forEach((v, c) => expect(v).toBeGreaterThan(discColour(skin, 3)[c]!));
    for (const v of [...centre, r, g, b]) expect(v).toBeLessThanOrEqual(1);
  });
});
