// Scene descriptions (src/scene/): validation with messages that name the field and the
// allowed range, loading of grid files, the planner's decisions per scene, and the
// specialization it drives: the functions of disabled effects are absent from the
// linked WGSL (no GPU needed to link). Also the PFM writer's row order and the tone map.
import { describe, expect, it } from 'vitest';
import { linkSceneKernel } from '../../src/scene/gpuRenderer.ts';
import { decodePfm, encodePfm, srgbEncode, toneMapRgba8 } from '../../src/scene/image.ts';
import { resolveScene } from '../../src/scene/load.ts';
import { GENERAL_CONDITIONS, plan, type Plan } from '../../src/scene/plan.ts';
import { parseScene, SceneValidationError, validateScene } from '../../src/scene/validate.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';
import { EXAMPLE_SCENES, exampleSceneJson } from '../support/sceneRender.ts';

/** A minimal valid scene to which each test adds or breaks one thing. */
const base = (): Record<string, unknown> => ({
  image: { width: 4, height: 4 },
  samplesPerPixel: 4,
  scatteringOrder: 1,
  camera: {
    type: 'perspective',
    position: [0, 0, 5],
    target: [0, 0, 0],
    up: [0, 1, 0],
    fovY: 40,
  },
});

const fog = (extra: Record<string, unknown> = {}): Record<string, unknown> => ({
  type: 'homogeneous',
  bounds: { type: 'box', min: [-1, -1, -1], max: [1, 1, 1] },
  sigmaA: [0.1, 0.1, 0.1],
  sigmaS: [1, 1, 1],
  ...extra,
});

const errorsOf = (scene: unknown): string[] => {
  const result = validateScene(scene);
  return result.ok ? [] : result.errors;
};

