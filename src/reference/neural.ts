// Float64 twin of shaders/neural.wesl (chapter 8): the multiresolution hash encoding
// and tiny MLP of Instant-NGP (Müller et al. 2022), forward and backward, each written
// from its formula; on top of them the whole-ray march through the neural field and
// its gradient with respect to every parameter (hash table entries and MLP weights).
// As for the voxel grid (inverse.ts), the twin's ray gradient runs the reverse-mode
// recursion from the back of the ray with every sample stored, while the kernel
// re-marches from the front; the tests hold both against central finite differences
// of the twin's loss.
import {
  compositeStep,
  fieldActivate,
  fieldActivateBackward,
  marchSegment,
  trilinearWeight,
  type GridPoint,
  type Vec4,
} from './inverse.ts';
import type { Vec3 } from './phase.ts';

export const NEURAL_LEVELS = 8;
export const NEURAL_FEATURES = 2;
export const NEURAL_INPUTS = NEURAL_LEVELS * NEURAL_FEATURES;
export const NEURAL_HIDDEN = 16;
/** Offsets (in floats) of b₁, W₂ and b₂ in the packed weights; 340 weights in all. */
export const NEURAL_B1 = 256;
export const NEURAL_W2 = 272;
export const NEURAL_B2 = 336;
export const NEURAL_MLP_SIZE = 340;

/** N_l = ⌊4·2^{l/2}⌋ in integers (4√2 as 181/32), l clamped to 15. */
export function hashLevelResolution(level: number): number {
  const l = Math.min(level >>> 0, 15);
  if ((l & 1) === 0) return 4 << (l >> 1);
  return Math.floor((181 << (l >> 1)) / 32);
}

/** (v_x·1 ⊕ v_y·2654435761 ⊕ v_z·805459861) mod T, products modulo 2³², T a power of two. */
export function spatialHash(vertex: Vec3, tableSize: number): number {
  const h = (vertex[0] ^ Math.imul(vertex[1], 2654435761) ^ Math.imul(vertex[2], 805459861)) >>> 0;
  return (h & (tableSize - 1)) >>> 0;
}

/** Dense index (x fastest) while (N + 1)³ ≤ T, else spatialHash. */
export function hashGridIndex(vertex: Vec3, resolution: number, tableSize: number): number {
  const side = resolution + 1;
  if (side ** 3 <= tableSize) return (vertex[2] * side + vertex[1]) * side + vertex[0];
  return spatialHash(vertex, tableSize);
}

/** The cell of a level (N cells per axis over the box) around p, and p's place in it. */
export function hashCellLocate(p: Vec3, boxMin: Vec3, boxMax: Vec3, resolution: number): GridPoint {
  const n = Math.max(resolution, 1);
  const base: number[] = [];
  const fraction: number[] = [];
  for (let axis = 0; axis < 3; axis++) {
    const unit = (p[axis]! - boxMin[axis]!) / (boxMax[axis]! - boxMin[axis]!);
    const u = Math.min(Math.max(unit, 0), 1) * n;
    const b = Math.min(Math.floor(u), n - 1);
    base.push(b);
    fraction.push(u - b);
  }
  return { base: base as unknown as Vec3, fraction: fraction as unknown as Vec3 };
}

/** max(x, 0) per component. */
export function relu(x: Vec4): Vec4 {
  return [Math.max(x[0], 0), Math.max(x[1], 0), Math.max(x[2], 0), Math.max(x[3], 0)];
}

/**
 * The MLP's forward pass on the 16 features y: writes the pre-activations
 * a = W₁y + b₁ to `hidden` (16 numbers) and returns W₂ ReLU(a) + b₂ = (ρ, e_r, e_g, e_b).
 * `mlp` holds the 340 packed weights (layout of shaders/neural.wesl) from `offset`.
 */
export function neuralForward(
  mlp: ArrayLike<number>,
  features: ArrayLike<number>,
  hidden: Float64Array,
  offset = 0,
): Vec4 {
  const out = [0, 1, 2, 3].map((o) => mlp[offset + NEURAL_B2 + o]!);
  for (let j = 0; j < NEURAL_HIDDEN; j++) {
    let a = mlp[offset + NEURAL_B1 + j]!;
    for (let i = 0; i < NEURAL_INPUTS; i++) a += mlp[offset + 16 * j + i]! * features[i]!;
    hidden[j] = a;
    const h = Math.max(a, 0);
    for (let o = 0; o < 4; o++) out[o]! += mlp[offset + NEURAL_W2 + 4 * j + o]! * h;
  }
  return out as unknown as Vec4;
}

