// Float64 twin of shaders/medium.wesl: a 1D medium along a ray, answering σt(s),
// the exact τ(s0, s1) and a majorant on a segment. Same field names as the WGSL
// struct Medium1D; `cells` has at most GRID1D_MAX_CELLS entries.
import {
  FINITE_LIMIT,
  GRID1D_MAX_CELLS,
  opticalThicknessGrid1D,
  opticalThicknessHomogeneous,
  opticalThicknessSine,
  saturatingProduct,
} from './transmittance.ts';
import { planeCrossing, rayBoxSegment } from './geometry.ts';

export const MEDIUM_HOMOGENEOUS = 0;
export const MEDIUM_SINE = 1;
export const MEDIUM_GRID = 2;

export interface Medium1D {
  kind: number;
  sigma0: number;
  amplitude: number;
  frequency: number;
  phase: number;
  cellSize: number;
  cellCount: number;
  cells: readonly number[];
}

export function homogeneousMedium(sigmaT: number): Medium1D {
  return {
    kind: MEDIUM_HOMOGENEOUS,
    sigma0: sigmaT,
    amplitude: 0,
    frequency: 0,
    phase: 0,
    cellSize: 0,
    cellCount: 0,
    cells: [],
  };
}

export function sineMedium(
  sigma0: number,
  amplitude: number,
  frequency: number,
  phase = 0,
): Medium1D {
  return {
    kind: MEDIUM_SINE,
    sigma0,
    amplitude,
    frequency,
    phase,
    cellSize: 0,
    cellCount: 0,
    cells: [],
  };
}

export function gridMedium(cells: readonly number[], cellSize: number): Medium1D {
  if (cells.length > GRID1D_MAX_CELLS)
    throw new Error(`a 1D grid has at most ${GRID1D_MAX_CELLS} cells`);
  return {
    kind: MEDIUM_GRID,
    sigma0: 0,
    amplitude: 0,
    frequency: 0,
    phase: 0,
    cellSize,
    cellCount: cells.length,
    cells,
  };
}

export function mediumExtinction(medium: Medium1D, s: number): number {
  switch (medium.kind) {
    case MEDIUM_SINE: {
      const a = Math.min(Math.max(medium.amplitude, 0), 1);
      // No coefficient clamp (units do not matter); the value is capped at the largest f32.
      return saturatingProduct(
        medium.sigma0,
        1 + a * Math.sin(medium.frequency * s + medium.phase),
      );
    }
    case MEDIUM_GRID: {
      const count = Math.min(medium.cellCount, GRID1D_MAX_CELLS);
      if (s < 0 || medium.cellSize <= 0 || s >= count * medium.cellSize) return 0;
      const index = Math.min(Math.floor(s / medium.cellSize), count - 1);
      return Math.max(medium.cells[index] ?? 0, 0);
    }
    default:
      return Math.max(medium.sigma0, 0);
  }
}

export function mediumOpticalDepth(medium: Medium1D, s0: number, s1: number): number {
  switch (medium.kind) {
    case MEDIUM_SINE:
      return opticalThicknessSine(
        medium.sigma0,
        medium.amplitude,
        medium.frequency,
        medium.phase,
        s0,
        s1,
      );
    case MEDIUM_GRID:
      return opticalThicknessGrid1D(medium.cells, medium.cellCount, medium.cellSize, s0, s1);
    default:
      return opticalThicknessHomogeneous(medium.sigma0, s1 - s0);
  }
}

export function mediumMajorant(medium: Medium1D, s0: number, s1: number): number {
  switch (medium.kind) {
    case MEDIUM_SINE:
      return saturatingProduct(medium.sigma0, 1 + Math.min(Math.max(medium.amplitude, 0), 1));
    case MEDIUM_GRID: {
      if (medium.cellSize <= 0) return 0;
      let majorant = 0;
      const count = Math.min(medium.cellCount, GRID1D_MAX_CELLS);
      for (let i = 0; i < count; i++) {
        if ((i + 1) * medium.cellSize > s0 && i * medium.cellSize < s1)
          majorant = Math.max(majorant, medium.cells[i] ?? 0);
      }
      return majorant;
    }
    default:
      return Math.max(medium.sigma0, 0);
  }
}

// ---------------------------------------------------------------------------
// 3D density grids: twin of the DensityGrid functions of shaders/medium.wesl, with
// the same conventions (cell-centred samples, clamp-to-edge, 0 outside the closed
// box, densities clamped to [0, 1e18], σt = densityScale·ρ capped at the largest f32). The WGSL `texture_3d<f32>`
// of samples is a Float32Array here, x fastest: sample (i, j, k) is
// volume[i + nx·(j + ny·k)].
// Written from the definitions: the trilinear value is a weighted sum over the eight
// corners, and the segment majorant splits the segment at every plane it crosses.

