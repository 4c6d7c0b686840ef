// The scene builder of <sb-single-scatter> (src/widgets/single-scatter/model.ts): every
// combination of its controls gives a scene the validator accepts, the toggles give the
// plans the chapter describes (src/scene/plan.ts), scattering off keeps σt, the occluder
// sits inside the spot's cone, and on the float64 CPU twin the occluder darkens the image
// by more than the Monte Carlo error (its shaft and its shadow).
import { describe, expect, it } from 'vitest';
import { CpuSceneRenderer } from '../../src/scene/cpuRenderer.ts';
import { resolveScene } from '../../src/scene/load.ts';
import { nodeFileReader } from '../../src/scene/loadNode.ts';
import { packScene, sceneData } from '../../src/scene/pack.ts';
import { plan, type Plan } from '../../src/scene/plan.ts';
import type { SceneDescription } from '../../src/scene/types.ts';
import { parseScene, validateScene } from '../../src/scene/validate.ts';
import { SINGLE_SCATTER } from '../../src/widgets/single-scatter/schema.ts';
import {
  buildScene,
  inputsFrom,
  sceneKey,
  type SingleScatterInputs,
} from '../../src/widgets/single-scatter/model.ts';
import { parseParameters, type ParameterValues } from '../../src/widgets/parameters.ts';

const DEFAULTS: ParameterValues = parseParameters(SINGLE_SCATTER.parameters, () => null).values;
const OPTIONS = { width: 96, height: 72, spp: 64, seed: 1 };

function inputs(overrides: ParameterValues = {}): SingleScatterInputs {
  return inputsFrom({ ...DEFAULTS, ...overrides });
}

function planOf(overrides: ParameterValues = {}): Plan {
  return plan(parseScene(buildScene(inputs(overrides), OPTIONS)));
}

function enabled(p: Plan, effect: string): boolean {
  const found = p.effects.find((e) => e.effect === effect);
  if (!found) throw new Error(`no effect ${effect}`);
  return found.enabled;
}