/**
 * The MLP's backward pass for one sample with δ = ∂L/∂(ρ, e): adds ∂L/∂W₂ = δhᵀ,
 * ∂L/∂b₂ = δ, ∂L/∂W₁ = γyᵀ, ∂L/∂b₁ = γ (γ_j = [a_j > 0](W₂ᵀδ)_j) to `gradient` (from
 * `gradientOffset`, the weights' layout; the weights are read from `offset`) and writes
 * ∂L/∂y = W₁ᵀγ to dFeatures.
 */
export function neuralBackward(
  mlp: ArrayLike<number>,
  features: ArrayLike<number>,
  hidden: ArrayLike<number>,
  delta: Vec4,
  gradient: Float64Array,
  dFeatures: Float64Array,
  offset = 0,
  gradientOffset = offset,
): void {
  const go = gradientOffset;
  for (let o = 0; o < 4; o++) gradient[go + NEURAL_B2 + o]! += delta[o]!;
  dFeatures.fill(0, 0, NEURAL_INPUTS);
  for (let j = 0; j < NEURAL_HIDDEN; j++) {
    const a = hidden[j]!;
    const h = Math.max(a, 0);
    let gamma = 0;
    for (let o = 0; o < 4; o++) {
      gradient[go + NEURAL_W2 + 4 * j + o]! += h * delta[o]!;
      gamma += mlp[offset + NEURAL_W2 + 4 * j + o]! * delta[o]!;
    }
    if (!(a > 0)) gamma = 0;
    gradient[go + NEURAL_B1 + j]! += gamma;
    for (let i = 0; i < NEURAL_INPUTS; i++) {
      gradient[go + 16 * j + i]! += gamma * features[i]!;
      dFeatures[i]! += gamma * mlp[offset + 16 * j + i]!;
    }
  }
}

// ---------------------------------------------------------------------------
// Whole rays through a neural field (twin of the kernel's loops).

/**
 * A neural field: the hash tables of every level, then the MLP, in one array of
 * parameters. Level l's entry e, feature f is values[(l·T + e)·F + f]; the MLP's 340
 * weights start at mlpOffset = L·T·F.
 */
export interface NeuralField {
  tableSize: number;
  values: Float64Array;
  boxMin: Vec3;
  boxMax: Vec3;
}

export function neuralMlpOffset(tableSize: number): number {
  return NEURAL_LEVELS * tableSize * NEURAL_FEATURES;
}

export function neuralParameterCount(tableSize: number): number {
  return neuralMlpOffset(tableSize) + NEURAL_MLP_SIZE;
}

/** Where one sample reads the tables: 8 corners per level, their entries (float index) and weights. */
export interface NeuralEncoding {
  features: Float64Array;
  /** Index of feature 0 of corner k of level l at 8l + k. */
  entries: Int32Array;
  weights: Float64Array;
}

/** The 16 features at p: per level, the trilinear interpolation of its cell's eight vertices. */
export function neuralEncode(field: NeuralField, p: Vec3): NeuralEncoding {
  const features = new Float64Array(NEURAL_INPUTS);
  const entries = new Int32Array(8 * NEURAL_LEVELS);
  const weights = new Float64Array(8 * NEURAL_LEVELS);
  const T = field.tableSize;
  for (let level = 0; level < NEURAL_LEVELS; level++) {
    const n = hashLevelResolution(level);
    const point = hashCellLocate(p, field.boxMin, field.boxMax, n);
    for (let corner = 0; corner < 8; corner++) {
      const vertex: Vec3 = [
        point.base[0] + (corner & 1),
        point.base[1] + ((corner >> 1) & 1),
        point.base[2] + ((corner >> 2) & 1),
      ];
      const entry = (level * T + hashGridIndex(vertex, n, T)) * NEURAL_FEATURES;
      const w = trilinearWeight(point.fraction, corner);
      entries[8 * level + corner] = entry;
      weights[8 * level + corner] = w;
      for (let f = 0; f < NEURAL_FEATURES; f++)
        features[NEURAL_FEATURES * level + f]! += w * field.values[entry + f]!;
    }
  }
  return { features, entries, weights };
}

/** The raw outputs (ρ, e) of the field at p, with what the backward pass needs. */
export function sampleNeuralRaw(
  field: NeuralField,
  p: Vec3,
): { raw: Vec4; encoding: NeuralEncoding; hidden: Float64Array } {
  const encoding = neuralEncode(field, p);
  const hidden = new Float64Array(NEURAL_HIDDEN);
  const raw = neuralForward(
    field.values,
    encoding.features,
    hidden,
    neuralMlpOffset(field.tableSize),
  );
  return { raw, encoding, hidden };
}

