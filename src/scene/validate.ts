// Validation of scene descriptions (types.ts; README "Scenes"). Every problem becomes
// one message that names the field by its JSON path, the value found and what is
// allowed, e.g. "media[0].sigmaS[1] = -2: must be ≥ 0 (1/m)". All problems are
// reported at once; nothing is clamped or replaced by a default, except the optional
// fields whose defaults the README states (seed 0, no media, lights or surfaces,
// isotropic phase function, no emission). Pure: files named by grids are checked for
// their path here and read by load.ts.
import {
  SCENE_LIMITS,
  type BoundsDescription,
  type CameraDescription,
  type GridDescription,
  type LightDescription,
  type MediumDescription,
  type Rgb,
  type SceneDescription,
  type SurfaceDescription,
  type Vec3,
} from './types.ts';
import { DEFAULT_PHASE, PHASE_IDS, phaseEntry, type PhaseDescription } from '../phase/registry.ts';

export type SceneValidation =
  { ok: true; scene: SceneDescription } | { ok: false; errors: string[] };

/** Thrown by parseScene: the message lists every problem, one per line. */
export class SceneValidationError extends Error {
  readonly errors: readonly string[];
  constructor(errors: readonly string[]) {
    super(`invalid scene:\n${errors.map((e) => `  ${e}`).join('\n')}`);
    this.name = 'SceneValidationError';
    this.errors = errors;
  }
}

interface Range {
  min?: number;
  max?: number;
  /** The bounds themselves are excluded. */
  exclusiveMin?: boolean;
  exclusiveMax?: boolean;
  integer?: boolean;
  unit?: string;
}

const L = SCENE_LIMITS;
const COORDINATE: Range = { min: -L.coordinate, max: L.coordinate, unit: 'm' };
const COEFFICIENT: Range = { min: 0, max: L.coefficient, unit: '1/m' };

function show(value: unknown): string {
  if (value === undefined) return 'undefined';
  const text = JSON.stringify(value) ?? String(value);
  return text.length > 60 ? `${text.slice(0, 57)}...` : text;
}

function describeRange(r: Range): string {
  const kind = r.integer ? 'an integer' : 'a number';
  const lo = r.min === undefined ? '' : `${r.exclusiveMin ? '(' : '['}${r.min}`;
  const hi = r.max === undefined ? '' : `${r.max}${r.exclusiveMax ? ')' : ']'}`;
  const range = lo && hi ? ` in ${lo}, ${hi}` : lo ? ` ${r.exclusiveMin ? '>' : '≥'} ${r.min}` : '';
  return `${kind}${range}${r.unit ? ` (${r.unit})` : ''}`;
}

class Reader {
  readonly errors: string[] = [];

  fail(path: string, value: unknown, message: string): null {
    this.errors.push(`${path} = ${show(value)}: ${message}`);
    return null;
  }

  missing(path: string, what: string): null {
    this.errors.push(`${path}: missing (required: ${what})`);
    return null;
  }

  /** An object with the given keys; unknown keys are errors. */
  object(
    path: string,
    value: unknown,
    required: readonly string[],
    optional: readonly string[] = [],
  ): Record<string, unknown> | null {
    if (typeof value !== 'object' || value === null || Array.isArray(value))
      return this.fail(path, value, `must be an object with ${required.join(', ')}`);
    const record = value as Record<string, unknown>;
    const allowed = [...required, ...optional];
    for (const key of Object.keys(record))
      if (!allowed.includes(key))
        this.errors.push(`${path}.${key}: unknown field (allowed: ${allowed.join(', ')})`);
    return record;
  }