describe('scene validation', () => {
  it.each(EXAMPLE_SCENES)('the example scene %s is valid', (name) => {
    expect(errorsOf(exampleSceneJson(name))).toEqual([]);
  });

  it('names the field, the value and the allowed range', () => {
    const scene = { ...base(), media: [fog({ sigmaS: [1, -2, 1] })] };
    expect(errorsOf(scene)).toEqual(['media[0].sigmaS[1] = -2: must be ≥ 0 (1/m)']);
  });

  it('reports every problem at once, never repairs one', () => {
    const scene = {
      ...base(),
      image: { width: 0, height: 4.5 },
      samplesPerPixel: 'many',
      scatteringOrder: -1,
      colour: 'blue',
    };
    expect(errorsOf(scene)).toEqual([
      'scene.colour: unknown field (allowed: image, samplesPerPixel, scatteringOrder, camera, name, description, seed, media, lights, surfaces, $schema)',
      'image.width = 0: must be ≥ 1 (pixels)',
      'image.height = 4.5: must be an integer in [1, 2048] (pixels)',
      'samplesPerPixel = "many": must be an integer in [1, 1000000]',
      'scatteringOrder = -1: must be ≥ 0',
    ]);
  });

  it('explains missing fields, unknown kinds and bad shapes', () => {
    const noCamera = base();
    delete noCamera.camera;
    expect(errorsOf(noCamera)).toEqual(['camera: missing (required: an object)']);
    expect(errorsOf({ ...base(), lights: [{ type: 'area', radiance: [1, 1, 1] }] })).toEqual([
      'lights[0].type = "area": must be one of "directional", "point", "spot", "environment"',
    ]);
    expect(errorsOf({ ...base(), media: [fog({ sigmaA: [1, 1] })] })).toEqual([
      'media[0].sigmaA = [1,1]: must be an RGB triple [r, g, b] a number in [0, 1000000] (1/m): an array of 3 numbers',
    ]);
    expect(errorsOf({ ...base(), scatteringOrder: 'lots' })[0]).toContain(
      'scatteringOrder = "lots": must be an integer in [0, 1000] or "unlimited"',
    );
    expect(errorsOf('a scene')).toEqual([
      'scene = "a scene": must be an object with image, samplesPerPixel, scatteringOrder, camera',
    ]);
  });

  it('checks ranges with units: fov, g, albedo, spot cones, grid sizes', () => {
    const camera = { ...(base().camera as object), fovY: 180 };
    expect(errorsOf({ ...base(), camera })).toEqual(['camera.fovY = 180: must be ≤ 179 (degrees)']);
    expect(
      errorsOf({ ...base(), media: [fog({ phase: { type: 'henyey-greenstein', g: 1 } })] }),
    ).toEqual(['media[0].phase.g = 1: must be ≤ 0.99999']);
    expect(
      errorsOf({
        ...base(),
        surfaces: [{ type: 'sphere', center: [0, 0, 0], radius: 1, albedo: [1.2, 0, 0] }],
      }),
    ).toEqual(['surfaces[0].albedo[0] = 1.2: must be ≤ 1 (albedo)']);
    const spot = {
      type: 'spot',
      position: [0, 3, 0],
      direction: [0, -1, 0],
      intensity: [1, 1, 1],
      innerAngle: 30,
      outerAngle: 20,
    };
    expect(errorsOf({ ...base(), lights: [spot] })).toEqual([
      'lights[0].outerAngle = 20: must be ≥ lights[0].innerAngle = 30 (degrees)',
    ]);
    const grid = { dimensions: [2, 2, 2], density: [1, 1, 1] };
    expect(errorsOf({ ...base(), media: [{ ...fog({ type: 'grid' }), grid }] })).toEqual([
      'media[0].grid.density = "[3 numbers]": must be an array of nx·ny·nz = 8 densities (x fastest)',
    ]);
    const escape = { dimensions: [2, 2, 2], file: '../secrets.f32' };
    expect(errorsOf({ ...base(), media: [{ ...fog({ type: 'grid' }), grid: escape }] })[0]).toMatch(
      /^media\[0\]\.grid\.file = "\.\.\/secrets\.f32": must be a relative path under public\//,
    );
  });

  it('refuses geometry the renderer cannot take: parallel up vectors, overlapping media, two grids, too many lights', () => {
    const camera = { ...(base().camera as object), up: [0, 0, 1] };
    expect(errorsOf({ ...base(), camera })).toEqual([
      'camera.up = [0,0,1]: must not be parallel to the view (target − position)',
    ]);
    const ball = fog({ bounds: { type: 'sphere', center: [1.5, 0, 0], radius: 1 } });
    expect(errorsOf({ ...base(), media: [fog(), ball] })).toEqual([
      'media[1].bounds overlaps media[0].bounds: media must not overlap (they may touch)',
    ]);
    const touching = fog({ bounds: { type: 'sphere', center: [2, 0, 0], radius: 1 } });
    expect(errorsOf({ ...base(), media: [fog(), touching] })).toEqual([]);
    const grid = (x: number): Record<string, unknown> => ({
      ...fog({ type: 'grid', bounds: { type: 'box', min: [x, 0, 0], max: [x + 1, 1, 1] } }),
      grid: { dimensions: [1, 1, 1], density: [1] },
    });
    expect(errorsOf({ ...base(), media: [grid(0), grid(2)] })).toEqual([
      'media[1].type = "grid": at most 1 grid medium per scene (media[0] is one already)',
    ]);
    const light = { type: 'point', position: [0, 1, 0], intensity: [1, 1, 1] };
    expect(errorsOf({ ...base(), lights: Array(9).fill(light) })).toEqual([
      'lights = "[9 entries]": holds 9 lights; the renderer takes at most 8',
    ]);
  });

  it('parseScene throws every message; optional fields get the defaults the README states', () => {
    expect(() => parseScene({ ...base(), seed: -1 })).toThrow(SceneValidationError);
    expect(() => parseScene({ ...base(), seed: -1 })).toThrow(/seed = -1: must be ≥ 0/);
    const scene = parseScene({ ...base(), media: [fog()] });
    expect(scene.seed).toBe(0);
    expect(scene.lights).toEqual([]);
    expect(scene.media[0]?.phase).toEqual({ type: 'isotropic' });
    expect(scene.media[0]?.emission).toBeUndefined();
  });

  it('grid files: a wrong size or a missing file is an error naming the field', async () => {
    const scene = parseScene({
      ...base(),
      media: [{ ...fog({ type: 'grid' }), grid: { dimensions: [2, 2, 2], file: 'volumes/x.f32' } }],
    });
    await expect(resolveScene(scene, () => Promise.resolve(new Uint8Array(12)))).rejects.toThrow(
      'media[0].grid.file = "volumes/x.f32": holds 12 bytes; dimensions 2×2×2 need 32 (float32, x fastest)',
    );
    await expect(resolveScene(scene, () => Promise.reject(new Error('ENOENT')))).rejects.toThrow(
      /cannot be read under public\//,
    );
    const negative = new Float32Array(8).fill(1);
    negative[3] = -1;
    await expect(
      resolveScene(scene, () => Promise.resolve(new Uint8Array(negative.buffer))),
    ).rejects.toThrow(/density 3 is -1/);
  });
});

