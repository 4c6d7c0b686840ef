// Float64 twin of shaders/inverse.wesl (chapter 8): activations, trilinear grid
// lookups, emission–absorption compositing and its derivative, the loss, Adam and
// the regularizers, each written from its formula. On top of them, the whole-ray
// forward march and its gradient with respect to every grid parameter. The twin's
// gradient accumulates from the back of the ray (the textbook reverse-mode
// recursion with the per-sample values stored), while the WGSL kernel re-marches
// from the front and takes "the radiance behind" as C minus the running sum; the
// tests hold both against central finite differences of the twin's loss.
import { rayBoxSegment } from './geometry.ts';
import type { Vec3 } from './phase.ts';
import { rngSeed } from './rng.ts';

export type Vec4 = readonly [number, number, number, number];

export const DENSITY_SCALE = 10;
export const INVERSE_MAX_STEPS = 512;
export const ADAM_BETA1 = 0.9;
export const ADAM_BETA2 = 0.99;
export const ADAM_EPSILON = 1e-12;

/** ln(1 + e^x) without overflow: max(x, 0) + log1p(e^−|x|). */
export function softplus(x: number): number {
  return Math.max(x, 0) + Math.log1p(Math.exp(-Math.abs(x)));
}

/** 1/(1 + e^−x), with the exponential's argument never positive. */
export function sigmoid(x: number): number {
  const e = Math.exp(-Math.abs(x));
  return x >= 0 ? 1 / (1 + e) : e / (1 + e);
}

/** (σt, c) = (10·softplus(ρ), sigmoid(e)) from the raw (ρ, e_r, e_g, e_b). */
export function fieldActivate(raw: Vec4): Vec4 {
  return [DENSITY_SCALE * softplus(raw[0]), sigmoid(raw[1]), sigmoid(raw[2]), sigmoid(raw[3])];
}

/** Chain rule through fieldActivate: dσ/dρ = 10·sigmoid(ρ), dc/de = c(1 − c). */
export function fieldActivateBackward(raw: Vec4, gradient: Vec4): Vec4 {
  const dColour = (e: number): number => sigmoid(e) * sigmoid(-e);
  return [
    gradient[0] * DENSITY_SCALE * sigmoid(raw[0]),
    gradient[1] * dColour(raw[1]),
    gradient[2] * dColour(raw[2]),
    gradient[3] * dColour(raw[3]),
  ];
}

export interface GridPoint {
  base: Vec3;
  fraction: Vec3;
}

/** The 2×2×2 block around p and the position inside it; voxel values sit at voxel centres. */
export function gridPointLocate(
  p: Vec3,
  boxMin: Vec3,
  boxMax: Vec3,
  resolution: number,
): GridPoint {
  const n = Math.max(resolution, 2);
  const base: number[] = [];
  const fraction: number[] = [];
  for (let axis = 0; axis < 3; axis++) {
    const size = boxMax[axis]! - boxMin[axis]!;
    const u = Math.min(Math.max(((p[axis]! - boxMin[axis]!) / size) * n - 0.5, 0), n - 1);
    const b = Math.min(Math.floor(u), n - 2);
    base.push(b);
    fraction.push(u - b);
  }
  return { base: base as unknown as Vec3, fraction: fraction as unknown as Vec3 };
}

/** Product over the axes of f (corner bit set) or 1 − f. */
export function trilinearWeight(fraction: Vec3, corner: number): number {
  let weight = 1;
  for (let axis = 0; axis < 3; axis++) {
    const f = fraction[axis]!;
    weight *= (corner >> axis) & 1 ? f : 1 - f;
  }
  return weight;
}

/** Index of corner k of the block at base, x fastest. */
export function gridCornerIndex(base: Vec3, corner: number, resolution: number): number {
  const x = base[0] + (corner & 1);
  const y = base[1] + ((corner >> 1) & 1);
  const z = base[2] + ((corner >> 2) & 1);
  return (z * resolution + y) * resolution + x;
}

export interface MarchSegment {
  start: number;
  step: number;
  count: number;
}

/** Entry t0, step h = (t1 − t0)/n and sample count n of a ray through the box; n = 0 on a miss. */
export function marchSegment(
  boxMin: Vec3,
  boxMax: Vec3,
  origin: Vec3,
  direction: Vec3,
  steps: number,
): MarchSegment {
  const [t0, t1] = rayBoxSegment(boxMin, boxMax, origin, direction, 0, 1e17);
  if (!(t0 < t1)) return { start: 0, step: 0, count: 0 };
  const n = Math.min(Math.max(steps >>> 0, 1), INVERSE_MAX_STEPS);
  return { start: t0, step: (t1 - t0) / n, count: n };
}

/** One front-to-back step: L += T(1 − e^{−σh})c, T ← T e^{−σh}; state = (L_rgb, T). */
export function compositeStep(state: Vec4, sample: Vec4, step: number): Vec4 {
  const x = Math.max(sample[0], 0) * step;
  const alpha = -Math.expm1(-x);
  const t = state[3];
  return [
    state[0] + t * alpha * sample[1],
    state[1] + t * alpha * sample[2],
    state[2] + t * alpha * sample[3],
    t * Math.exp(-x),
  ];
}