  number(path: string, value: unknown, r: Range): number | null {
    if (value === undefined) return this.missing(path, describeRange(r));
    if (typeof value !== 'number' || !Number.isFinite(value))
      return this.fail(path, value, `must be ${describeRange(r)}`);
    if (r.integer && !Number.isInteger(value))
      return this.fail(path, value, `must be ${describeRange(r)}`);
    const unit = r.unit ? ` (${r.unit})` : '';
    if (r.min !== undefined && (r.exclusiveMin ? value <= r.min : value < r.min))
      return this.fail(path, value, `must be ${r.exclusiveMin ? '>' : '≥'} ${r.min}${unit}`);
    if (r.max !== undefined && (r.exclusiveMax ? value >= r.max : value > r.max))
      return this.fail(path, value, `must be ${r.exclusiveMax ? '<' : '≤'} ${r.max}${unit}`);
    return value;
  }

  triple(path: string, value: unknown, r: Range, what: string): Vec3 | null {
    if (value === undefined) return this.missing(path, `${what}, 3 numbers`);
    if (!Array.isArray(value) || value.length !== 3)
      return this.fail(path, value, `must be ${what}: an array of 3 numbers`);
    const parts = value.map((v, k) => this.number(`${path}[${k}]`, v, r));
    return parts.every((p) => p !== null) ? (parts as Vec3) : null;
  }

  vec3(path: string, value: unknown): Vec3 | null {
    return this.triple(path, value, COORDINATE, 'a point or vector [x, y, z] in m');
  }

  /** A direction of any nonzero length, returned normalized. */
  direction(path: string, value: unknown): Vec3 | null {
    const v = this.triple(path, value, { min: -1e6, max: 1e6 }, 'a direction [x, y, z]');
    if (!v) return null;
    const length = Math.hypot(...v);
    if (!(length >= 1e-9)) return this.fail(path, value, 'must be a nonzero direction');
    return [v[0] / length, v[1] / length, v[2] / length];
  }

  rgb(path: string, value: unknown, r: Range): Rgb | null {
    return this.triple(path, value, r, `an RGB triple [r, g, b] ${describeRange(r)}`);
  }

  choice<T extends string>(path: string, value: unknown, options: readonly T[]): T | null {
    if (value === undefined) return this.missing(path, `one of ${options.map(show).join(', ')}`);
    if (typeof value !== 'string' || !options.includes(value as T))
      return this.fail(path, value, `must be one of ${options.map(show).join(', ')}`);
    return value as T;
  }

  text(path: string, value: unknown, maxLength: number): string | null {
    if (typeof value !== 'string' || value.length > maxLength)
      return this.fail(path, value, `must be a string of at most ${maxLength} characters`);
    return value;
  }

  array(path: string, value: unknown, maxLength: number, what: string): unknown[] | null {
    if (!Array.isArray(value))
      return this.fail(path, value, `must be an array of ${what} (at most ${maxLength})`);
    if (value.length > maxLength)
      return this.fail(
        path,
        `[${value.length} entries]`,
        `holds ${value.length} ${what}; the renderer takes at most ${maxLength}`,
      );
    return value;
  }
}

const cross = (a: Vec3, b: Vec3): Vec3 => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];

function readCamera(r: Reader, path: string, value: unknown): CameraDescription | null {
  const type = r.choice(`${path}.type`, (value as { type?: unknown } | null)?.type, [
    'perspective',
    'orthographic',
  ] as const);
  if (type === 'perspective') {
    const o = r.object(path, value, ['type', 'position', 'target', 'up', 'fovY']);
    if (!o) return null;
    const position = r.vec3(`${path}.position`, o.position);
    const target = r.vec3(`${path}.target`, o.target);
    const up = r.direction(`${path}.up`, o.up);
    const fovY = r.number(`${path}.fovY`, o.fovY, { min: 0.001, max: 179, unit: 'degrees' });
    if (!position || !target || !up || fovY === null) return null;
    const view: Vec3 = [target[0] - position[0], target[1] - position[1], target[2] - position[2]];
    const distance = Math.hypot(...view);
    if (!(distance > 1e-6))
      return r.fail(`${path}.target`, o.target, 'must differ from camera.position');
    if (Math.hypot(...cross(view, up)) <= 1e-6 * distance)
      return r.fail(`${path}.up`, o.up, 'must not be parallel to the view (target − position)');
    return { type, position, target, up, fovY };
  }
  if (type === 'orthographic') {
    const o = r.object(path, value, ['type', 'position', 'direction', 'up', 'width', 'height']);
    if (!o) return null;
    const position = r.vec3(`${path}.position`, o.position);
    const direction = r.direction(`${path}.direction`, o.direction);
    const up = r.direction(`${path}.up`, o.up);
    const footprint: Range = { min: 0, exclusiveMin: true, max: L.coordinate, unit: 'm' };
    const width = r.number(`${path}.width`, o.width, footprint);
    const height = r.number(`${path}.height`, o.height, footprint);
    if (!position || !direction || !up || width === null || height === null) return null;
    if (Math.hypot(...cross(direction, up)) <= 1e-6)
      return r.fail(`${path}.up`, o.up, 'must not be parallel to camera.direction');
    return { type, position, direction, up, width, height };
  }
  return null;
}