export type Vec3 = readonly [number, number, number];

/** Same fields as the WGSL struct DensityGrid (its samples are passed beside it). */
export interface DensityGrid {
  dimensions: Vec3;
  boundsMin: Vec3;
  boundsMax: Vec3;
  densityScale: number;
}

/** A grid with its samples, as a widget or a test builds it and as the GPU receives it. */
export interface DensityGridData {
  grid: DensityGrid;
  volume: Float32Array;
}

/** Same fields as the WGSL struct GridMajorantSegment. */
export interface GridMajorantSegment {
  majorant: number;
  cellsVisited: number;
  capped: number;
}

export const GRID_DDA_MAX_CELLS = 256;

const AXES = [0, 1, 2] as const;
const clampBetween = (x: number, lo: number, hi: number): number => Math.min(Math.max(x, lo), hi);
/**
 * Densities are clamped to f32(1e18), the value of the WGSL FINITE_LIMIT: the majorant
 * grid stores clamped samples as f32, and must still bound the density. densityScale
 * (1/m) is not clamped (a bound on a coefficient is a unit of length); σt = scale·ρ is
 * capped at the largest f32, as in the shader.
 */
const DENSITY_LIMIT = Math.fround(FINITE_LIMIT);
const clampDensity = (x: number): number => clampBetween(x, 0, DENSITY_LIMIT);
const f32 = Math.fround;

/**
 * Builds a grid whose fields are rounded to f32, as the GPU sees them. `values` has
 * nx·ny·nz finite entries, x fastest.
 */
export function makeDensityGrid(
  values: ArrayLike<number>,
  dimensions: Vec3,
  boundsMin: Vec3,
  boundsMax: Vec3,
  densityScale: number,
): DensityGridData {
  const [nx, ny, nz] = dimensions;
  if (!dimensions.every((n) => Number.isInteger(n) && n >= 1))
    throw new Error(`grid dimensions must be positive integers, got ${dimensions.join('×')}`);
  if (values.length !== nx * ny * nz)
    throw new Error(`a ${nx}×${ny}×${nz} grid needs ${nx * ny * nz} values, got ${values.length}`);
  const volume = Float32Array.from(values);
  if (!volume.every(Number.isFinite)) throw new Error('grid values must be finite');
  const round = (v: Vec3): Vec3 => [f32(v[0]), f32(v[1]), f32(v[2])];
  return {
    grid: {
      dimensions: [nx, ny, nz],
      boundsMin: round(boundsMin),
      boundsMax: round(boundsMax),
      densityScale: f32(densityScale),
    },
    volume,
  };
}

/** True when every sample is equal, the precondition of gridOpticalDepthConstant. */
export function gridIsConstant(volume: Float32Array): boolean {
  return volume.every((v) => v === volume[0]);
}

export function gridHasVolume(grid: DensityGrid): boolean {
  return AXES.every(
    (a) =>
      grid.dimensions[a] >= 1 &&
      grid.boundsMin[a] < grid.boundsMax[a] &&
      grid.boundsMin[a] >= -FINITE_LIMIT &&
      grid.boundsMax[a] <= FINITE_LIMIT,
  );
}

export function gridSample(grid: DensityGrid, volume: Float32Array, cell: Vec3): number {
  const [nx, ny, nz] = grid.dimensions;
  const i = Math.min(cell[0], Math.max(nx, 1) - 1);
  const j = Math.min(cell[1], Math.max(ny, 1) - 1);
  const k = Math.min(cell[2], Math.max(nz, 1) - 1);
  return clampDensity(volume[i + nx * (j + ny * k)] ?? 0);
}

/**
 * The extinction densities of a grid's samples, x fastest: nx·ny·nz values (at least one),
 * each the sample as gridSample reads it (clamped to [0, 1e18], a missing one 0) times the
 * grid's densityScale s, saturating at F32_MAX (saturatingProduct), rounded to f32. The
 * scene kernel reads its grid from a storage buffer of these (integrator.wesl
 * sceneDensity), so a lookup neither clamps nor multiplies. Its trilinear blend of s·ρ
 * equals s times the blend of ρ (gridDensityTrilinear) up to f32 rounding, and rounding
 * is monotone, so the largest of eight scaled samples is still the scaled majorant.
 */
