// The scene builder of <sb-volume-path-tracer> (src/widgets/volume-path-tracer/model.ts):
// its scenes validate, the planner picks the single-scattering estimator for order 1
// and the volumetric path tracer for unlimited order, the medium mask and the error
// measures are right, and on the float64 CPU twin multiple scattering brightens a
// high-albedo cloud well beyond single scattering while the two agree for albedo 0.
import { describe, expect, it } from 'vitest';
import { resolveScene } from '../../src/scene/load.ts';
import { renderScene } from '../../src/scene/renderScene.ts';
import { validateScene } from '../../src/scene/validate.ts';
import {
  CPU_BUDGET,
  FOOTPRINT,
  GPU_BUDGET,
  GRID_SIZE,
  RADIUS,
  buildScene,
  cloudDensity,
  inputsFrom,
  maskedLuminance,
  mediumMask,
  plans,
  relativeError,
  type PathTracerInputs,
} from '../../src/widgets/volume-path-tracer/model.ts';
import { VOLUME_PATH_TRACER } from '../../src/widgets/volume-path-tracer/schema.ts';

const DEFAULTS = inputsFrom(
  Object.fromEntries(VOLUME_PATH_TRACER.parameters.map((p) => [p.name, p.default])),
);

describe('volume-path-tracer scenes', () => {
  it('validate for both media, both orders and both budgets, with σt = τ/2R and α = σs/σt', () => {
    for (const scene of ['sphere', 'cloud'] as const)
      for (const order of [1, 'unlimited'] as const)
        for (const budget of [GPU_BUDGET, CPU_BUDGET]) {
          const description = buildScene({ ...DEFAULTS, scene }, order, budget, 16, 3);
          const checked = validateScene(JSON.parse(JSON.stringify(description)));
          expect(checked.ok).toBe(true);
          expect(description.scatteringOrder).toBe(order);
          expect(description.image).toEqual({ width: budget.width, height: budget.height });
          const medium = description.media[0]!;
          expect(medium.type).toBe(scene === 'cloud' ? 'grid' : 'homogeneous');
          const sigmaT = medium.sigmaA[0] + medium.sigmaS[0];
          expect(sigmaT).toBeCloseTo(DEFAULTS.density / (2 * RADIUS), 12);
          expect(medium.sigmaS[0] / sigmaT).toBeCloseTo(DEFAULTS.albedo, 12);
          expect(medium.phase).toEqual({ type: 'henyey-greenstein', g: DEFAULTS.g });
        }
  });

  it('the extreme parameter values of the schema still validate', () => {
    const extremes: PathTracerInputs[] = [
      { scene: 'sphere', albedo: 0, g: -0.9, density: 0.5, spp: 1 },
      { scene: 'cloud', albedo: 1, g: 0.95, density: 30, spp: 64 },
    ];
    for (const inputs of extremes)
      for (const order of [1, 'unlimited'] as const)
        expect(() => buildScene(inputs, order, GPU_BUDGET, 1, 0)).not.toThrow();
  });

  it('plans single scattering for order 1 and path tracing for unlimited order', () => {
    for (const scene of ['sphere', 'cloud'] as const) {
      const { single, multiple } = plans({ ...DEFAULTS, scene });
      expect(single.integrator).toBe('single-scattering');
      expect(single.conditions.pathTracing).toBe(false);
      expect(multiple.integrator).toBe('path-tracing');
      expect(multiple.conditions.pathTracing).toBe(true);
      expect(multiple.conditions.gridMedia).toBe(scene === 'cloud');
      expect(multiple.conditions.phaseHg).toBe(true);
      expect(multiple.conditions.lightDirectional && multiple.conditions.lightEnvironment).toBe(
        true,
      );
    }
    // Albedo 0: nothing scatters, so neither image needs scattering code.
    const black = plans({ ...DEFAULTS, albedo: 0 });
    expect(black.single.integrator).toBe('emission-absorption');
    expect(black.multiple.integrator).toBe('emission-absorption');
  });

  it('the cloud grid peaks at exactly 1 and is empty at the corners of its cube', () => {
    const density = cloudDensity();
    expect(density).toHaveLength(GRID_SIZE ** 3);
    expect(Math.max(...density)).toBe(1);
    expect(density[0]).toBe(0);
    expect(density.every((d) => d >= 0 && d <= 1)).toBe(true);
  });

  it('the mask holds the pixels where the medium is optically thick (τ ≥ 1 along the view)', () => {
    const n = 200;
    const count = (mask: Uint8Array): number => mask.reduce((s, v) => s + v, 0);
    // Ball, τ = 8 across: τ(r) = 8√(1 − r²) ≥ 1 for r² ≤ 1 − 1/64.
    const sphere = count(mediumMask({ ...DEFAULTS, scene: 'sphere', density: 8 }, n, n));
    expect(sphere / (n * n)).toBeCloseTo(
      (Math.PI * RADIUS ** 2 * (1 - 1 / 64)) / FOOTPRINT ** 2,
      2,
    );
    // A ball thinner than 1 everywhere keeps the pixels with at least half its largest τ.
    const thin = count(mediumMask({ ...DEFAULTS, scene: 'sphere', density: 0.5 }, n, n));
    expect(thin / (n * n)).toBeCloseTo((Math.PI * RADIUS ** 2 * 0.75) / FOOTPRINT ** 2, 2);
    // The cloud covers part of the ball's disc.
    const cloud = count(mediumMask({ ...DEFAULTS, scene: 'cloud', density: 16 }, n, n));
    expect(cloud).toBeGreaterThan(0.1 * sphere);
    expect(cloud).toBeLessThan(0.9 * sphere);
  });

  it('relative error removes the reference noise and measures a known difference', () => {
    const reference = [1, 1, 1, 1];
    const noiseless = [0, 0, 0, 0];
    expect(relativeError([1.1, 0.9, 1.1, 0.9], reference, noiseless)).toBeCloseTo(0.1, 12);
    // Difference (0.1)² per entry, reference noise (0.06)²: sqrt(0.01 − 0.0036) = 0.08.
    expect(relativeError([1.1, 0.9, 1.1, 0.9], reference, [0.06, 0.06, 0.06, 0.06])).toBeCloseTo(
      0.08,
      12,
    );
    expect(relativeError([1, 1, 1, 1], reference, [0.01, 0.01, 0.01, 0.01])).toBeNaN();
    expect(maskedLuminance([1, 1, 1, 5, 5, 5], Uint8Array.from([1, 0]))).toBeCloseTo(1, 12);
  });
});

describe('volume-path-tracer on the CPU twin', () => {
  const size = { width: 6, height: 6 };
  async function ratio(inputs: PathTracerInputs): Promise<number> {
    const mask = mediumMask(inputs, size.width, size.height);
    const luminance = async (order: 1 | 'unlimited'): Promise<number> => {
      const resolved = await resolveScene(buildScene(inputs, order, size, 32, 11));
      const render = await renderScene(resolved, { kind: 'cpu' });
      return maskedLuminance(render.accumulator.mean(), mask);
    };
    return (await luminance('unlimited')) / (await luminance(1));
  }

  it('multiple scattering brightens a white cloud, and changes nothing at albedo 0', async () => {
    // At α = 0.99 and τ = 10 most escaping light has scattered several times; the
    // bound is loose (the measured ratio is far larger) so the test stays deterministic.
    expect(await ratio({ ...DEFAULTS, albedo: 0.99, density: 10 })).toBeGreaterThan(1.5);
    // α = 0: no scattering at all, both renders are the same emission–absorption image.
    expect(await ratio({ ...DEFAULTS, albedo: 0 })).toBeCloseTo(1, 12);
  });
});