function readBounds(r: Reader, path: string, value: unknown): BoundsDescription | null {
  const type = r.choice(`${path}.type`, (value as { type?: unknown } | null)?.type, [
    'box',
    'sphere',
  ] as const);
  if (type === 'box') {
    const o = r.object(path, value, ['type', 'min', 'max']);
    if (!o) return null;
    const min = r.vec3(`${path}.min`, o.min);
    const max = r.vec3(`${path}.max`, o.max);
    if (!min || !max) return null;
    for (let k = 0; k < 3; k++)
      if (!(max[k]! > min[k]!))
        return r.fail(`${path}.max[${k}]`, max[k], `must be > ${path}.min[${k}] = ${min[k]}`);
    return { type, min, max };
  }
  if (type === 'sphere') {
    const o = r.object(path, value, ['type', 'center', 'radius']);
    if (!o) return null;
    const center = r.vec3(`${path}.center`, o.center);
    const radius = r.number(`${path}.radius`, o.radius, {
      min: 0,
      exclusiveMin: true,
      max: L.coordinate,
      unit: 'm',
    });
    if (!center || radius === null) return null;
    return { type, center, radius };
  }
  return null;
}

function readPhase(r: Reader, path: string, value: unknown): PhaseDescription | null {
  if (value === undefined) return { ...DEFAULT_PHASE };
  const type = r.choice(`${path}.type`, (value as { type?: unknown } | null)?.type, PHASE_IDS);
  if (type === null) return null;
  // The entry's parameters, read like every other number (names, ranges, messages).
  const { parameters } = phaseEntry(type);
  const o = r.object(path, value, ['type', ...parameters.map((p) => p.name)]);
  if (!o) return null;
  const values = parameters.map((p) => [p.name, r.number(`${path}.${p.name}`, o[p.name], p)]);
  if (values.some(([, v]) => v === null)) return null;
  return { type, ...Object.fromEntries(values) } as PhaseDescription;
}

/** A path under public/: relative, forward slashes, no "..", a raw float32 file. */
const GRID_FILE = /^(?!.*(?:^|\/)\.\.?(?:\/|$))[A-Za-z0-9_\-./]+\.f32$/;

function readGrid(r: Reader, path: string, value: unknown): GridDescription | null {
  const o = r.object(path, value, ['dimensions'], ['density', 'file']);
  if (!o) return null;
  const size: Range = { min: 1, max: L.gridDimension, integer: true, unit: 'samples' };
  const dimensions = r.triple(
    `${path}.dimensions`,
    o.dimensions,
    size,
    'the samples per axis [nx, ny, nz]',
  );
  if ((o.density === undefined) === (o.file === undefined)) {
    r.errors.push(
      `${path}: needs exactly one of "density" (inline array) or "file" (a .f32 file under public/)`,
    );
    return null;
  }
  if (!dimensions) return null;
  const count = dimensions[0] * dimensions[1] * dimensions[2];
  if (o.file !== undefined) {
    if (typeof o.file !== 'string' || !GRID_FILE.test(o.file) || o.file.startsWith('/'))
      return r.fail(
        `${path}.file`,
        o.file,
        'must be a relative path under public/ ending in .f32 (raw little-endian float32, x fastest), without ".."',
      );
    return { dimensions, file: o.file };
  }
  if (!Array.isArray(o.density) || o.density.length !== count)
    return r.fail(
      `${path}.density`,
      Array.isArray(o.density) ? `[${o.density.length} numbers]` : o.density,
      `must be an array of nx·ny·nz = ${count} densities (x fastest)`,
    );
  const density = o.density as unknown[];
  for (let i = 0; i < density.length; i++) {
    const v = density[i];
    if (typeof v !== 'number' || !Number.isFinite(v) || v < 0 || v > L.coefficient) {
      r.fail(`${path}.density[${i}]`, v, `must be a number in [0, ${L.coefficient}]`);
      return null;
    }
  }
  return { dimensions, density: density as number[] };
}