export function gridScaledSamples(
  grid: DensityGrid,
  volume: Float32Array,
): Float32Array<ArrayBuffer> {
  const [nx, ny, nz] = grid.dimensions;
  const samples = new Float32Array(Math.max(1, nx * ny * nz));
  // The scale as the kernel's records hold it (f32): the majorant grid is scaled by that
  // value, and a scaled sample must not exceed the scaled majorant by a rounding.
  const scale = Math.fround(grid.densityScale);
  for (let i = 0; i < samples.length; i++)
    samples[i] = saturatingProduct(scale, clampDensity(volume[i] ?? 0));
  return samples;
}

export function lerpWithinEndpoints(a: number, b: number, t: number): number {
  return clampBetween((1 - t) * a + t * b, Math.min(a, b), Math.max(a, b));
}

function insideClosedBox(grid: DensityGrid, p: Vec3): boolean {
  return AXES.every((a) => p[a] >= grid.boundsMin[a] && p[a] <= grid.boundsMax[a]);
}

/** Where a trilinear lookup falls among the samples (WGSL GridTrilinearCorners). */
export interface GridTrilinearCorners {
  lower: Vec3;
  upper: Vec3;
  weights: Vec3;
}

/**
 * The lower sample index ⌊u⌋ (at most `last`), the upper one min(lower + 1, last) and the
 * weights u − ⌊u⌋ of the upper ones, u the continuous sample coordinate clamped to
 * [0, n − 1] (sample i sits at u = i; clamp-to-edge). p inside the grid's box.
 */
export function gridTrilinearCorners(grid: DensityGrid, last: Vec3, p: Vec3): GridTrilinearCorners {
  const lower: number[] = [];
  const upper: number[] = [];
  const weights: number[] = [];
  for (const a of AXES) {
    const n = grid.dimensions[a];
    const u = ((p[a] - grid.boundsMin[a]) / (grid.boundsMax[a] - grid.boundsMin[a])) * n - 0.5;
    const clamped = clampBetween(u, 0, n - 1);
    const base = Math.floor(clamped);
    const i = Math.min(base, last[a]);
    lower.push(i);
    upper.push(Math.min(i + 1, last[a]));
    weights.push(clamped - base);
  }
  return {
    lower: lower as unknown as Vec3,
    upper: upper as unknown as Vec3,
    weights: weights as unknown as Vec3,
  };
}

/**
 * The trilinear blend of eight samples, lower = (ρ000, ρ100, ρ010, ρ110) and upper =
 * (ρ001, ρ101, ρ011, ρ111) with the index bits x, y, z, at weights f ∈ [0, 1]³: seven
 * lerps a(1 − t) + bt, bounded by the largest sample (a convex combination cannot exceed
 * it; the bound removes only rounding, so majorants bound the result exactly).
 */
export function trilinearBlend(
  lower: readonly [number, number, number, number],
  upper: readonly [number, number, number, number],
  f: Vec3,
): number {
  const lerp = (a: number, b: number, t: number): number => a * (1 - t) + b * t;
  const [l0, l1, l2, l3] = lower;
  const [u0, u1, u2, u3] = upper;
  const y0 = lerp(lerp(l0, l1, f[0]), lerp(l2, l3, f[0]), f[1]);
  const y1 = lerp(lerp(u0, u1, f[0]), lerp(u2, u3, f[0]), f[1]);
  return Math.min(lerp(y0, y1, f[2]), Math.max(...lower, ...upper));
}

/**
 * The stored density of a sample whose index is inside the grid, clamped to [0, 1e18]
 * (gridSample without its index clamp). The WGSL reads a texture, which knows its size;
 * here the grid gives the row lengths.
 */
export function gridTexel(grid: DensityGrid, volume: Float32Array, cell: Vec3): number {
  const [nx, ny] = grid.dimensions;
  return clampDensity(volume[cell[0] + nx * (cell[1] + ny * cell[2])] ?? 0);
}

export function gridDensityTrilinear(grid: DensityGrid, volume: Float32Array, p: Vec3): number {
  if (!gridHasVolume(grid) || !insideClosedBox(grid, p)) return 0;
  const last = grid.dimensions.map((n) => Math.max(n, 1) - 1) as unknown as Vec3;
  const { lower: a, upper: b, weights } = gridTrilinearCorners(grid, last, p);
  const texel = (x: number, y: number, z: number): number => gridTexel(grid, volume, [x, y, z]);
  const value = trilinearBlend(
    [
      texel(a[0], a[1], a[2]),
      texel(b[0], a[1], a[2]),
      texel(a[0], b[1], a[2]),
      texel(b[0], b[1], a[2]),
    ],
    [
      texel(a[0], a[1], b[2]),
      texel(b[0], a[1], b[2]),
      texel(a[0], b[1], b[2]),
      texel(b[0], b[1], b[2]),
    ],
    weights,
  );
  return saturatingProduct(grid.densityScale, value);
}

