// Writes public/volumes/smoke-24.f32, the density grid of the example scenes
// (public/scenes/*.json): 24×24×24 float32 samples, little-endian, x fastest, a
// rising plume of a few Gaussian puffs modulated by deterministic value noise, 0 at the
// faces. Densities are dimensionless (a scene's σa, σs are per unit density).
// Run: node scripts/make-smoke-volume.mjs
import { writeFileSync } from 'node:fs';

const N = 24;
const hash = (i, j, k) => {
  let h = (i * 374761393 + j * 668265263 + k * 2147483647) >>> 0;
  h = Math.imul(h ^ (h >>> 13), 1274126177) >>> 0;
  return ((h ^ (h >>> 16)) >>> 0) / 4294967296;
};
const smooth = (t) => t * t * (3 - 2 * t);
const noise = (x, y, z) => {
  const [i, j, k] = [Math.floor(x), Math.floor(y), Math.floor(z)];
  const [u, v, w] = [smooth(x - i), smooth(y - j), smooth(z - k)];
  let sum = 0;
  for (let c = 0; c < 8; c++) {
    const [a, b, d] = [c & 1, (c >> 1) & 1, (c >> 2) & 1];
    sum += (a ? u : 1 - u) * (b ? v : 1 - v) * (d ? w : 1 - w) * hash(i + a, j + b, k + d);
  }
  return sum;
};
const puffs = [
  [0.5, 0.25, 0.5, 0.16],
  [0.45, 0.5, 0.55, 0.18],
  [0.58, 0.72, 0.45, 0.15],
];
const values = new Float32Array(N * N * N);
for (let k = 0; k < N; k++)
  for (let j = 0; j < N; j++)
    for (let i = 0; i < N; i++) {
      const [x, y, z] = [(i + 0.5) / N, (j + 0.5) / N, (k + 0.5) / N];
      let density = 0;
      for (const [cx, cy, cz, r] of puffs)
        density += Math.exp(-((x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2) / (2 * r * r));
      const detail = 0.55 + 0.9 * noise(6 * x, 6 * y, 6 * z);
      const edge = Math.min(x, y, z, 1 - x, 1 - y, 1 - z);
      const fade = Math.min(1, edge / 0.08);
      values[i + N * (j + N * k)] = Math.max(0, density * detail * fade);
    }
writeFileSync(
  new URL('../public/volumes/smoke-24.f32', import.meta.url),
  Buffer.from(values.buffer),
);
let max = 0;
for (const v of values) max = Math.max(max, v);
console.log(`wrote public/volumes/smoke-24.f32 (${N}³ samples, max density ${max.toFixed(3)})`);