function readMedium(r: Reader, path: string, value: unknown): MediumDescription | null {
  const type = r.choice(`${path}.type`, (value as { type?: unknown } | null)?.type, [
    'homogeneous',
    'grid',
  ] as const);
  if (!type) return null;
  const common = ['type', 'bounds', 'sigmaA', 'sigmaS'];
  const o = r.object(path, value, type === 'grid' ? [...common, 'grid'] : common, [
    'phase',
    'emission',
  ]);
  if (!o) return null;
  const bounds = readBounds(r, `${path}.bounds`, o.bounds);
  const sigmaA = r.rgb(`${path}.sigmaA`, o.sigmaA, COEFFICIENT);
  const sigmaS = r.rgb(`${path}.sigmaS`, o.sigmaS, COEFFICIENT);
  const phase = readPhase(r, `${path}.phase`, o.phase);
  const emission =
    o.emission === undefined
      ? undefined
      : r.rgb(`${path}.emission`, o.emission, {
          min: 0,
          max: L.lightValue,
          unit: 'W/(m²·sr)',
        });
  const grid = type === 'grid' ? readGrid(r, `${path}.grid`, o.grid) : undefined;
  if (!bounds || !sigmaA || !sigmaS || !phase || emission === null || grid === null) return null;
  const medium = { bounds, sigmaA, sigmaS, phase, ...(emission ? { emission } : {}) };
  return type === 'grid' ? { type, ...medium, grid: grid! } : { type, ...medium };
}

function readLight(r: Reader, path: string, value: unknown): LightDescription | null {
  const type = r.choice(`${path}.type`, (value as { type?: unknown } | null)?.type, [
    'directional',
    'point',
    'spot',
    'environment',
  ] as const);
  const power = (unit: string): Range => ({ min: 0, max: L.lightValue, unit });
  if (type === 'directional') {
    const o = r.object(path, value, ['type', 'direction', 'irradiance']);
    if (!o) return null;
    const direction = r.direction(`${path}.direction`, o.direction);
    const irradiance = r.rgb(`${path}.irradiance`, o.irradiance, power('W/m²'));
    return direction && irradiance ? { type, direction, irradiance } : null;
  }
  if (type === 'point') {
    const o = r.object(path, value, ['type', 'position', 'intensity']);
    if (!o) return null;
    const position = r.vec3(`${path}.position`, o.position);
    const intensity = r.rgb(`${path}.intensity`, o.intensity, power('W/sr'));
    return position && intensity ? { type, position, intensity } : null;
  }
  if (type === 'spot') {
    const o = r.object(path, value, [
      'type',
      'position',
      'direction',
      'intensity',
      'innerAngle',
      'outerAngle',
    ]);
    if (!o) return null;
    const position = r.vec3(`${path}.position`, o.position);
    const direction = r.direction(`${path}.direction`, o.direction);
    const intensity = r.rgb(`${path}.intensity`, o.intensity, power('W/sr'));
    const angle: Range = { min: 0, max: 180, unit: 'degrees, half-angle' };
    const innerAngle = r.number(`${path}.innerAngle`, o.innerAngle, angle);
    const outerAngle = r.number(`${path}.outerAngle`, o.outerAngle, angle);
    if (!position || !direction || !intensity || innerAngle === null || outerAngle === null)
      return null;
    if (outerAngle < innerAngle)
      return r.fail(
        `${path}.outerAngle`,
        outerAngle,
        `must be ≥ ${path}.innerAngle = ${innerAngle} (degrees)`,
      );
    return { type, position, direction, intensity, innerAngle, outerAngle };
  }
  if (type === 'environment') {
    const o = r.object(path, value, ['type', 'radiance']);
    if (!o) return null;
    const radiance = r.rgb(`${path}.radiance`, o.radiance, power('W/(m²·sr)'));
    return radiance ? { type, radiance } : null;
  }
  return null;
}

