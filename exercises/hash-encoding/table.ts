// The "learned" hash table of the hash-encoding exercise (chapter 8) and its float64
// twin. The student's function reads entries through tableFeature(level, entry,
// feature), which stands in for the trained tables of the widget's neural field: a
// fixed pseudo-random number per (level, entry, feature), uniform in [−1, 1). Every u32
// entry is readable, so a wrong index (an unmasked hash, a negative remainder cast to
// u32) reads a wrong number instead of going out of bounds, and no two entries are
// related, so a wrong index is caught wherever it differs from the right one.
import {
  NEURAL_FEATURES,
  NEURAL_LEVELS,
  neuralEncode,
  type NeuralField,
} from '../../src/reference/neural.ts';
import type { Vec3 } from '../../src/reference/phase.ts';

/** The box the levels cut into cells (m): the widget's. */
export const EXERCISE_BOX_MIN: Vec3 = [-1, -1, -1];
export const EXERCISE_BOX_MAX: Vec3 = [1, 1, 1];

/**
 * WGSL of the table: PCG's output permutation (O'Neill 2014, RXS-M-XS) of a word
 * that mixes level, entry and feature; the top 24 bits to a float in [−1, 1) exactly.
 */
export const TABLE_WGSL = `// The learned table, stood in for by fixed pseudo-random numbers: feature f (0 or 1)
// of entry e of level l, uniform in [−1, 1). Entries are numbered 0 … T − 1.
fn tableFeature(level: u32, entry: u32, feature: u32) -> f32 {
  var h = entry * 2u + (feature & 1u) + level * 0x9e3779b9u;
  h = h * 747796405u + 2891336453u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  h = (h >> 22u) ^ h;
  return f32(h >> 8u) * (2.0 / 16777216.0) - 1.0;
}
`;

/** Float64 twin of tableFeature (exact: the WGSL's arithmetic is integer until the last, exact, step). */
export function tableFeature(level: number, entry: number, feature: number): number {
  let h = (Math.imul(entry, 2) + (feature & 1) + Math.imul(level, 0x9e3779b9)) >>> 0;
  h = (Math.imul(h, 747796405) + 2891336453) >>> 0;
  h = Math.imul(((h >>> ((h >>> 28) + 4)) ^ h) >>> 0, 277803737) >>> 0;
  h = ((h >>> 22) ^ h) >>> 0;
  return (h >>> 8) * (2 / 16777216) - 1;
}

/** The exercise's table as a neural field of the book's reference (MLP weights zero). */
export function exerciseField(tableSize: number): NeuralField {
  const values = new Float64Array(NEURAL_LEVELS * tableSize * NEURAL_FEATURES + 340);
  for (let level = 0; level < NEURAL_LEVELS; level++)
    for (let entry = 0; entry < tableSize; entry++)
      for (let f = 0; f < NEURAL_FEATURES; f++)
        values[(level * tableSize + entry) * NEURAL_FEATURES + f] = tableFeature(level, entry, f);
  return { tableSize, values, boxMin: EXERCISE_BOX_MIN, boxMax: EXERCISE_BOX_MAX };
}

/**
 * The float64 answer for the arguments of one case, [x, y, z, level, tableSize,
 * feature]: src/reference/neural.ts's neuralEncode on the exercise's table.
 */
export function expectedFeature(
  args: readonly number[],
  fields = new Map<number, NeuralField>(),
): number {
  const [x, y, z, level, tableSize, feature] = args as [
    number,
    number,
    number,
    number,
    number,
    number,
  ];
  let field = fields.get(tableSize);
  if (!field) {
    field = exerciseField(tableSize);
    fields.set(tableSize, field);
  }
  return neuralEncode(field, [x, y, z]).features[NEURAL_FEATURES * level + feature]!;
}
