// Float64 twin of shaders/volume.wesl (chapter 7): transfer-function lookup,
// opacity correction, front-to-back compositing and emission–absorption ray
// casting through a scalar grid with early ray termination. Written from the
// formulas: the lookup finds the last control point at or below v, the opacity
// correction is 1 − (1 − α)^r with log1p/expm1 (float64 needs no series), and
// the march composites the same midpoint samples with the same termination rule.
import { rayBoxSegment, RAY_T_LIMIT } from './geometry.ts';
import { gridDensityTrilinear, gridHasVolume, type DensityGrid, type Vec3 } from './medium.ts';
import { FINITE_LIMIT, saturatingQuotient } from './transmittance.ts';

export const TRANSFER_MAX_POINTS = 16;
export const VOLUME_MAX_STEPS = 8192;
/** Where the shader's opacityToOpticalDepth switches from its series (float64 needs none). */
export const OPACITY_SERIES_LIMIT = 0.0625;
export const VOLUME_STEP_SLACK = 1e-6;

export type Rgba = readonly [number, number, number, number];

/**
 * Same content as the WGSL struct TransferFunction: `count` points with values
 * `values[k]` (the shader packs them four to a vec4f) and colours and opacities `rgba[k]`.
 */
export interface TransferFunction {
  count: number;
  values: readonly number[];
  rgba: readonly Rgba[];
}

/** Same fields as the WGSL struct VolumeMarchResult. */
export interface VolumeMarchResult {
  color: [number, number, number];
  transmittance: number;
  steps: number;
  plannedSteps: number;
  terminated: number;
  capped: number;
}

const clamp = (x: number, lo: number, hi: number): number => Math.min(Math.max(x, lo), hi);

/** A transfer function from control points sorted by value (at most TRANSFER_MAX_POINTS). */
export function makeTransferFunction(
  points: readonly { value: number; color: readonly [number, number, number]; opacity: number }[],
): TransferFunction {
  if (points.length > TRANSFER_MAX_POINTS)
    throw new Error(`a transfer function holds at most ${TRANSFER_MAX_POINTS} points`);
  return {
    count: points.length,
    values: points.map((p) => p.value),
    rgba: points.map((p) => [p.color[0], p.color[1], p.color[2], p.opacity] as const),
  };
}

/** Words of a TransferFunction struct in a uniform buffer (count, 3 pad, 4×vec4f values, 16×vec4f rgba). */
export const TRANSFER_FUNCTION_WORDS = 4 + TRANSFER_MAX_POINTS + 4 * TRANSFER_MAX_POINTS;

/** Packs a transfer function into the WGSL struct's uniform layout (336 bytes). */
export function packTransferFunction(
  tf: TransferFunction,
  words: Uint32Array = new Uint32Array(TRANSFER_FUNCTION_WORDS),
  offset = 0,
): Uint32Array {
  const floats = new Float32Array(words.buffer, words.byteOffset, words.length);
  words[offset] = Math.min(tf.count, TRANSFER_MAX_POINTS) >>> 0;
  for (let k = 0; k < TRANSFER_MAX_POINTS; k++) {
    floats[offset + 4 + k] = tf.values[k] ?? 0;
    const q = tf.rgba[k] ?? [0, 0, 0, 0];
    for (let c = 0; c < 4; c++) floats[offset + 4 + TRANSFER_MAX_POINTS + 4 * k + c] = q[c]!;
  }
  return words;
}

export function transferLookup(tf: TransferFunction, v: number): Rgba {
  const n = Math.min(tf.count, TRANSFER_MAX_POINTS);
  if (n === 0) return [0, 0, 0, 0];
  const value = (k: number): number => tf.values[k] ?? 0;
  const q = (k: number): Rgba => tf.rgba[k] ?? [0, 0, 0, 0];
  if (v < value(0)) return q(0);
  // The last point at or below v (the points are sorted): v lies in [v_j, v_{j+1}).
  let j = 0;
  for (let k = 1; k < n; k++) if (value(k) <= v) j = k;
  if (j === n - 1) return q(n - 1);
  const w = (v - value(j)) / (value(j + 1) - value(j));
  const a = q(j);
  const b = q(j + 1);
  const lerp = (c: 0 | 1 | 2 | 3): number => a[c] + w * (b[c] - a[c]);
  return [lerp(0), lerp(1), lerp(2), lerp(3)];
}

