// The hash encoding's hidden checks: points, levels, table sizes and features drawn from
// the grading seed (src/grading/checks/generated.ts), so that no table of inputs
// answers them. Each check mixes dense and hashed levels or points inside cells, where
// every one of the public checks' mistakes shows.
import type { CheckSpec } from '../../src/grading/exercise.ts';
import { caseSampler, type CaseSampler } from '../../src/grading/checks/generated.ts';
import { hashLevelResolution } from '../../src/reference/neural.ts';
import { TOLERANCE, encodingCase, vertexPoint } from './exercise.ts';

function point(r: CaseSampler, extent: number): [number, number, number] {
  return [r.uniform(-extent, extent), r.uniform(-extent, extent), r.uniform(-extent, extent)];
}

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'generated-cases',
    name: 'Arbitrary points, levels and table sizes',
    points: 3,
    message:
      'Your feature is wrong for some point, level and table size: check N_l, the cell and the ' +
      'position in it, the dense index or the spatial hash, and the trilinear weights.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hash-encoding arbitrary');
      return Array.from({ length: 32 }, (_, k) => {
        const level = r.integer(0, 7);
        const log2 = r.integer(8, 16);
        return encodingCase(
          `case ${k + 1}: level ${level}, T = 2^${log2}`,
          point(r, 1),
          level,
          log2,
          r.integer(0, 1),
        );
      });
    },
  },
  {
    kind: 'generated-cases',
    name: 'Vertices of every level',
    points: 2,
    message:
      'At a vertex the feature is that vertex’s own entry: N_l = ⌊4·2^{l/2}⌋, the dense index ' +
      'while (N_l + 1)³ ≤ T, else the spatial hash with the primes in the order x, y, z and mod T on u32.',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hash-encoding vertices');
      return Array.from({ length: 24 }, (_, k) => {
        const level = r.integer(0, 7);
        const n = hashLevelResolution(level);
        const vertex: [number, number, number] = [
          r.integer(1, n - 1),
          r.integer(1, n - 1),
          r.integer(1, n - 1),
        ];
        const log2 = r.integer(8, 14);
        return encodingCase(
          `case ${k + 1}: vertex ${vertex.join(', ')} of level ${level}, T = 2^${log2}`,
          vertexPoint(vertex, level),
          level,
          log2,
          r.integer(0, 1),
        );
      });
    },
  },
  {
    kind: 'generated-cases',
    name: 'Outside the box and on its faces',
    points: 1,
    message:
      'Points outside the box read its nearest point (clamp (p + 1)/2 to [0, 1]); on the face p = 1 ' +
      'the cell is the last one (base = N − 1, f = 1).',
    ...TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'hash-encoding outside');
      return Array.from({ length: 8 }, (_, k) => {
        const p = point(r, 1);
        const axis = k % 3;
        p[axis] = k < 4 ? r.sign() * r.uniform(1, 3) : r.sign();
        // Every other case on a hashed level (N_l ≥ 16, T ≤ 2^12 < 17³), so that the
        // check needs the hash as well as the clamp whatever the seed.
        const level = k % 2 === 0 ? r.integer(0, 7) : r.integer(4, 7);
        const log2 = k % 2 === 0 ? r.integer(8, 16) : r.integer(8, 12);
        return encodingCase(
          `case ${k + 1}: level ${level}, T = 2^${log2}`,
          p,
          level,
          log2,
          r.integer(0, 1),
        );
      });
    },
  },
];