/** (∂L/∂σ, ∂L/∂c) of one sample: h(T_{k+1} g·c − g·B_k) and T_k α_k g. */
export function compositeStepBackward(
  lossGradient: Vec3,
  before: Vec4,
  sample: Vec4,
  step: number,
  behind: Vec3,
): Vec4 {
  const x = Math.max(sample[0], 0) * step;
  const alpha = -Math.expm1(-x);
  const after = before[3] * Math.exp(-x);
  const gDotC =
    lossGradient[0] * sample[1] + lossGradient[1] * sample[2] + lossGradient[2] * sample[3];
  const gDotB =
    lossGradient[0] * behind[0] + lossGradient[1] * behind[1] + lossGradient[2] * behind[2];
  const w = before[3] * alpha;
  return [
    step * (after * gDotC - gDotB),
    w * lossGradient[0],
    w * lossGradient[1],
    w * lossGradient[2],
  ];
}

/** One index per stratum [⌊jN/n⌋, ⌊(j+1)N/n⌋) of [0, N), offset by the hash rngSeed(j, frame). */
export function stratifiedSubsetIndex(
  j: number,
  count: number,
  total: number,
  frame: number,
): number {
  if (count >= total) return j;
  const low = Math.floor((j * total) / count);
  const high = Math.floor(((j + 1) * total) / count);
  return low + (rngSeed(j, frame) % Math.max(high - low, 1));
}

export function pixelSquaredError(radiance: Vec3, target: Vec3): number {
  return (
    (radiance[0] - target[0]) ** 2 + (radiance[1] - target[1]) ** 2 + (radiance[2] - target[2]) ** 2
  );
}

export function pixelLossGradient(radiance: Vec3, target: Vec3, weight: number): Vec3 {
  return [
    2 * weight * (radiance[0] - target[0]),
    2 * weight * (radiance[1] - target[1]),
    2 * weight * (radiance[2] - target[2]),
  ];
}

/** Adam (Kingma & Ba 2015, Algorithm 1): returns [θ, m, v] after one step at iteration t ≥ 1. */
export function adamStep(
  value: number,
  gradient: number,
  m: number,
  v: number,
  iteration: number,
  learningRate: number,
): [number, number, number] {
  const t = Math.max(iteration >>> 0, 1);
  const m1 = ADAM_BETA1 * m + (1 - ADAM_BETA1) * gradient;
  const v1 = ADAM_BETA2 * v + (1 - ADAM_BETA2) * gradient * gradient;
  const mHat = m1 / (1 - ADAM_BETA1 ** t);
  const vHat = v1 / (1 - ADAM_BETA2 ** t);
  return [value - (learningRate * mHat) / (Math.sqrt(vHat) + ADAM_EPSILON), m1, v1];
}

/** d/dρ_i of Σ_j (ρ_i − ρ_j)² over the face neighbours j. */
export function totalVariationGradient(
  value: number,
  neighbourSum: number,
  neighbourCount: number,
): number {
  return 2 * (neighbourCount * value - neighbourSum);
}

/** The Cauchy sparsity prior ln(1 + 2σt²) of one voxel (σt in 1/m). */
export function sparsityPenalty(raw: number): number {
  const sigma = DENSITY_SCALE * softplus(raw);
  return Math.log1p(2 * sigma * sigma);
}

/** d/dρ of sparsityPenalty. */
export function sparsityGradient(raw: number): number {
  const sigma = DENSITY_SCALE * softplus(raw);
  return ((4 * sigma) / (1 + 2 * sigma * sigma)) * DENSITY_SCALE * sigmoid(raw);
}

// ---------------------------------------------------------------------------
// Whole rays through a grid (twin of the kernel's loops).

/** A resolution³ grid of raw parameters (ρ, e_r, e_g, e_b), 4 numbers per voxel, x fastest. */
export interface ParameterGrid {
  resolution: number;
  values: Float64Array;
  boxMin: Vec3;
  boxMax: Vec3;
}

/** The interpolated raw parameters at p, and where p fell. */
export function sampleGridRaw(grid: ParameterGrid, p: Vec3): { raw: Vec4; point: GridPoint } {
  const point = gridPointLocate(p, grid.boxMin, grid.boxMax, grid.resolution);
  const raw = [0, 0, 0, 0];
  for (let corner = 0; corner < 8; corner++) {
    const w = trilinearWeight(point.fraction, corner);
    const index = 4 * gridCornerIndex(point.base, corner, grid.resolution);
    for (let c = 0; c < 4; c++) raw[c]! += w * grid.values[index + c]!;
  }
  return { raw: raw as unknown as Vec4, point };
}

export interface RayResult {
  radiance: Vec3;
  transmittance: number;
  samples: number;
}