describe('single-scatter scene builder', () => {
  it('builds a valid scene for every combination of the choices', () => {
    let count = 0;
    for (const medium of ['fog', 'smoke'])
      for (const light of ['spot', 'directional'])
        for (const occluder of ['sphere', 'box', 'none'])
          for (const scattering of ['on', 'off'])
            for (const emission of ['on', 'off'])
              for (const floor of ['on', 'off']) {
                const scene = buildScene(
                  inputs({ medium, light, occluder, scattering, emission, floor }),
                  OPTIONS,
                );
                const result = validateScene(scene);
                expect(result.ok, JSON.stringify(result)).toBe(true);
                count++;
              }
    expect(count).toBe(96);
  });

  it('also at the ends of the numeric ranges', () => {
    for (const parameter of SINGLE_SCATTER.parameters) {
      if (parameter.kind !== 'number') continue;
      for (const value of [parameter.min, parameter.max]) {
        const scene = buildScene(inputs({ [parameter.name]: value }), OPTIONS);
        expect(validateScene(scene).ok).toBe(true);
      }
    }
  });

  it('plans the default scene: single scattering, Beer shadow rays, equiangular, no emission', () => {
    const p = planOf();
    expect(p.integrator).toBe('single-scattering');
    expect(enabled(p, 'in-scattering')).toBe(true);
    expect(enabled(p, 'equiangular sampling')).toBe(true);
    expect(enabled(p, 'shadow rays')).toBe(true);
    expect(p.effects.find((e) => e.effect === 'shadow rays')!.method).toContain("Beer's law");
    expect(enabled(p, 'emission')).toBe(false);
    expect(enabled(p, 'spot lights')).toBe(true);
    expect(enabled(p, 'directional lights')).toBe(false);
    expect(p.conditions.gridMedia).toBe(false);
    expect(p.conditions.pathTracing).toBe(false);
  });

  it('scattering off keeps σt, skips in-scattering but keeps shadow rays for the floor', () => {
    const on = buildScene(inputs(), OPTIONS).media[0]!;
    const off = buildScene(inputs({ scattering: 'off' }), OPTIONS).media[0]!;
    expect(off.sigmaS).toEqual([0, 0, 0]);
    // σt of the middle channel (σs·1 + σa) is the same; the scattering is moved into σa.
    expect(off.sigmaA[1]).toBeCloseTo(on.sigmaA[1] + on.sigmaS[1], 12);
    const p = planOf({ scattering: 'off' });
    expect(p.integrator).toBe('single-scattering');
    expect(enabled(p, 'in-scattering')).toBe(false);
    expect(enabled(p, 'phase functions')).toBe(false);
    expect(enabled(p, 'equiangular sampling')).toBe(false);
    expect(enabled(p, 'shadow rays')).toBe(true);
  });

  it('nothing scattering and no surfaces: emission–absorption, shadow rays and lights skipped', () => {
    const p = planOf({
      scattering: 'off',
      floor: 'off',
      occluder: 'none',
      emission: 'on',
      albedo: 0.5,
    });
    expect(p.integrator).toBe('emission-absorption');
    expect(enabled(p, 'shadow rays')).toBe(false);
    expect(enabled(p, 'spot lights')).toBe(false);
    expect(enabled(p, 'surfaces')).toBe(false);
    expect(enabled(p, 'emission')).toBe(true);
    expect(p.conditions.volumeScattering).toBe(false);
  });

  it('emission needs σa > 0: with albedo 1 it is skipped', () => {
    expect(enabled(planOf({ emission: 'on', albedo: 1 }), 'emission')).toBe(false);
    expect(enabled(planOf({ emission: 'on', albedo: 0.9 }), 'emission')).toBe(true);
  });

  it('the sun: no equiangular sampling, a directional light', () => {
    const p = planOf({ light: 'directional' });
    expect(enabled(p, 'equiangular sampling')).toBe(false);
    expect(enabled(p, 'directional lights')).toBe(true);
    expect(enabled(p, 'spot lights')).toBe(false);
  });

  it('the smoke grid: ratio-tracked shadow rays, no equiangular points, and the file resolves', async () => {
    const p = planOf({ medium: 'smoke' });
    expect(p.conditions.gridMedia).toBe(true);
    expect(p.conditions.homogeneousClosedForm).toBe(false);
    expect(enabled(p, 'equiangular sampling')).toBe(false);
    expect(p.effects.find((e) => e.effect === 'shadow rays')!.method).toContain('ratio tracking');
    const resolved = await resolveScene(
      parseScene(buildScene(inputs({ medium: 'smoke' }), OPTIONS)),
      nodeFileReader,
    );
    expect(resolved.grid?.maxDensity).toBeGreaterThan(1);
  });

  it('the occluder lies inside the spot cone and inside the fog', () => {
    const scene = buildScene(inputs(), OPTIONS);
    const light = scene.lights[0]!;
    const sphere = scene.surfaces.find((s) => s.type === 'sphere')!;
    if (light.type !== 'spot' || sphere.type !== 'sphere') throw new Error('unexpected scene');
    const toCentre = sphere.center.map((c, i) => c - light.position[i]!);
    const distance = Math.hypot(...toCentre);
    const axisLength = Math.hypot(...light.direction);
    const cos =
      toCentre.reduce((sum, c, i) => sum + c * light.direction[i]!, 0) / (distance * axisLength);
    const angle = (Math.acos(cos) * 180) / Math.PI;
    const angularRadius = (Math.asin(sphere.radius / distance) * 180) / Math.PI;
    expect(angle + angularRadius).toBeLessThan(light.innerAngle);
    const fog = scene.media[0]!;
    if (fog.bounds.type !== 'box') throw new Error('unexpected bounds');
    expect(sphere.center[1] + sphere.radius).toBeLessThan(fog.bounds.max[1]);
  });

  it('the scene key ignores the spp target and nothing else', () => {
    expect(sceneKey(inputs({ spp: 64 }))).toBe(sceneKey(inputs({ spp: 1024 })));
    expect(sceneKey(inputs({ g: 0.5 }))).not.toBe(sceneKey(inputs()));
  });

  it('on the CPU twin, the occluder darkens the image by more than the Monte Carlo error', async () => {
    const render = async (scene: SceneDescription): Promise<{ mean: number; error: number }> => {
      const packed = packScene(await resolveScene(parseScene(scene)));
      const renderer = new CpuSceneRenderer(
        sceneData(packed, plan(scene).conditions),
        packed.width,
        packed.height,
        packed.seed,
      );
      const spp = 16;
      await renderer.renderPass(0, spp);
      const accumulator = renderer.accumulation;
      // The image's mean radiance and its standard error (pixels are independent).
      const mean = accumulator.mean();
      const errors = accumulator.standardError();
      let sum = 0;
      let variance = 0;
      for (let i = 0; i < mean.length; i++) {
        sum += mean[i]!;
        variance += errors[i]! ** 2;
      }
      return { mean: sum / mean.length, error: Math.sqrt(variance) / mean.length };
    };
    const small = { width: 24, height: 18, spp: 16, seed: 5 };
    const withSphere = await render(buildScene(inputs(), small));
    const without = await render(buildScene(inputs({ occluder: 'none' }), small));
    const difference = without.mean - withSphere.mean;
    const error = Math.hypot(withSphere.error, without.error);
    expect(difference).toBeGreaterThan(5 * error);
  });
});