function readSurface(r: Reader, path: string, value: unknown): SurfaceDescription | null {
  const type = r.choice(`${path}.type`, (value as { type?: unknown } | null)?.type, [
    'plane',
    'sphere',
    'box',
  ] as const);
  const albedoRange: Range = { min: 0, max: 1, unit: 'albedo' };
  if (type === 'plane') {
    const o = r.object(path, value, ['type', 'point', 'normal', 'albedo']);
    if (!o) return null;
    const point = r.vec3(`${path}.point`, o.point);
    const normal = r.direction(`${path}.normal`, o.normal);
    const albedo = r.rgb(`${path}.albedo`, o.albedo, albedoRange);
    return point && normal && albedo ? { type, point, normal, albedo } : null;
  }
  if (type === 'sphere') {
    const o = r.object(path, value, ['type', 'center', 'radius', 'albedo']);
    if (!o) return null;
    const center = r.vec3(`${path}.center`, o.center);
    const radius = r.number(`${path}.radius`, o.radius, {
      min: 0,
      exclusiveMin: true,
      max: L.coordinate,
      unit: 'm',
    });
    const albedo = r.rgb(`${path}.albedo`, o.albedo, albedoRange);
    return center && radius !== null && albedo ? { type, center, radius, albedo } : null;
  }
  if (type === 'box') {
    const o = r.object(path, value, ['type', 'min', 'max', 'albedo']);
    if (!o) return null;
    const min = r.vec3(`${path}.min`, o.min);
    const max = r.vec3(`${path}.max`, o.max);
    const albedo = r.rgb(`${path}.albedo`, o.albedo, albedoRange);
    if (!min || !max || !albedo) return null;
    for (let k = 0; k < 3; k++)
      if (!(max[k]! >= min[k]!))
        return r.fail(`${path}.max[${k}]`, max[k], `must be ≥ ${path}.min[${k}] = ${min[k]}`);
    if ([0, 1, 2].filter((k) => max[k]! > min[k]!).length < 2)
      return r.fail(`${path}.max`, max, 'the box must have positive extent on at least two axes');
    return { type, min, max, albedo };
  }
  return null;
}

/** Whether two media bounds share interior points (touching faces are allowed). */
export function boundsOverlap(a: BoundsDescription, b: BoundsDescription): boolean {
  if (a.type === 'box' && b.type === 'box')
    return [0, 1, 2].every((k) => a.min[k]! < b.max[k]! && b.min[k]! < a.max[k]!);
  if (a.type === 'sphere' && b.type === 'sphere')
    return Math.hypot(...a.center.map((c, k) => c - b.center[k]!)) < a.radius + b.radius;
  const box = a.type === 'box' ? a : (b as Extract<BoundsDescription, { type: 'box' }>);
  const ball = a.type === 'sphere' ? a : (b as Extract<BoundsDescription, { type: 'sphere' }>);
  const gap = ball.center.map((c, k) => c - Math.min(Math.max(c, box.min[k]!), box.max[k]!));
  return Math.hypot(...gap) < ball.radius;
}

