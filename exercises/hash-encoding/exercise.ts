// The multiresolution hash encoding's lookup of one level (chapter 8, "A neural field"):
// the public part of the exercise. The student writes what the widget's neural field
// does for each level at every sample (shaders/neural.wesl: hashLevelResolution,
// hashCellLocate, hashGridIndex with the spatial hash of Müller et al. 2022, eq. 4, and
// the trilinear interpolation of the cell's eight vertices), reading a fixed table
// (table.ts) instead of a trained one. The reference is the library's code; the float64
// twin (src/reference/neural.ts on the same table) agrees with it
// (tests/grading/hashEncoding.test.ts).
import type { CaseSpec, ExerciseDefinition } from '../../src/grading/exercise.ts';
import { hashLevelResolution } from '../../src/reference/neural.ts';
import { TABLE_WGSL } from './table.ts';

/**
 * Tolerance of every case: a feature is a convex combination of eight table numbers in
 * [−1, 1). The f32 rounding of p (≈ 6·10⁻⁸) moves u = (p + 1)/2·N_l by up to ≈ 1.4·10⁻⁶
 * on the finest level (N = 45), and the feature by that times a difference of table
 * numbers (≤ 2): a few 10⁻⁶, and a correct solution that computes u in another order
 * rounds differently by as much again. A wrong entry or weight moves the feature by
 * about its own size (0.1 … 1).
 */
export const TOLERANCE = { rtol: 1e-4, atol: 1e-4 } as const;

/** A case [x, y, z, level, T, feature] with its coordinates rounded to f32. */
export function encodingCase(
  label: string,
  p: readonly [number, number, number],
  level: number,
  tableLog2: number,
  feature: number,
): CaseSpec {
  return { label, args: [...p.map(Math.fround), level, 2 ** tableLog2, feature] };
}

/** The point of the box at vertex v (integers 0 … N_l) of a level: −1 + 2v/N_l per axis. */
export function vertexPoint(
  vertex: readonly [number, number, number],
  level: number,
): [number, number, number] {
  const n = hashLevelResolution(level);
  return vertex.map((v) => -1 + (2 * v) / n) as [number, number, number];
}

/** Interior vertices of a level, spread over its cells (fixed for the public checks). */
function interiorVertex(level: number, k: number): [number, number, number] {
  const n = hashLevelResolution(level);
  const pick = (a: number): number => 1 + ((a * 7 + k * 5 + level * 3) % (n - 1));
  return [pick(1), pick(2 + k), pick(5 + 2 * k)];
}

/** Fixed points inside the box, off every vertex and face of every level. */
const INSIDE: readonly [number, number, number][] = [
  [0.1234, -0.4567, 0.789],
  [-0.8123, 0.3321, -0.1017],
  [0.5551, 0.6013, -0.7349],
  [-0.2718, -0.9142, 0.4142],
];