export function gridCellIndex(grid: DensityGrid, p: Vec3): Vec3 {
  return AXES.map((a) => {
    const m = grid.dimensions[a];
    const lo = grid.boundsMin[a];
    const hi = grid.boundsMax[a];
    const x = (clampBetween(p[a], lo, hi) - lo) / (hi - lo);
    return clampBetween(Math.floor(x * m), 0, m - 1);
  }) as unknown as Vec3;
}

export function gridMajorantLookup(
  majorantGrid: DensityGrid,
  majorantVolume: Float32Array,
  p: Vec3,
): number {
  if (!gridHasVolume(majorantGrid) || !insideClosedBox(majorantGrid, p)) return 0;
  return saturatingProduct(
    majorantGrid.densityScale,
    gridSample(majorantGrid, majorantVolume, gridCellIndex(majorantGrid, p)),
  );
}

/**
 * CPU only: a coarse majorant grid for `fine`, one cell per block of blockSize³ fine
 * cells (the last block of an axis may be partial, so the coarse box may reach past
 * the fine one). Each coarse cell holds the largest sample that a trilinear lookup
 * inside the block can touch: the block's own samples plus ONE NEIGHBOUR ON EACH SIDE
 * per axis. A point in the outer half cell of a block blends the sample just across
 * the block face with weight up to ½, so the largest sample of the block alone can lie
 * below σt there, and delta tracking with σt > σ̄ is biased (physics.md §4.5). The
 * trilinear value is a convex combination of the samples it touches, so their maximum
 * bounds it, and the GPU's bound on its blend (trilinearBlend) keeps that true in f32. Because block faces
 * lie on fine cell faces, a fine sample coordinate there is a half-integer; f32
 * rounding of a position near a block face can change its coarse cell but not which
 * samples its lookup touches, and those belong to the support of both blocks.
 * The coarse densityScale is the fine one, so σ̄ = densityScale·(block maximum).
 */
export function gridMajorantBuild(
  fine: DensityGrid,
  volume: Float32Array,
  blockSize: number,
): DensityGridData {
  const block = Math.max(1, Math.floor(blockSize));
  const n = fine.dimensions.map((d) => Math.max(d, 1)) as unknown as Vec3;
  const m = n.map((d) => Math.ceil(d / block)) as unknown as Vec3;
  // The coarse box covers m·block fine cells per axis; a partial last block extends
  // it. Rounded up to f32 so that it never ends inside the fine box.
  const boundsMax = AXES.map((a) => {
    if (m[a] * block === n[a]) return fine.boundsMax[a];
    const lo = fine.boundsMin[a];
    const exact = lo + ((fine.boundsMax[a] - lo) * m[a] * block) / n[a];
    return roundUpToF32(exact);
  }) as unknown as Vec3;
  const values = new Float32Array(m[0] * m[1] * m[2]);
  // Per axis and coarse index c: the sample range [c·block − 1, (c+1)·block] ∩ [0, n − 1].
  const support = (a: number, c: number): [number, number] => [
    Math.max(c * block - 1, 0),
    Math.min((c + 1) * block, (n[a] ?? 1) - 1),
  ];
  for (let cz = 0; cz < m[2]; cz++) {
    const [z0, z1] = support(2, cz);
    for (let cy = 0; cy < m[1]; cy++) {
      const [y0, y1] = support(1, cy);
      for (let cx = 0; cx < m[0]; cx++) {
        const [x0, x1] = support(0, cx);
        let largest = 0;
        for (let k = z0; k <= z1; k++)
          for (let j = y0; j <= y1; j++)
            for (let i = x0; i <= x1; i++)
              largest = Math.max(largest, gridSample(fine, volume, [i, j, k]));
        values[cx + m[0] * (cy + m[1] * cz)] = largest;
      }
    }
  }
  return {
    grid: { dimensions: m, boundsMin: fine.boundsMin, boundsMax, densityScale: fine.densityScale },
    volume: values,
  };
}

function roundUpToF32(x: number): number {
  const rounded = f32(x);
  if (rounded >= x) return rounded;
  const bits = new Float32Array([rounded]);
  const word = new Uint32Array(bits.buffer);
  word[0] = (word[0] ?? 0) + (rounded >= 0 ? 1 : -1);
  return bits[0] ?? rounded;
}

