// A Lorenz–Mie medium in a scene (issue 21; src/phase/registry.ts entry `mie`), on the CPU:
// validation messages for its parameters, the plan's condition, the packed phase-table
// buffer (one table per distinct parameter set, the f32 words of the twin's
// mieTabulatePhase), the specialization (the table binding and code only in kernels of
// scenes with a Mie medium, and in the general kernel), and the twin's render of the
// physics.md §5 slab against the closed form with the phase function from the Mie series
// itself (not the table). The GPU side is tests/shaders/scene-mie.test.ts.
import { describe, expect, it } from 'vitest';
import {
  MIE_SIZE_PARAMETER_MAX,
  PHASE_TABLE_WORDS,
  phaseTableAt,
} from '../../src/phase/registry.ts';
import { mieTabulatePhase } from '../../src/reference/mie.ts';
import { linkSceneKernel } from '../../src/scene/gpuRenderer.ts';
import { resolveScene } from '../../src/scene/load.ts';
import { sceneMedium } from '../../src/reference/integrator.ts';
import { packScene, sceneData } from '../../src/scene/pack.ts';
import { GENERAL_CONDITIONS, plan } from '../../src/scene/plan.ts';
import { renderScene } from '../../src/scene/renderScene.ts';
import { parseScene, validateScene } from '../../src/scene/validate.ts';
import {
  BH_SPHERE,
  bhSphereSlabPhase,
  mieSlabSystematic,
  slabExact,
  slabScene,
} from '../support/analyticScenes.ts';
import { estimateOf, exampleSceneJson, expectMatchesExact } from '../support/sceneRender.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

const FOG_DROPLET = { type: 'mie', sizeParameter: 20, indexReal: 1.33, indexImaginary: 0 };
const SOOT = { type: 'mie', sizeParameter: 0.5, indexReal: 1.75, indexImaginary: 0.44 };

const medium = (phase: unknown, x = 0): Record<string, unknown> => ({
  type: 'homogeneous',
  bounds: { type: 'box', min: [x - 1, -1, -1], max: [x + 0.5, 1, 1] },
  sigmaA: [0.1, 0.1, 0.1],
  sigmaS: [1, 1, 1],
  phase,
});

const sceneWith = (...phases: unknown[]): Record<string, unknown> => ({
  image: { width: 4, height: 4 },
  samplesPerPixel: 4,
  scatteringOrder: 'unlimited',
  camera: { type: 'perspective', position: [0, 0, 9], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 },
  media: phases.map((phase, i) => medium(phase, 2 * i - 3)),
  lights: [{ type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] }],
});

const errorsOf = (scene: unknown): string[] => {
  const result = validateScene(scene);
  return result.ok ? [] : result.errors;
};

describe('a Mie medium: validation', () => {
  it('accepts a droplet and keeps its parameters', () => {
    expect(parseScene(sceneWith(FOG_DROPLET)).media[0]!.phase).toEqual(FOG_DROPLET);
  });

  it('reports every bad parameter at once, naming the field, value and allowed range', () => {
    const bad = { type: 'mie', sizeParameter: 500, indexReal: 1, indexImaginary: -0.1 };
    expect(errorsOf(sceneWith(bad))).toEqual([
      `media[0].phase.sizeParameter = 500: must be ≤ ${MIE_SIZE_PARAMETER_MAX}`,
      'media[0].phase.indexReal = 1: must be ≥ 1.01',
      'media[0].phase.indexImaginary = -0.1: must be ≥ 0',
    ]);
    expect(errorsOf(sceneWith({ ...FOG_DROPLET, sizeParameter: 0 }))).toEqual([
      'media[0].phase.sizeParameter = 0: must be ≥ 0.01',
    ]);
    expect(errorsOf(sceneWith({ ...FOG_DROPLET, indexImaginary: null }))).toEqual([
      `media[0].phase.indexImaginary = null: must be a number in [0, 10]`,
    ]);
    expect(errorsOf(sceneWith({ type: 'mie', sizeParameter: 3 }))).toEqual([
      'media[0].phase.indexReal: missing (required: a number in [1.01, 3])',
      'media[0].phase.indexImaginary: missing (required: a number in [0, 10])',
    ]);
    expect(errorsOf(sceneWith({ ...FOG_DROPLET, g: 0.8 }))).toEqual([
      'media[0].phase.g: unknown field (allowed: type, sizeParameter, indexReal, indexImaginary)',
    ]);
  });
});