export const EXERCISE: ExerciseDefinition = {
  id: 'hash-encoding',
  chapter: '08-inverse-volume-rendering',
  title: 'One level of the multiresolution hash encoding',
  starter: `// Feature \`feature\` (0 or 1) of level \`level\` (0 … 7) of Instant-NGP's hash encoding at
// the point p = (x, y, z) of the box [−1, 1]³, with T = tableSize entries per level (a
// power of two). tableFeature(level, entry, feature) reads entry 0 … T − 1 of the level.
fn hashEncodeLevel(x: f32, y: f32, z: f32, level: u32, tableSize: u32, feature: u32) -> f32 {
  // Your code here: N_l, the cell of p and its place in it, the eight vertices'
  // entries (dense or hashed), and their trilinear interpolation.
  return tableFeature(level, 0u, feature);
}
`,
  signature:
    'fn hashEncodeLevel(x: f32, y: f32, z: f32, level: u32, tableSize: u32, feature: u32) -> f32',
  hints: [
    'N_l = ⌊4·2^{l/2}⌋ = 4, 5, 8, 11, 16, 22, 32, 45. In f32, exp2 need not be exact at integers: compute it in integers, 4 << (l/2) for even l and (181 << (l/2)) / 32 for odd l (181/32 = 4√2 to the floor).',
    'u = clamp((p + 1)/2, 0, 1)·N per axis; the cell is base = min(floor(u), N − 1) (so p = 1 stays in the last cell) and the position in it f = u − base.',
    'Corner c = 0 … 7 is base + (c & 1, (c >> 1) & 1, (c >> 2) & 1) with weight Π over the axes of f (offset 1) or 1 − f (offset 0).',
    'Entry of vertex v: while (N + 1)³ ≤ T, (v_z (N + 1) + v_y)(N + 1) + v_x; else (v_x ^ v_y·2654435761 ^ v_z·805459861) & (T − 1), all in u32 (the products wrap modulo 2³²).',
  ],
  gradingNotes:
    'Each case passes when |f − f_ref| ≤ 1e-4 + 1e-4·|f_ref|, against the book’s hash encoding ' +
    '(shaders/neural.wesl) on the same table. Public: vertices of the dense levels, points inside ' +
    'cells of dense and hashed levels, vertices of hashed levels, points outside the box. Hidden ' +
    'checks draw points, levels, table sizes and features from the grading seed.',
  subject: {
    name: 'hashEncodeLevel',
    params: [
      { name: 'x', type: 'f32' },
      { name: 'y', type: 'f32' },
      { name: 'z', type: 'f32' },
      { name: 'level', type: 'u32' },
      { name: 'tableSize', type: 'u32' },
      { name: 'feature', type: 'u32' },
    ],
    result: 'f32',
  },
  helpers: {
    imports: [],
    wgsl: TABLE_WGSL,
  },
  reference: `import package::inverse::trilinearWeight;
import package::neural::{hashCellLocate, hashGridIndex, hashLevelResolution};
fn hashEncodeLevel(x: f32, y: f32, z: f32, level: u32, tableSize: u32, feature: u32) -> f32 {
  let n = hashLevelResolution(level);
  let point = hashCellLocate(vec3f(x, y, z), vec3f(-1.0), vec3f(1.0), n);
  var value = 0.0;
  for (var corner = 0u; corner < 8u; corner++) {
    let vertex = point.base + vec3u(corner & 1u, (corner >> 1u) & 1u, (corner >> 2u) & 1u);
    let entry = hashGridIndex(vertex, n, tableSize);
    value += trilinearWeight(point.fraction, corner) * tableFeature(level, entry, feature);
  }
  return value;
}`,
  checks: [
    {
      kind: 'cases',
      name: 'Level resolution: vertices of the dense levels',
      points: 2,
      message:
        'At a vertex of level l the feature is that vertex’s own entry, so only N_l and the ' +
        'dense index matter here: check N_l = ⌊4·2^{l/2}⌋ = 4, 5, 8, 11, 16, 22, 32 for l = 0 … 6 ' +
        '(level 0 has 4 cells, not 5: l counts from 0), u = (p + 1)/2·N, and the entry ' +
        '(v_z (N + 1) + v_y)(N + 1) + v_x with N + 1 vertices per axis.',
      ...TOLERANCE,
      cases: [0, 1, 2, 3, 4, 5, 6].flatMap((level) =>
        [0, 1].map((k) =>
          encodingCase(
            `vertex ${interiorVertex(level, k).join(', ')} of level ${level}, T = 2^16`,
            vertexPoint(interiorVertex(level, k), level),
            level,
            16,
            k,
          ),
        ),
      ),
    },
    {
      kind: 'cases',
      name: 'Trilinear interpolation inside the cells (dense levels)',
      points: 2,
      message:
        'Inside a cell the feature is the trilinear interpolation of the cell’s eight vertices: ' +
        'weight Π f or 1 − f per axis with f = u − base the position in the cell, summed over all ' +
        'eight (not the nearest vertex, not the cell centre).',
      ...TOLERANCE,
      cases: [0, 1, 2, 3].flatMap((level) =>
        INSIDE.map((p, k) =>
          encodingCase(`p = (${p.join(', ')}), level ${level}, T = 2^12`, p, level, 12, k & 1),
        ),
      ),
    },
    {
      kind: 'cases',
      name: 'Spatial hash: vertices of the hashed levels',
      points: 2,
      message:
        'On the levels with more than T vertices the entry is the spatial hash ' +
        '(v_x·1 ⊕ v_y·2654435761 ⊕ v_z·805459861) mod T: the primes in that order (x, y, z), ' +
        'products and XOR in u32 (wrapping modulo 2³²), and mod T as h & (T − 1) or h % T on the ' +
        'u32 (not on an i32, whose remainder is negative when the top bit is set, and not left out).',
      ...TOLERANCE,
      cases: [3, 4, 5, 6, 7].flatMap((level) =>
        [0, 1, 2].map((k) =>
          encodingCase(
            `vertex ${interiorVertex(level, k).join(', ')} of level ${level}, T = 2^10`,
            vertexPoint(interiorVertex(level, k), level),
            level,
            10,
            k & 1,
          ),
        ),
      ),
    },
    {
      kind: 'cases',
      name: 'Hashed levels inside the cells',
      points: 2,
      message:
        'Inside the cells of the hashed levels: the spatial hash of each of the eight vertices and ' +
        'their trilinear interpolation.',
      ...TOLERANCE,
      cases: [4, 5, 6, 7].flatMap((level) =>
        INSIDE.map((p, k) =>
          encodingCase(`p = (${p.join(', ')}), level ${level}, T = 2^12`, p, level, 12, k & 1),
        ),
      ),
    },
    {
      kind: 'cases',
      name: 'Points outside the box',
      points: 1,
      message:
        'A point outside the box reads the nearest point of the box: clamp (p + 1)/2 to [0, 1] ' +
        'before scaling by N, and keep p = 1 in the last cell (base ≤ N − 1).',
      ...TOLERANCE,
      cases: [
        encodingCase('p = (1.5, 0.2, −0.3), level 2', [1.5, 0.2, -0.3], 2, 12, 0),
        encodingCase('p = (−2, −1.25, 0.4), level 5', [-2, -1.25, 0.4], 5, 12, 1),
        encodingCase('p = (1, 1, 1), level 7', [1, 1, 1], 7, 12, 0),
        encodingCase('p = (0.3, 3, −1), level 6', [0.3, 3, -1], 6, 14, 1),
      ],
    },
  ],
};