/** The colour of one ray through the neural field (midpoint samples, then the background). */
export function marchRayNeural(
  field: NeuralField,
  origin: Vec3,
  direction: Vec3,
  steps: number,
  background: Vec3,
): Vec3 {
  const segment = marchSegment(field.boxMin, field.boxMax, origin, direction, steps);
  let state: Vec4 = [0, 0, 0, 1];
  for (let k = 0; k < segment.count; k++) {
    const t = segment.start + (k + 0.5) * segment.step;
    const p: Vec3 = [
      origin[0] + t * direction[0],
      origin[1] + t * direction[1],
      origin[2] + t * direction[2],
    ];
    state = compositeStep(state, fieldActivate(sampleNeuralRaw(field, p).raw), segment.step);
  }
  return [
    state[0] + state[3] * background[0],
    state[1] + state[3] * background[1],
    state[2] + state[3] * background[2],
  ];
}

/**
 * Adds ∂L/∂θ of one ray to `gradient` (like field.values) for lossGradient = ∂L/∂C of
 * its pixel: reverse mode from the back of the ray (as inverse.ts's
 * marchRayGridGradient), each sample's ∂L/∂(σ, c) pulled back through the activations,
 * the MLP (neuralBackward) and the trilinear weights of the encoding to the tables.
 *
 * `magnitude`, when given, receives per parameter the sum of |contribution| (the scale
 * against which a float32 sum of the same contributions is measured).
 */
export function marchRayNeuralGradient(
  field: NeuralField,
  origin: Vec3,
  direction: Vec3,
  steps: number,
  background: Vec3,
  lossGradient: Vec3,
  gradient: Float64Array,
  magnitude?: Float64Array,
): void {
  const segment = marchSegment(field.boxMin, field.boxMax, origin, direction, steps);
  const n = segment.count;
  if (n === 0) return;
  const h = segment.step;
  const offset = neuralMlpOffset(field.tableSize);
  const transmittance = new Float64Array(n + 1);
  transmittance[0] = 1;
  const samples: ReturnType<typeof sampleNeuralRaw>[] = [];
  const fields: Vec4[] = [];
  for (let k = 0; k < n; k++) {
    const t = segment.start + (k + 0.5) * h;
    const sample = sampleNeuralRaw(field, [
      origin[0] + t * direction[0],
      origin[1] + t * direction[1],
      origin[2] + t * direction[2],
    ]);
    samples.push(sample);
    fields.push(fieldActivate(sample.raw));
    transmittance[k + 1] = transmittance[k]! * Math.exp(-fields[k]![0] * h);
  }
  const g = lossGradient;
  const behind = [0, 1, 2].map((c) => transmittance[n]! * background[c]!);
  const dFeatures = new Float64Array(NEURAL_INPUTS);
  const local = magnitude ? new Float64Array(NEURAL_MLP_SIZE) : null;
  for (let k = n - 1; k >= 0; k--) {
    const c = fields[k]!;
    const w = transmittance[k]! * -Math.expm1(-c[0] * h);
    const gDotC = g[0] * c[1] + g[1] * c[2] + g[2] * c[3];
    const gDotB = g[0] * behind[0]! + g[1] * behind[1]! + g[2] * behind[2]!;
    const dField: Vec4 = [
      h * (transmittance[k + 1]! * gDotC - gDotB),
      w * g[0],
      w * g[1],
      w * g[2],
    ];
    for (let ch = 0; ch < 3; ch++) behind[ch]! += w * c[ch + 1]!;
    const { raw, encoding, hidden } = samples[k]!;
    const delta = fieldActivateBackward(raw, dField);
    if (local) {
      // This sample's MLP contributions alone, for their magnitudes.
      local.fill(0);
      neuralBackward(field.values, encoding.features, hidden, delta, local, dFeatures, offset, 0);
      for (let i = 0; i < NEURAL_MLP_SIZE; i++) {
        gradient[offset + i]! += local[i]!;
        magnitude![offset + i]! += Math.abs(local[i]!);
      }
    } else {
      neuralBackward(field.values, encoding.features, hidden, delta, gradient, dFeatures, offset);
    }
    for (let level = 0; level < NEURAL_LEVELS; level++)
      for (let corner = 0; corner < 8; corner++) {
        const entry = encoding.entries[8 * level + corner]!;
        const weight = encoding.weights[8 * level + corner]!;
        for (let f = 0; f < NEURAL_FEATURES; f++) {
          const d = weight * dFeatures[NEURAL_FEATURES * level + f]!;
          gradient[entry + f]! += d;
          if (magnitude) magnitude[entry + f]! += Math.abs(d);
        }
      }
  }
}