export function opacityToOpticalDepth(alpha: number): number {
  if (!(alpha > 0)) return 0;
  if (alpha >= 1) return FINITE_LIMIT;
  return -Math.log1p(-alpha);
}

export function opacityCorrected(alpha: number, stepRatio: number): number {
  const a = clamp(alpha, 0, 1);
  const ratio = clamp(stepRatio, 0, FINITE_LIMIT);
  if (ratio === 1) return a;
  if (a >= 1) return ratio > 0 ? 1 : 0;
  // 1 − (1 − α)^r = −expm1(r·ln(1 − α)).
  return clamp(-Math.expm1(ratio * Math.log1p(-a)), 0, 1);
}

export function compositeFrontToBack(
  accumulated: readonly [number, number, number, number],
  color: readonly [number, number, number],
  alpha: number,
): [number, number, number, number] {
  const a = clamp(alpha, 0, 1);
  const t = accumulated[3];
  return [
    accumulated[0] + t * a * color[0],
    accumulated[1] + t * a * color[1],
    accumulated[2] + t * a * color[2],
    t * (1 - a),
  ];
}

export function volumeStepCount(segmentLength: number, stepSize: number): number {
  if (!(segmentLength > 0)) return 1;
  if (!(stepSize > 0)) return VOLUME_MAX_STEPS;
  return clamp(
    Math.ceil((segmentLength / stepSize) * (1 - VOLUME_STEP_SLACK)),
    1,
    VOLUME_MAX_STEPS,
  );
}

export function volumeRaymarch(
  grid: DensityGrid,
  volume: Float32Array,
  valueOffset: number,
  tf: TransferFunction,
  referenceStep: number,
  origin: Vec3,
  direction: Vec3,
  stepSize: number,
  terminationThreshold: number,
): VolumeMarchResult {
  const result: VolumeMarchResult = {
    color: [0, 0, 0],
    transmittance: 1,
    steps: 0,
    plannedSteps: 0,
    terminated: 0,
    capped: 0,
  };
  if (!gridHasVolume(grid)) return result;
  const [t0, t1] = rayBoxSegment(grid.boundsMin, grid.boundsMax, origin, direction, 0, RAY_T_LIMIT);
  if (!(t0 <= t1)) return result;
  const span = t1 - t0;
  const n = volumeStepCount(span, stepSize);
  const h = span / n;
  // h/Δs₀ of the unclamped lengths (units do not matter), capped at the largest f32 like
  // the shader's saturating quotient; Δs₀ ≤ 0 makes every opacity > 0 opaque.
  const ratio = saturatingQuotient(h, referenceStep);
  result.plannedSteps = n;
  result.capped = !(stepSize > 0) || span > VOLUME_MAX_STEPS * stepSize ? 1 : 0;
  // L = Σ_i T_i α'_i c_i with T_i = Π_{j<i} (1 − α'_j), summed until T < ε.
  let transmittance = 1;
  const color: [number, number, number] = [0, 0, 0];
  for (let i = 0; i < n; i++) {
    const t = t0 + (i + 0.5) * h;
    const p: Vec3 = [
      origin[0] + t * direction[0],
      origin[1] + t * direction[1],
      origin[2] + t * direction[2],
    ];
    const q = transferLookup(tf, gridDensityTrilinear(grid, volume, p) + valueOffset);
    const alpha = opacityCorrected(q[3], ratio);
    const weight = transmittance * alpha;
    color[0] += weight * Math.max(q[0], 0);
    color[1] += weight * Math.max(q[1], 0);
    color[2] += weight * Math.max(q[2], 0);
    transmittance *= 1 - alpha;
    result.steps = i + 1;
    if (transmittance < terminationThreshold) {
      result.terminated = 1;
      break;
    }
  }
  result.color = color;
  result.transmittance = transmittance;
  return result;
}