/** The colour of one ray: front-to-back compositing of the grid's field, then the background. */
export function marchRayGrid(
  grid: ParameterGrid,
  origin: Vec3,
  direction: Vec3,
  steps: number,
  background: Vec3,
): RayResult {
  const segment = marchSegment(grid.boxMin, grid.boxMax, origin, direction, steps);
  let state: Vec4 = [0, 0, 0, 1];
  for (let k = 0; k < segment.count; k++) {
    const t = segment.start + (k + 0.5) * segment.step;
    const p: Vec3 = [
      origin[0] + t * direction[0],
      origin[1] + t * direction[1],
      origin[2] + t * direction[2],
    ];
    state = compositeStep(state, fieldActivate(sampleGridRaw(grid, p).raw), segment.step);
  }
  return {
    radiance: [
      state[0] + state[3] * background[0],
      state[1] + state[3] * background[1],
      state[2] + state[3] * background[2],
    ],
    transmittance: state[3],
    samples: segment.count,
  };
}

/**
 * Adds ∂L/∂θ of one ray to `gradient` (4 numbers per voxel, like grid.values), where
 * lossGradient = ∂L/∂C of this pixel. Reverse mode from the back: a forward march
 * stores T_k, α_k and the field per sample; then, walking k = n−1 … 0 with the
 * radiance behind B = T_n L_bg + Σ_{j>k} T_j α_j c_j, each sample gets
 * ∂L/∂σ_k = h(T_{k+1} g·c_k − g·B) and ∂L/∂c_k = T_k α_k g, is pulled back through
 * the activations and spread to its eight voxels with the trilinear weights.
 *
 * `magnitude`, when given, receives per parameter the sum over its contributions of
 * the size of the numbers each contribution is computed from (trilinear weight ×
 * activation slope × h·|g|₁·(T_{k+1} + max C) for ρ, × T_k α_k |g_c| for e): the
 * scale against which a float32 evaluation's rounding is measured. The max C term
 * stands for the kernel's B = C − (running sum), which cancels.
 */
export function marchRayGridGradient(
  grid: ParameterGrid,
  origin: Vec3,
  direction: Vec3,
  steps: number,
  background: Vec3,
  lossGradient: Vec3,
  gradient: Float64Array,
  magnitude?: Float64Array,
): void {
  const segment = marchSegment(grid.boxMin, grid.boxMax, origin, direction, steps);
  const n = segment.count;
  if (n === 0) return;
  const h = segment.step;
  const transmittance = new Float64Array(n + 1);
  const alpha = new Float64Array(n);
  const fields: Vec4[] = [];
  const raws: Vec4[] = [];
  const points: GridPoint[] = [];
  transmittance[0] = 1;
  for (let k = 0; k < n; k++) {
    const t = segment.start + (k + 0.5) * h;
    const { raw, point } = sampleGridRaw(grid, [
      origin[0] + t * direction[0],
      origin[1] + t * direction[1],
      origin[2] + t * direction[2],
    ]);
    const field = fieldActivate(raw);
    raws.push(raw);
    points.push(point);
    fields.push(field);
    alpha[k] = -Math.expm1(-field[0] * h);
    transmittance[k + 1] = transmittance[k]! * Math.exp(-field[0] * h);
  }
  const g = lossGradient;
  const gNorm = Math.abs(g[0]) + Math.abs(g[1]) + Math.abs(g[2]);
  const behind = [
    transmittance[n]! * background[0],
    transmittance[n]! * background[1],
    transmittance[n]! * background[2],
  ];
  const pieces: number[] = [];
  if (magnitude) {
    // The final colour C, for the scale of the kernel's cancelling C − (running sum).
    const colour = [...behind];
    for (let k = 0; k < n; k++)
      for (let ch = 0; ch < 3; ch++)
        colour[ch]! += transmittance[k]! * alpha[k]! * fields[k]![ch + 1]!;
    const largest = Math.max(...colour.map(Math.abs));
    for (let k = 0; k < n; k++) pieces.push(h * gNorm * (transmittance[k + 1]! + largest));
  }
  for (let k = n - 1; k >= 0; k--) {
    const c = fields[k]!;
    const w = transmittance[k]! * alpha[k]!;
    const gDotC = g[0] * c[1] + g[1] * c[2] + g[2] * c[3];
    const gDotB = g[0] * behind[0]! + g[1] * behind[1]! + g[2] * behind[2]!;
    const dField: Vec4 = [
      h * (transmittance[k + 1]! * gDotC - gDotB),
      w * g[0],
      w * g[1],
      w * g[2],
    ];
    for (let ch = 0; ch < 3; ch++) behind[ch]! += w * c[ch + 1]!;
    const dRaw = fieldActivateBackward(raws[k]!, dField);
    const scale = magnitude
      ? fieldActivateBackward(raws[k]!, [
          pieces[k]!,
          w * Math.abs(g[0]),
          w * Math.abs(g[1]),
          w * Math.abs(g[2]),
        ])
      : null;
    const point = points[k]!;
    for (let corner = 0; corner < 8; corner++) {
      const weight = trilinearWeight(point.fraction, corner);
      const index = 4 * gridCornerIndex(point.base, corner, grid.resolution);
      for (let ch = 0; ch < 4; ch++) {
        gradient[index + ch]! += weight * dRaw[ch]!;
        if (magnitude && scale) magnitude[index + ch]! += weight * Math.abs(scale[ch]!);
      }
    }
  }
}