describe('a Mie medium: plan and packing', () => {
  it('the plan links phaseMie only when a Mie medium scatters', () => {
    const conditions = plan(parseScene(sceneWith(FOG_DROPLET))).conditions;
    expect(conditions).toMatchObject({ phaseMie: true, phaseHg: false, phaseRayleigh: false });
    const effect = plan(parseScene(sceneWith(FOG_DROPLET))).effects.find(
      (e) => e.effect === 'phase functions',
    );
    expect(effect?.method).toBe('Lorenz–Mie (tabulated)');
    const dark = sceneWith(FOG_DROPLET);
    (dark.media as Record<string, unknown>[])[0]!.sigmaS = [0, 0, 0];
    expect(plan(parseScene(dark)).conditions.phaseMie).toBe(false);
    const hg = plan(parseScene(sceneWith({ type: 'henyey-greenstein', g: 0.5 }))).conditions;
    expect(hg.phaseMie).toBe(false);
  });

  it('one f32 table per distinct parameter set, indexed by the records, equal to the twin’s', async () => {
    const packed = packScene(
      await resolveScene(
        parseScene(sceneWith(FOG_DROPLET, { type: 'isotropic' }, SOOT, FOG_DROPLET)),
      ),
    );
    expect(packed.phaseTables.length).toBe(2 * PHASE_TABLE_WORDS);
    const scene = sceneData(packed, GENERAL_CONDITIONS);
    expect([0, 1, 2, 3].map((i) => sceneMedium(scene, i).phase.table)).toEqual([0, 0, 1, 0]);
    expect([0, 1, 2, 3].map((i) => sceneMedium(scene, i).phase.kind)).toEqual([3, 0, 3, 3]);
    const expected = mieTabulatePhase(0.5, { n: 1.75, kappa: 0.44 });
    const table = phaseTableAt(packed.phaseTables, 1);
    for (const column of ['oneMinusMu', 'onePlusMu', 'pdf', 'cdf'] as const)
      expect(table[column]).toEqual(Float64Array.from(Float32Array.from(expected[column])));
  });

  it('a scene without tabulated phase functions packs no tables', async () => {
    const packed = packScene(await resolveScene(parseScene(sceneWith({ type: 'rayleigh' }))));
    expect(packed.phaseTables.length).toBe(0);
  });

  it(`building the largest table (x = ${MIE_SIZE_PARAMETER_MAX}) stays well under a second`, () => {
    // Not a timing assertion on the renderer: a bound that keeps the range's upper end a
    // load-time cost (≈ 30 ms measured; 10 s only catches a runaway series).
    const start = performance.now();
    mieTabulatePhase(MIE_SIZE_PARAMETER_MAX, { n: 1.5, kappa: 0.01 });
    expect(performance.now() - start).toBeLessThan(10_000);
  });
});

const defines = (code: string, fn: string): boolean => new RegExp(`\\bfn ${fn}\\(`).test(code);
const TABLE_CODE = ['scenePhaseTableLoad', 'phaseTabulatedEvalDirections', 'phaseTabulatedSample'];

describe('a Mie medium: specialization', () => {
  it('the kernel of a Mie scene binds the tables and links the table code', async () => {
    const code = await linkSceneKernel(
      SHADER_LIBRARY,
      plan(parseScene(exampleSceneJson('mie-fog'))).conditions,
    );
    expect(code).toMatch(/@binding\(5\)\s*var<storage,\s*read>\s*scenePhaseTables/);
    for (const fn of TABLE_CODE) expect(defines(code, fn), fn).toBe(true);
  });

  it('kernels without a Mie medium neither bind nor read the tables', async () => {
    const code = await linkSceneKernel(
      SHADER_LIBRARY,
      plan(parseScene(sceneWith({ type: 'henyey-greenstein', g: 0.5 }))).conditions,
    );
    expect(code).not.toContain('scenePhaseTables');
    expect(code).not.toContain('PhaseTable');
    for (const fn of TABLE_CODE) expect(defines(code, fn), fn).toBe(false);
  });

  it('the general kernel handles Mie media too', async () => {
    const code = await linkSceneKernel(SHADER_LIBRARY, GENERAL_CONDITIONS);
    expect(code).toContain('scenePhaseTables');
    for (const fn of TABLE_CODE) expect(defines(code, fn), fn).toBe(true);
  });
});

describe('a Mie medium: the twin renders the physics.md §5 slab', () => {
  it('single scattering matches the closed form with the series phase function', async () => {
    const { series, tableError } = bhSphereSlabPhase();
    expect(tableError / series, 'the table resolves this smooth lobe').toBeLessThan(1e-4);
    const scene = await resolveScene(parseScene(slabScene('homogeneous', 1, BH_SPHERE)));
    const estimate = estimateOf(await renderScene(scene, { kind: 'cpu' }));
    expectMatchesExact(
      estimate,
      (_, c) => slabExact(c, series),
      'Mie slab, twin',
      mieSlabSystematic(1e-6),
    );
  });
});
