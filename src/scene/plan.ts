// The effect planner (DESIGN.md contract 3): plan(scene) decides which effects a scene
// needs and the cheapest correct method for each, and turns the decisions into the WESL
// link conditions of shaders/integrator.wesl, so that the linked kernel contains only
// the planned code. Pure: the same scene always gives the same plan.
//
// The general kernel (GENERAL_CONDITIONS) links every effect with the general methods:
// the volumetric path tracer with the scattering order read at run time, tracking
// (spectral tracking for free flights, ratio tracking for shadow rays) in every medium,
// homogeneous ones included, and every light kind and phase function. It renders any
// scene; a specialized kernel renders its own scene with less code and fewer random
// numbers, and tests hold the two to the same image within Monte Carlo error.
import { PHASE_CONDITIONS, PHASE_FUNCTIONS, type PhaseCondition } from '../phase/registry.ts';
import type { MediumDescription, SceneDescription } from './types.ts';

export const CONDITION_NAMES = [
  'media',
  'gridMedia',
  'sphereMedia',
  'homogeneousClosedForm',
  'emission',
  'volumeScattering',
  'surfaces',
  'surfaceScattering',
  'pathTracing',
  // One per phase function with a condition, in registry order (src/phase/registry.ts).
  ...PHASE_CONDITIONS,
  'lightDirectional',
  'lightPoint',
  'lightSpot',
  'lightEnvironment',
  'equiangular',
  'oneHomogeneousMedium',
  'oneGridMedium',
  'oneLight',
  'grayMedia',
] as const;

export type ConditionName = (typeof CONDITION_NAMES)[number];
export type Conditions = Readonly<Record<ConditionName, boolean>>;

/** Every phase condition set to `value`, or to `value(condition)`. */
function phaseConditions(
  value: boolean | ((condition: PhaseCondition) => boolean),
): Record<PhaseCondition, boolean> {
  return Object.fromEntries(
    PHASE_CONDITIONS.map((c) => [c, typeof value === 'boolean' ? value : value(c)]),
  ) as Record<PhaseCondition, boolean>;
}

/** Every effect, general methods: the kernel that renders any scene. */
export const GENERAL_CONDITIONS: Conditions = {
  media: true,
  gridMedia: true,
  sphereMedia: true,
  homogeneousClosedForm: false,
  emission: true,
  volumeScattering: true,
  surfaces: true,
  surfaceScattering: true,
  pathTracing: true,
  ...phaseConditions(true),
  lightDirectional: true,
  lightPoint: true,
  lightSpot: true,
  lightEnvironment: true,
  equiangular: false,
  oneHomogeneousMedium: false,
  oneGridMedium: false,
  oneLight: false,
  grayMedia: false,
};

export type Integrator = 'emission-absorption' | 'single-scattering' | 'path-tracing';

export interface PlanEffect {
  /** e.g. "shadow rays", "emission". */
  effect: string;
  enabled: boolean;
  /** The method chosen, when enabled. */
  method: string | null;
  /** Why it is on or off, in terms of the scene. */
  reason: string;
}

export interface Plan {
  integrator: Integrator;
  /** The scene's maximum scattering order. */
  scatteringOrder: number | 'unlimited';
  effects: PlanEffect[];
  conditions: Conditions;
}

const positive = (v: readonly number[] | undefined): boolean => !!v && v.some((x) => x > 0);
/** All channels equal (a missing coefficient is 0 in every channel). */
const gray = (v: readonly number[] | undefined): boolean => !v || v.every((x) => x === v[0]);
const emits = (m: MediumDescription): boolean => positive(m.emission) && positive(m.sigmaA);
const describeList = (items: string[]): string =>
  items.length <= 1 ? (items[0] ?? '') : `${items.slice(0, -1).join(', ')} and ${items.at(-1)}`;