const effect = (p: Plan, name: string) => p.effects.find((e) => e.effect === name);

describe('the planner', () => {
  const planOf = (json: Record<string, unknown>): Plan => plan(parseScene(json));

  it('σs = 0: emission–absorption, no scattering code, no shadow rays, no phase functions', () => {
    const p = planOf({
      ...base(),
      scatteringOrder: 'unlimited',
      media: [fog({ sigmaS: [0, 0, 0], emission: [1, 1, 1] })],
      lights: [{ type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] }],
    });
    expect(p.integrator).toBe('emission-absorption');
    expect(p.conditions).toMatchObject({
      emission: true,
      volumeScattering: false,
      pathTracing: false,
      lightDirectional: false,
      homogeneousClosedForm: true,
    });
    expect(effect(p, 'shadow rays')?.enabled).toBe(false);
    expect(effect(p, 'in-scattering')?.reason).toBe('σs = 0 in every medium');
    expect(effect(p, 'emission')?.method).toMatch(/closed form/);
  });

  it('order 0 turns scattering off even when σs > 0', () => {
    const p = planOf({
      ...base(),
      scatteringOrder: 0,
      media: [fog()],
      lights: [{ type: 'point', position: [0, 2, 0], intensity: [1, 1, 1] }],
    });
    expect(p.integrator).toBe('emission-absorption');
    expect(effect(p, 'integrator')?.reason).toBe('scattering order 0');
    expect(p.conditions.volumeScattering).toBe(false);
    expect(p.conditions.lightPoint).toBe(false);
  });

  it("homogeneous single scattering: Beer's law for shadow rays, no emission term when nothing emits, no surface code", () => {
    const p = planOf({
      ...base(),
      media: [fog({ phase: { type: 'henyey-greenstein', g: 0.5 } })],
      lights: [{ type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] }],
    });
    expect(p.integrator).toBe('single-scattering');
    expect(effect(p, 'shadow rays')?.method).toBe(
      "Beer's law (closed form) through homogeneous media",
    );
    expect(effect(p, 'emission')).toMatchObject({
      enabled: false,
      reason: 'no medium emits (emission absent or zero, or σa = 0)',
    });
    expect(p.conditions).toMatchObject({
      homogeneousClosedForm: true,
      gridMedia: false,
      emission: false,
      surfaces: false,
      phaseHg: true,
      phaseRayleigh: false,
      equiangular: false,
    });
  });

  it('grids: ratio tracking for shadow rays; the reservoir-chosen collision takes the point and spot lights', () => {
    const p = plan(parseScene({ ...exampleSceneJson('smoke-spotlight') }));
    expect(p.integrator).toBe('single-scattering');
    expect(effect(p, 'shadow rays')?.method).toBe(
      'ratio tracking through grids and surface occlusion',
    );
    expect(effect(p, 'equiangular sampling')).toMatchObject({
      enabled: false,
      reason: 'grids only: the reservoir-chosen collision takes every light',
    });
    expect(p.conditions).toMatchObject({
      gridMedia: true,
      homogeneousClosedForm: false,
      equiangular: false,
      lightSpot: true,
      lightPoint: true,
      lightDirectional: false,
      surfaces: true,
      surfaceScattering: true,
    });
  });

  it('point lights in a homogeneous medium get equiangular sampling', () => {
    const p = planOf({
      ...base(),
      media: [fog()],
      lights: [{ type: 'point', position: [0, 0.5, 0], intensity: [1, 1, 1] }],
    });
    expect(effect(p, 'equiangular sampling')?.enabled).toBe(true);
    expect(p.conditions).toMatchObject({
      equiangular: true,
      lightPoint: true,
      homogeneousClosedForm: true,
      // The one-medium kernel takes equiangular points too (without segment lists).
      oneHomogeneousMedium: true,
    });
  });

  it('the one-medium kernel: one homogeneous medium under delta lights, and surfaces only for single scattering', () => {
    const sun = { type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] };
    const one = (json: Record<string, unknown>) =>
      planOf({ ...base(), media: [fog()], lights: [sun], ...json }).conditions.oneHomogeneousMedium;
    expect(one({})).toBe(true);
    expect(one({ scatteringOrder: 'unlimited' })).toBe(true);
    const point = { type: 'point', position: [0, 0.5, 0], intensity: [1, 1, 1] };
    // Single scattering under a point light takes equiangular points, the one-medium
    // kernel as well as the general one; the path tracer samples free flights either way.
    expect(one({ lights: [point] })).toBe(true);
    expect(one({ lights: [point, sun] })).toBe(true);
    expect(one({ lights: [point], scatteringOrder: 'unlimited' })).toBe(true);
    expect(one({ lights: [sun, { type: 'environment', radiance: [1, 1, 1] }] })).toBe(false);
    expect(one({ media: [fog({ emission: [1, 1, 1] })] })).toBe(false);
    const ball = { type: 'sphere', center: [0, 0, 0], radius: 0.2, albedo: [1, 1, 1] };
    // Surfaces stop view rays and block shadow rays in the single-scattering one; the
    // one-medium path tracer has no surface bounces.
    expect(one({ surfaces: [ball] })).toBe(true);
    expect(one({ surfaces: [ball], lights: [point, sun] })).toBe(true);
    expect(one({ surfaces: [ball], scatteringOrder: 'unlimited' })).toBe(false);
    expect(one({ scatteringOrder: 0 })).toBe(false);
    expect(
      effect(planOf({ ...base(), media: [fog()], lights: [sun] }), 'integrator')?.method,
    ).toMatch(/one-medium kernel/);
  });

  it('the one-medium path tracer in a grid: one grid medium under delta lights, path traced', () => {
    const sun = { type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] };
    const smoke = (extra: Record<string, unknown> = {}) => ({
      ...fog(extra),
      type: 'grid',
      grid: { dimensions: [2, 2, 2], density: [0, 1, 0.5, 1, 1, 0.25, 1, 0] },
    });
    const grid = (json: Record<string, unknown>) =>
      planOf({ ...base(), media: [smoke()], lights: [sun], scatteringOrder: 'unlimited', ...json })
        .conditions;
    expect(grid({})).toMatchObject({ oneGridMedium: true, oneHomogeneousMedium: false });
    // Single scattering keeps the general estimator (reservoir-chosen collisions).
    expect(grid({ scatteringOrder: 1 }).oneGridMedium).toBe(false);
    expect(
      grid({ lights: [sun, { type: 'environment', radiance: [1, 1, 1] }] }).oneGridMedium,
    ).toBe(false);
    expect(grid({ media: [smoke({ emission: [1, 1, 1] })] }).oneGridMedium).toBe(false);
    expect(
      grid({
        media: [smoke(), fog({ bounds: { type: 'box', min: [2, 2, 2], max: [3, 3, 3] } })],
      }).oneGridMedium,
    ).toBe(false);
    expect(
      grid({ surfaces: [{ type: 'sphere', center: [0, 0, 0], radius: 0.2, albedo: [1, 1, 1] }] })
        .oneGridMedium,
    ).toBe(false);
    expect(
      effect(
        planOf({ ...base(), media: [smoke()], lights: [sun], scatteringOrder: 'unlimited' }),
        'integrator',
      )?.method,
    ).toMatch(/one grid medium under delta lights/);
  });

  it('branches a scene cannot take are left out: ray–sphere code without spheres, the light loop for one light', () => {
    const sun = { type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] };
    const point = { type: 'point', position: [0, 2, 0], intensity: [1, 1, 1] };
    const conditions = (json: Record<string, unknown>) =>
      planOf({ ...base(), media: [fog()], lights: [sun], ...json }).conditions;
    expect(conditions({})).toMatchObject({ sphereMedia: false, oneLight: true });
    expect(conditions({ lights: [sun, point] }).oneLight).toBe(false);
    expect(conditions({ lights: [] }).oneLight).toBe(false);
    // Gray media: σa and σs equal over the channels in every medium (one exponential for
    // the one-medium kernels' shadow rays).
    expect(conditions({}).grayMedia).toBe(true);
    expect(conditions({ media: [fog({ sigmaS: [1, 1, 1.1] })] }).grayMedia).toBe(false);
    expect(conditions({ media: [fog({ sigmaA: [0, 0.1, 0] })] }).grayMedia).toBe(false);
    expect(GENERAL_CONDITIONS.grayMedia).toBe(false);
    const ball = fog({ bounds: { type: 'sphere', center: [0, 0, 0], radius: 0.5 } });
    expect(conditions({ media: [ball] }).sphereMedia).toBe(true);
    const apart = fog({ bounds: { type: 'sphere', center: [3, 0, 0], radius: 0.5 } });
    expect(conditions({ media: [fog(), apart] }).sphereMedia).toBe(true);
    // The general kernel renders any scene: spheres and a loop over the lights.
    expect(GENERAL_CONDITIONS).toMatchObject({ sphereMedia: true, oneLight: false });
  });

  it('order ≥ 2 with something that scatters: the path tracer', () => {
    expect(plan(parseScene(exampleSceneJson('cloud-sky'))).integrator).toBe('path-tracing');
    const surfacesOnly = plan(parseScene(exampleSceneJson('spheres-on-floor')));
    expect(surfacesOnly.integrator).toBe('path-tracing');
    expect(surfacesOnly.conditions).toMatchObject({
      media: false,
      gridMedia: false,
      volumeScattering: false,
      surfaceScattering: true,
    });
    expect(effect(surfacesOnly, 'media')?.reason).toBe('no media');
  });

  it('no light sources: nothing to scatter, so emission–absorption only', () => {
    const p = planOf({ ...base(), scatteringOrder: 'unlimited', media: [fog()] });
    expect(p.integrator).toBe('emission-absorption');
    expect(effect(p, 'in-scattering')?.reason).toBe('no light source to scatter');
  });

  it('is a pure function of the scene', () => {
    const json = exampleSceneJson('cloud-sky');
    expect(plan(parseScene(json))).toEqual(plan(parseScene(structuredClone(json))));
  });
});