/** Validates unknown JSON as a scene; every problem is reported, none is repaired. */
export function validateScene(value: unknown): SceneValidation {
  const r = new Reader();
  const o = r.object(
    'scene',
    value,
    ['image', 'samplesPerPixel', 'scatteringOrder', 'camera'],
    ['name', 'description', 'seed', 'media', 'lights', 'surfaces', '$schema'],
  );
  if (!o) return { ok: false, errors: r.errors };
  if (o.name !== undefined) r.text('name', o.name, 200);
  if (o.description !== undefined) r.text('description', o.description, 2000);
  const image = r.object('image', o.image, ['width', 'height']);
  const pixels: Range = { min: 1, max: L.imageSize, integer: true, unit: 'pixels' };
  const width = image ? r.number('image.width', image.width, pixels) : null;
  const height = image ? r.number('image.height', image.height, pixels) : null;
  const samplesPerPixel = r.number('samplesPerPixel', o.samplesPerPixel, {
    min: 1,
    max: L.samplesPerPixel,
    integer: true,
  });
  const seed =
    o.seed === undefined
      ? 0
      : r.number('seed', o.seed, { min: 0, max: 2 ** 32 - 1, integer: true });
  let scatteringOrder: number | 'unlimited' | null = null;
  if (o.scatteringOrder === 'unlimited') scatteringOrder = 'unlimited';
  else if (typeof o.scatteringOrder === 'number')
    scatteringOrder = r.number('scatteringOrder', o.scatteringOrder, {
      min: 0,
      max: L.scatteringOrder,
      integer: true,
    });
  else if (o.scatteringOrder === undefined)
    r.missing('scatteringOrder', `an integer in [0, ${L.scatteringOrder}] or "unlimited"`);
  else
    r.fail(
      'scatteringOrder',
      o.scatteringOrder,
      `must be an integer in [0, ${L.scatteringOrder}] or "unlimited" (0 = emission–absorption only, 1 = single scattering)`,
    );
  const camera =
    o.camera === undefined ? r.missing('camera', 'an object') : readCamera(r, 'camera', o.camera);
  const list = <T>(
    key: string,
    max: number,
    what: string,
    read: (r: Reader, path: string, v: unknown) => T | null,
  ): (T | null)[] => {
    if (o[key] === undefined) return [];
    const items = r.array(key, o[key], max, what);
    return items ? items.map((item, i) => read(r, `${key}[${i}]`, item)) : [null];
  };
  const media = list('media', L.media, 'media', readMedium);
  const lights = list('lights', L.lights, 'lights', readLight);
  const surfaces = list('surfaces', L.surfaces, 'surfaces', readSurface);
  const grids = media.flatMap((m, i) => (m?.type === 'grid' ? [i] : []));
  if (grids.length > L.gridMedia)
    r.errors.push(
      `media[${grids[1]}].type = "grid": at most ${L.gridMedia} grid medium per scene (media[${grids[0]}] is one already)`,
    );
  media.forEach((a, i) =>
    media.slice(0, i).forEach((b, j) => {
      if (a && b && boundsOverlap(a.bounds, b.bounds))
        r.errors.push(
          `media[${i}].bounds overlaps media[${j}].bounds: media must not overlap (they may touch)`,
        );
    }),
  );
  if (
    r.errors.length > 0 ||
    width === null ||
    height === null ||
    samplesPerPixel === null ||
    seed === null ||
    scatteringOrder === null ||
    !camera
  )
    return { ok: false, errors: r.errors };
  return {
    ok: true,
    scene: {
      ...(typeof o.name === 'string' ? { name: o.name } : {}),
      ...(typeof o.description === 'string' ? { description: o.description } : {}),
      image: { width, height },
      samplesPerPixel,
      seed,
      scatteringOrder,
      camera,
      media: media as MediumDescription[],
      lights: lights as LightDescription[],
      surfaces: surfaces as SurfaceDescription[],
    },
  };
}

/** validateScene, throwing SceneValidationError with every message. */
export function parseScene(value: unknown): SceneDescription {
  const result = validateScene(value);
  if (!result.ok) throw new SceneValidationError(result.errors);
  return result.scene;
}