/** The plan of a validated scene (validate.ts): effects, methods, reasons, conditions. */
export function plan(scene: SceneDescription): Plan {
  const order = scene.scatteringOrder;
  const atLeast = (n: number): boolean => order === 'unlimited' || order >= n;
  const media = scene.media;
  const homogeneous = media.some((m) => m.type === 'homogeneous');
  const grids = media.some((m) => m.type === 'grid');
  const emission = media.some(emits);
  const scatteringMedia = media.filter((m) => positive(m.sigmaS));
  const kinds = new Set(scene.lights.map((l) => l.type));
  const deltaLights = kinds.has('directional') || kinds.has('point') || kinds.has('spot');
  const anySource = scene.lights.length > 0 || emission;
  const volumeScattering = atLeast(1) && scatteringMedia.length > 0 && anySource;
  const surfaces = scene.surfaces.length > 0;
  const surfaceScattering = surfaces && atLeast(1) && anySource;
  const scattering = volumeScattering || surfaceScattering;
  const pathTracing = scattering && atLeast(2);
  const integrator: Integrator = pathTracing
    ? 'path-tracing'
    : scattering
      ? 'single-scattering'
      : 'emission-absorption';
  const localLights = kinds.has('point') || kinds.has('spot');
  // Equiangular points pay off in homogeneous media; in a grid σs·T varies more than 1/r²,
  // and the reservoir-chosen collision, which follows it, takes every light.
  const homogeneousScattering = scatteringMedia.some((m) => m.type === 'homogeneous');
  const equiangular = !pathTracing && volumeScattering && localLights && homogeneousScattering;
  const phases = new Set(scatteringMedia.map((m) => m.phase.type));
  // One homogeneous medium lit by delta lights: the one-medium kernels of
  // shaders/integrator.wesl, which skip the segment lists and vertex records. Surfaces too
  // for single scattering (they stop the view ray and block shadow rays); the one-medium
  // path tracer has no surface bounces.
  const oneHomogeneousMedium =
    volumeScattering &&
    media.length === 1 &&
    media[0]!.type === 'homogeneous' &&
    (!surfaces || !pathTracing) &&
    !emission &&
    !kinds.has('environment');
  // One grid medium lit by delta lights, path traced: the one-medium path tracer with
  // ratio-tracked shadow rays (the same random numbers as the general path tracer).
  const oneGridMedium =
    pathTracing &&
    volumeScattering &&
    media.length === 1 &&
    media[0]!.type === 'grid' &&
    !surfaces &&
    !emission &&
    !kinds.has('environment');
  const shadowRays = scattering && deltaLights;

  const effects: PlanEffect[] = [];
  const add = (effect: string, enabled: boolean, method: string | null, reason: string): void => {
    effects.push({ effect, enabled, method: enabled ? method : null, reason });
  };

  const orderText = order === 'unlimited' ? 'unlimited' : String(order);
  add(
    'integrator',
    true,
    (integrator === 'path-tracing'
      ? 'volumetric path tracing (spectral tracking, next-event estimation, Russian roulette)'
      : integrator === 'single-scattering'
        ? 'single-scattering estimator (one distance sample per medium segment, shadow rays)'
        : 'emission–absorption (no scattering code)') +
      (oneHomogeneousMedium
        ? '; one homogeneous medium under delta lights: the one-medium kernel (no segment lists)'
        : oneGridMedium
          ? '; one grid medium under delta lights: the one-medium path tracer (no segment lists)'
          : ''),
    integrator === 'path-tracing'
      ? `scattering order ${orderText} ≥ 2 and something scatters`
      : integrator === 'single-scattering'
        ? order === 1
          ? 'scattering order 1'
          : 'light can scatter only once here'
        : !atLeast(1)
          ? 'scattering order 0'
          : !anySource
            ? 'nothing emits and there are no lights, so nothing can be scattered'
            : 'σs = 0 in every medium and no surfaces to reflect',
  );

  const mediaMethods = [
    ...(homogeneous ? ["homogeneous: Beer's law and closed forms"] : []),
    ...(grids ? ['grid: trilinear density, majorant grid (DDA), tracking'] : []),
  ];
  add(
    'media',
    media.length > 0,
    describeList(mediaMethods),
    media.length > 0 ? `${media.length} medi${media.length === 1 ? 'um' : 'a'}` : 'no media',
  );

  add(
    'view transmittance',
    media.length > 0,
    integrator === 'path-tracing'
      ? 'free flights by spectral (delta) tracking, majorant σ̄ = largest channel' +
          (grids ? ' (majorant grid along the ray in grids)' : '')
      : describeList([
          ...(homogeneous ? ["Beer's law (closed form) in homogeneous media"] : []),
          ...(grids ? ['ratio tracking in grids (majorant grid)'] : []),
        ]),
    media.length > 0 ? 'rays cross media' : 'no media: rays are not attenuated',
  );

  add(
    'emission',
    emission,
    integrator === 'path-tracing'
      ? 'collision estimator at every tentative collision of spectral tracking'
      : describeList([
          ...(media.some((m) => emits(m) && m.type === 'homogeneous')
            ? ['closed form σa·Le·(1 − e^{−σt L})/σt per homogeneous segment']
            : []),
          ...(media.some((m) => emits(m) && m.type === 'grid')
            ? ['collision estimator along the ratio-tracking walk of each grid segment']
            : []),
        ]),
    emission
      ? `${media.filter(emits).length} emitting medi${media.filter(emits).length === 1 ? 'um' : 'a'}`
      : media.length === 0
        ? 'no media'
        : 'no medium emits (emission absent or zero, or σa = 0)',
  );

  add(
    'in-scattering',
    volumeScattering,
    integrator === 'path-tracing'
      ? 'spectral (delta) tracking free flights, phase sampling'
      : describeList([
          ...(scatteringMedia.some((m) => m.type === 'homogeneous')
            ? ['truncated exponential distance sampling in homogeneous media']
            : []),
          ...(scatteringMedia.some((m) => m.type === 'grid')
            ? [
                'one ratio-tracking collision per grid segment, chosen by weighted reservoir sampling',
              ]
            : []),
        ]),
    volumeScattering
      ? `σs > 0 in ${scatteringMedia.length} medi${scatteringMedia.length === 1 ? 'um' : 'a'} and scattering order ${orderText}`
      : !atLeast(1)
        ? 'scattering order 0'
        : scatteringMedia.length === 0
          ? 'σs = 0 in every medium'
          : 'no light source to scatter',
  );

  add(
    'phase functions',
    volumeScattering,
    describeList(PHASE_FUNCTIONS.filter((e) => phases.has(e.id)).map((e) => e.label)),
    volumeScattering ? 'the phase functions of the scattering media' : 'no in-scattering',
  );

  add(
    'equiangular sampling',
    equiangular,
    'Kulla & Fajardo 2012, one sample per point or spot light and homogeneous segment',
    equiangular
      ? 'point or spot lights illuminate a homogeneous scattering medium'
      : pathTracing
        ? 'the path tracer samples free flights instead'
        : !localLights || !volumeScattering
          ? 'no point or spot light in a scattering scene'
          : 'grids only: the reservoir-chosen collision takes every light',
  );

  add(
    'shadow rays',
    shadowRays,
    describeList([
      ...(homogeneous ? ["Beer's law (closed form) through homogeneous media"] : []),
      ...(grids ? ['ratio tracking through grids'] : []),
      ...(media.length === 0 ? ['occlusion tests only (no media)'] : []),
      ...(surfaces ? ['surface occlusion'] : []),
    ]),
    shadowRays
      ? 'delta lights illuminate scattering media or surfaces'
      : !scattering
        ? 'nothing is scattered (σs = 0 everywhere and no lit surfaces, or scattering order 0)'
        : 'no directional, point or spot light',
  );

  add(
    'surfaces',
    surfaces,
    surfaceScattering
      ? 'hit tests, diffuse (Lambertian) reflection'
      : 'hit tests only (black occluders)',
    surfaces ? `${scene.surfaces.length} surface(s)` : 'no surfaces',
  );

  for (const [kind, name] of [
    ['directional', 'directional lights'],
    ['point', 'point lights'],
    ['spot', 'spot lights'],
    ['environment', 'environment light'],
  ] as const) {
    const present = kinds.has(kind);
    const used = kind === 'environment' ? present : present && scattering;
    add(
      name,
      used,
      kind === 'environment'
        ? 'background radiance' + (scattering ? ', sampled by phase function or BRDF' : '')
        : 'next-event estimation',
      !present ? `no ${kind} light` : used ? `${kind} light present` : 'nothing scatters its light',
    );
  }

  const conditions: Conditions = {
    media: media.length > 0,
    gridMedia: grids,
    // Ray–sphere code only where a medium is a sphere: on SwiftShader every branch of the
    // hot loops costs (shaders/integrator.wesl mediumSegment).
    sphereMedia: media.some((m) => m.bounds.type === 'sphere'),
    homogeneousClosedForm: homogeneous,
    emission,
    volumeScattering,
    surfaces,
    surfaceScattering,
    pathTracing,
    ...phaseConditions(
      (c) => volumeScattering && PHASE_FUNCTIONS.some((e) => e.condition === c && phases.has(e.id)),
    ),
    lightDirectional: scattering && kinds.has('directional'),
    lightPoint: scattering && kinds.has('point'),
    lightSpot: scattering && kinds.has('spot'),
    lightEnvironment: kinds.has('environment'),
    equiangular,
    oneHomogeneousMedium,
    oneGridMedium,
    // Exactly one light: the one-medium kernels' next-event estimation without a loop
    // over the lights (1.2× paths/s on SwiftShader for the issue-19 box).
    oneLight: scene.lights.length === 1,
    // σa and σs equal over the channels in every medium: the one-medium kernels' shadow
    // rays take one exponential instead of three, the same values bit for bit (1.02–1.06×
    // paths/s for the issue-19 box with multiple scattering on SwiftShader: 778 → 766 ns
    // per path in the peers bench's median pass, 820 → 770 in `render --stats`).
    grayMedia: media.every((m) => gray(m.sigmaA) && gray(m.sigmaS)),
  };
  return { integrator, scatteringOrder: order, effects, conditions };
}