/** Whether the linked WGSL defines a function of that name. */
const defines = (code: string, fn: string): boolean => new RegExp(`\\bfn ${fn}\\(`).test(code);

describe('specialization: disabled effects are absent from the linked WGSL', () => {
  const link = (json: Record<string, unknown>) =>
    linkSceneKernel(SHADER_LIBRARY, plan(parseScene(json)).conditions);

  it('σs = 0 (emission–absorption): no shadow rays, phase functions, lights, tracking or surfaces', async () => {
    const code = await link({
      ...base(),
      scatteringOrder: 'unlimited',
      media: [fog({ sigmaS: [0, 0, 0], emission: [1, 1, 1] })],
      lights: [{ type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] }],
    });
    for (const fn of [
      'shadowTransmittance',
      'sceneTransmittance',
      'vertexDirectLighting',
      'mediumPhaseEval',
      'hgEvalDirections',
      'rayleighEval',
      'lightSampleDirectional',
      'sampleFreeFlight',
      'sceneGridDensity',
      'gridMajorantAlongSegment',
      'surfaceHitDistance',
      'estimateSingleScattering',
      'estimatePathTracing',
      'mediumFreeFlight',
    ])
      expect(defines(code, fn), fn).toBe(false);
    for (const fn of ['estimateEmissionAbsorption', 'emissionClosedForm', 'transmittanceBeer'])
      expect(defines(code, fn), fn).toBe(true);
  });

  it("homogeneous single scattering among surfaces: the one-medium kernel with Beer's law; no tracking, grid, emission, path tracer or segment lists", async () => {
    const code = await link({
      ...base(),
      media: [fog()],
      lights: [{ type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] }],
      surfaces: [{ type: 'sphere', center: [0, 0, 0], radius: 0.2, albedo: [0.5, 0.5, 0.5] }],
    });
    for (const fn of [
      'estimateSingleScatteringOneMedium',
      'oneMediumSurfaceLighting',
      'closestSurface',
      'transmittanceBeer',
    ])
      expect(defines(code, fn), fn).toBe(true);
    for (const fn of [
      'estimateSingleScattering',
      'sceneSegments',
      'vertexDirectLighting',
      'shadowTransmittance',
      'sampleFreeFlight',
      'sceneGridDensity',
      'emissionClosedForm',
      'estimatePathTracing',
      'lightSamplePoint',
      'spotFalloff',
      'equiangularSample',
      'hgEvalDirections',
    ])
      expect(defines(code, fn), fn).toBe(false);
  });

  it('one homogeneous medium under delta lights: the one-medium kernels, without segment lists, surfaces or the general estimators', async () => {
    const single = await link({
      ...base(),
      media: [fog()],
      lights: [{ type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] }],
    });
    expect(defines(single, 'estimateSingleScatteringOneMedium')).toBe(true);
    expect(defines(single, 'transmittanceBeer')).toBe(true);
    for (const fn of [
      'estimateSingleScattering',
      'sceneSegments',
      'segmentWalk',
      'vertexDirectLighting',
      'sampleFreeFlight',
      'surfaceHitDistance',
      'estimatePathTracing',
      'estimatePathTracingOneMedium',
      'pathTracingStep',
      'oneMediumPathStep',
    ])
      expect(defines(single, fn), fn).toBe(false);
    const multiple = await link({
      ...base(),
      scatteringOrder: 'unlimited',
      media: [fog()],
      lights: [{ type: 'point', position: [0, 0.5, 0], intensity: [1, 1, 1] }],
    });
    // Single scattering under a point light: equiangular points, in the one-medium kernel.
    const equiangular = await link({
      ...base(),
      media: [fog()],
      lights: [{ type: 'point', position: [0, 0.5, 0], intensity: [1, 1, 1] }],
    });
    expect(defines(equiangular, 'estimateSingleScatteringOneMedium')).toBe(true);
    expect(defines(equiangular, 'oneMediumEquiangularPoint')).toBe(true);
    expect(defines(equiangular, 'equiangularSample')).toBe(true);
    for (const fn of [
      'estimateSingleScattering',
      'sceneSegments',
      'segmentWalk',
      'vertexDirectLighting',
    ])
      expect(defines(equiangular, fn), fn).toBe(false);
    expect(defines(single, 'oneMediumEquiangularPoint')).toBe(false);
    // The kernel advances paths a segment at a time (path regeneration).
    expect(defines(multiple, 'oneMediumPathStep')).toBe(true);
    expect(defines(multiple, 'mediumFreeFlight')).toBe(true);
    for (const fn of [
      'pathTracingStep',
      'sceneSegments',
      'vertexDirectLighting',
      'segmentWalk',
      'sceneGridDensity',
    ])
      expect(defines(multiple, fn), fn).toBe(false);
  });

  it('one grid medium under delta lights, path traced: the one-medium path tracer with ratio-tracked shadow rays', async () => {
    const code = await link({
      ...base(),
      scatteringOrder: 'unlimited',
      media: [{ ...fog(), type: 'grid', grid: { dimensions: [1, 1, 1], density: [1] } }],
      lights: [{ type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] }],
    });
    for (const fn of ['oneMediumPathStep', 'segmentTransmittance', 'sceneGridDensity'])
      expect(defines(code, fn), fn).toBe(true);
    for (const fn of ['pathTracingStep', 'sceneSegments', 'segmentWalk', 'vertexDirectLighting'])
      expect(defines(code, fn), fn).toBe(false);
  });

  it('grids with point and spot lights: ratio tracking, the majorant grid and the spot falloff are linked', async () => {
    const code = await link(exampleSceneJson('smoke-spotlight'));
    for (const fn of [
      'sampleFreeFlight',
      'sceneGridDensity',
      'gridMajorantAlongSegment',
      'spotFalloff',
      'surfaceHitDistance',
    ])
      expect(defines(code, fn), fn).toBe(true);
    for (const fn of [
      'lightSampleDirectional',
      'estimatePathTracing',
      'rayleighEval',
      'equiangularSample',
    ])
      expect(defines(code, fn), fn).toBe(false);
  });

  it('a point light in a homogeneous medium: equiangular sampling is linked, tracking is not', async () => {
    const code = await link({
      ...base(),
      media: [fog()],
      lights: [{ type: 'point', position: [0, 0.5, 0], intensity: [1, 1, 1] }],
    });
    for (const fn of ['equiangularSample', 'equiangularSegmentSample', 'lightSamplePoint'])
      expect(defines(code, fn), fn).toBe(true);
    for (const fn of ['sampleFreeFlight', 'spotFalloff', 'sceneGridDensity'])
      expect(defines(code, fn), fn).toBe(false);
  });

  it('ray–sphere code only for a sphere medium', async () => {
    const sun = { type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] };
    const box = await link({ ...base(), media: [fog()], lights: [sun] });
    expect(defines(box, 'raySphereSegment')).toBe(false);
    expect(defines(box, 'rayBoxSegment')).toBe(true);
    const ball = fog({ bounds: { type: 'sphere', center: [0, 0, 0], radius: 0.5 } });
    const sphere = await link({ ...base(), media: [ball], lights: [sun] });
    expect(defines(sphere, 'raySphereSegment')).toBe(true);
  });

  it('the general kernel links every effect', async () => {
    const code = await linkSceneKernel(SHADER_LIBRARY, GENERAL_CONDITIONS);
    for (const fn of [
      'pathTracingStep',
      'mediumFreeFlight',
      'sceneGridDensity',
      'hgEvalDirections',
      'rayleighEval',
      'lightSampleSpot',
      'surfaceHitDistance',
      'sampleFreeFlight',
      'raySphereSegment',
    ])
      expect(defines(code, fn), fn).toBe(true);
  });
});

describe('image files', () => {
  it('PFM: little-endian (scale −1), rows stored bottom row first, read back exactly', () => {
    const rgb = Float32Array.from({ length: 2 * 3 * 3 }, (_, k) => k + 0.5);
    const bytes = encodePfm(3, 2, rgb);
    const header = 'PF\n3 2\n-1.0\n';
    expect(new TextDecoder().decode(bytes.slice(0, header.length))).toBe(header);
    const view = new DataView(bytes.buffer, header.length);
    // The first stored pixel is the bottom-left one: row 1, column 0.
    expect(view.getFloat32(0, true)).toBe(rgb[9]);
    expect(decodePfm(bytes)).toEqual({ width: 3, height: 2, rgb });
  });

  it('tone map: exposure, clamp, sRGB transfer', () => {
    expect(srgbEncode(0)).toBe(0);
    expect(srgbEncode(1)).toBeCloseTo(1, 12);
    expect(srgbEncode(0.0031308)).toBeCloseTo(0.04045, 5);
    expect(Array.from(toneMapRgba8(1, 1, [0.25, 2, -1], 1))).toEqual([
      Math.round(255 * srgbEncode(0.5)),
      255,
      0,
      255,
    ]);
  });
});