export function gridRayParameter(offset: number, slope: number): number {
  return planeCrossing(offset, slope);
}

const EMPTY_SEGMENT: [number, number] = [1, 0];

export function gridSegmentInBounds(
  grid: DensityGrid,
  origin: Vec3,
  direction: Vec3,
  tMin: number,
  tMax: number,
): [number, number] {
  if (!gridHasVolume(grid)) return [...EMPTY_SEGMENT];
  return [...rayBoxSegment(grid.boundsMin, grid.boundsMax, origin, direction, tMin, tMax)];
}

export function gridMajorantAlongRay(
  majorantGrid: DensityGrid,
  majorantVolume: Float32Array,
  origin: Vec3,
  direction: Vec3,
  tMin: number,
  tMax: number,
): GridMajorantSegment {
  const [t0, t1] = gridSegmentInBounds(majorantGrid, origin, direction, tMin, tMax);
  if (t0 > t1) return { majorant: 0, cellsVisited: 0, capped: 0 };
  const { boundsMin, boundsMax, dimensions } = majorantGrid;
  // Split [t0, t1] at every cell plane the ray crosses; each piece lies in one cell.
  const cuts = [t0, t1];
  for (const a of AXES) {
    if (direction[a] === 0) continue;
    for (let k = 1; k < dimensions[a]; k++) {
      const plane = boundsMin[a] + ((boundsMax[a] - boundsMin[a]) * k) / dimensions[a];
      const t = (plane - origin[a]) / direction[a];
      if (t > t0 && t < t1) cuts.push(t);
    }
  }
  cuts.sort((a, b) => a - b);
  const pieces: Vec3[] = [];
  const at = (t: number): Vec3 => AXES.map((a) => origin[a] + t * direction[a]) as unknown as Vec3;
  if (t1 === t0) {
    // A point: its cell, or the cell below a face it sits on when moving towards −axis.
    const p = at(t0);
    const cell = gridCellIndex(majorantGrid, p);
    pieces.push(
      AXES.map((a) => {
        const x = ((p[a] - boundsMin[a]) / (boundsMax[a] - boundsMin[a])) * dimensions[a];
        return direction[a] < 0 && cell[a] > 0 && x === cell[a] ? cell[a] - 1 : cell[a];
      }) as unknown as Vec3,
    );
  }
  for (let i = 0; i + 1 < cuts.length; i++) {
    const [a, b] = [cuts[i] ?? 0, cuts[i + 1] ?? 0];
    if (b > a) pieces.push(gridCellIndex(majorantGrid, at(0.5 * (a + b))));
  }
  const cells = pieces.filter(
    (cell, i) => i === 0 || !AXES.every((a) => cell[a] === pieces[i - 1]?.[a]),
  );
  const visited = cells.slice(0, GRID_DDA_MAX_CELLS);
  const largest = Math.max(0, ...visited.map((c) => gridSample(majorantGrid, majorantVolume, c)));
  return {
    majorant: saturatingProduct(majorantGrid.densityScale, largest),
    cellsVisited: visited.length,
    capped: cells.length > GRID_DDA_MAX_CELLS ? 1 : 0,
  };
}

/**
 * gridMajorantAlongRay for a segment [t0, t1] that the caller knows to lie in the majorant
 * grid's closed box (WGSL gridMajorantAlongSegment, the DDA without its slab test): there
 * the slab test returns the segment itself. Outside that contract the two differ (this one
 * still clips).
 */
export function gridMajorantAlongSegment(
  majorantGrid: DensityGrid,
  majorantVolume: Float32Array,
  origin: Vec3,
  direction: Vec3,
  segment: readonly [number, number],
): GridMajorantSegment {
  return gridMajorantAlongRay(
    majorantGrid,
    majorantVolume,
    origin,
    direction,
    segment[0],
    segment[1],
  );
}

export function gridOpticalDepthConstant(
  grid: DensityGrid,
  volume: Float32Array,
  origin: Vec3,
  direction: Vec3,
  tMin: number,
  tMax: number,
): number {
  const [t0, t1] = gridSegmentInBounds(grid, origin, direction, tMin, tMax);
  if (t1 <= t0) return 0;
  const sigmaT = saturatingProduct(grid.densityScale, gridSample(grid, volume, [0, 0, 0]));
  return opticalThicknessHomogeneous(sigmaT, (t1 - t0) * Math.hypot(...direction));
}
