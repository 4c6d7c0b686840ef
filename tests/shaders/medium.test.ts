// WGSL 3D density grids (shaders/medium.wesl) vs their float64 twins. The grid's
// samples are an r32float 3D texture, which the table harness cannot pass: a custom
// kernel (tests/support/densityGridGpu.ts, one entry point per function) reads points
// or rays from a storage buffer and the test creates the texture. The small helpers
// without textures go through the table harness at the end.
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  GRID_DDA_MAX_CELLS,
  gridDensityTrilinear,
  gridHasVolume,
  gridMajorantAlongSegment,
  gridMajorantBuild,
  gridMajorantLookup,
  gridRayParameter,
  lerpWithinEndpoints,
  makeDensityGrid,
  type DensityGrid,
  type DensityGridData,
  type GridMajorantSegment,
  type Vec3,
} from '../../src/reference/medium.ts';
import { rngNextFloat } from '../../src/reference/rng.ts';
import {
  f32Ray,
  f32Vec,
  gpuDensity,
  gpuMajorantAlongRay,
  gpuMajorantAlongSegment,
  gpuMajorantLookup,
  gpuOpticalDepthConstant,
  gpuSegmentInBounds,
  type Ray,
  twinMajorantAlongRay,
  twinOpticalDepthConstant,
  twinSegmentInBounds,
} from '../support/densityGridGpu.ts';
import { describeShaderFunction } from '../support/shaderHarness.ts';
import { F32_MAX } from '../support/f32.ts';

// ---------------------------------------------------------------------------
// Test grids, from a fixed PCG seed.

function randomGrid(
  dimensions: Vec3,
  boundsMin: Vec3,
  boundsMax: Vec3,
  densityScale: number,
  seed: number,
): DensityGridData {
  const state = { value: seed };
  const count = dimensions[0] * dimensions[1] * dimensions[2];
  const values = Array.from({ length: count }, () => 2 * rngNextFloat(state));
  return makeDensityGrid(values, dimensions, boundsMin, boundsMax, densityScale);
}

const FINE = randomGrid([7, 5, 4], [-1.5, 0.25, 2], [2.5, 3.25, 4.5], 3.7, 2026);
const MAJORANT = gridMajorantBuild(FINE.grid, FINE.volume, 2);

/** Centre of sample (i, j, k) in world space, rounded to f32. */
function sampleCentre(grid: DensityGrid, cell: Vec3): Vec3 {
  return f32Vec(
    cell.map(
      (c, a) =>
        grid.boundsMin[a as 0] +
        ((c + 0.5) * (grid.boundsMax[a as 0] - grid.boundsMin[a as 0])) / grid.dimensions[a as 0],
    ),
  );
}

function sampleValue(data: DensityGridData, [i, j, k]: Vec3): number {
  const [nx, ny] = data.grid.dimensions;
  return data.volume[i + nx * (j + ny * k)] ?? NaN;
}

/**
 * Absolute tolerance of a trilinear lookup, GPU vs twin, from the f32 operations
 * (physics.md §10). Per axis the sample coordinate u = (p − min)/(max − min)·n − ½
 * carries |δu| ≤ 6n·2⁻²⁴ (0.5 ULP for the subtraction, 2.5 ULP for the division,
 * 0.5 + 0.5 ULP for ·n and −½, all relative to values ≤ n); the interpolant changes by
 * at most (largest − smallest sample) per unit of u on each of the 3 axes. The seven
 * mixes and the final product by densityScale add ≤ 16 ULP of the largest sample.
 */
function densityTolerance(data: DensityGridData): number {
  const values = Array.from(data.volume);
  const largest = Math.max(...values);
  const range = largest - Math.min(...values);
  const n = Math.max(...data.grid.dimensions);
  return data.grid.densityScale * 2 ** -24 * (3 * 6 * n * range + 16 * largest);
}

/** Uniform on [min, max] (fc.double favours extreme values, which the stability tests cover). */
const uniform = (min: number, max: number) =>
  fc.noBias(fc.integer({ min: 0, max: 2 ** 30 })).map((i) => min + ((max - min) * i) / 2 ** 30);

const pointIn = (grid: DensityGrid, margin: number) =>
  fc
    .tuple(uniform(-margin, 1 + margin), uniform(-margin, 1 + margin), uniform(-margin, 1 + margin))
    .map((x) =>
      f32Vec(
        x.map(
          (s, a) => grid.boundsMin[a as 0] + s * (grid.boundsMax[a as 0] - grid.boundsMin[a as 0]),
        ),
      ),
    );

/**
 * Segments aimed at the box: from a point of the box grown by half its size on each
 * side towards a point inside it, with random speed, start and length, so that most
 * cross several cells, some start or end inside, and some miss.
 */
function raysThrough(grid: DensityGrid, count: number, seed: number): Ray[] {
  const fraction = (lo: number, hi: number) =>
    fc.tuple(uniform(lo, hi), uniform(lo, hi), uniform(lo, hi));
  const world = (x: readonly number[]): number[] =>
    x.map((s, a) => grid.boundsMin[a as 0] + s * (grid.boundsMax[a as 0] - grid.boundsMin[a as 0]));
  return fc
    .sample(
      fc.record({
        from: fraction(-0.5, 1.5),
        to: fraction(0, 1),
        speed: uniform(0.25, 2),
        start: uniform(-0.5, 0.8),
        length: uniform(0, 1.5),
      }),
      { numRuns: count, seed },
    )
    .map(({ from, to, speed, start, length }) => {
      const origin = world(from);
      const target = world(to);
      return f32Ray({
        origin: origin as unknown as Vec3,
        direction: target.map((t, a) => (t - (origin[a] ?? 0)) * speed) as unknown as Vec3,
        tMin: start / speed,
        tMax: (start + length) / speed,
      });
    });
}

// ---------------------------------------------------------------------------

describe('gridDensityTrilinear: WGSL vs float64 twin', () => {
  const tolerance = densityTolerance(FINE);

  it(`4096 points in and around a 7×5×4 grid agree within ${tolerance.toExponential(2)} (f32 position → weight rounding, §10)`, async () => {
    const points = fc.sample(pointIn(FINE.grid, 0.1), { numRuns: 4096, seed: 41 });
    const gpu = await gpuDensity(FINE, points);
    points.forEach((p, i) => {
      const twin = gridDensityTrilinear(FINE.grid, FINE.volume, p);
      const value = gpu[i] ?? NaN;
      expect(Number.isFinite(value), `GPU at ${p.join(', ')}`).toBe(true);
      expect(
        Math.abs(value - twin),
        `at ${p.join(', ')}: GPU ${value}, twin ${twin}`,
      ).toBeLessThanOrEqual(tolerance);
    });
  });

  it('at every sample centre both give densityScale times the stored sample (exactness of cell-centred samples)', async () => {
    const cells: Vec3[] = [];
    const [nx, ny, nz] = FINE.grid.dimensions;
    for (let k = 0; k < nz; k++)
      for (let j = 0; j < ny; j++) for (let i = 0; i < nx; i++) cells.push([i, j, k]);
    const centres = cells.map((c) => sampleCentre(FINE.grid, c));
    const gpu = await gpuDensity(FINE, centres);
    cells.forEach((cell, i) => {
      const expected = FINE.grid.densityScale * sampleValue(FINE, cell);
      const twin = gridDensityTrilinear(FINE.grid, FINE.volume, centres[i] as Vec3);
      // The centre itself is rounded to f32: u is then off an integer by ≤ 6n·2⁻²⁴.
      expect(
        Math.abs((gpu[i] ?? NaN) - expected),
        `GPU at sample ${cell.join(',')}`,
      ).toBeLessThanOrEqual(tolerance);
      expect(Math.abs(twin - expected), `twin at sample ${cell.join(',')}`).toBeLessThanOrEqual(
        tolerance,
      );
    });
  });

  it('is linear between neighbouring centres along each axis (both implementations)', async () => {
    const lines: { p: Vec3; expected: number }[] = [];
    for (const axis of [0, 1, 2] as const) {
      const a: Vec3 = [2, 2, 1];
      const b = a.map((c, k) => (k === axis ? c + 1 : c)) as unknown as Vec3;
      const pa = sampleCentre(FINE.grid, a);
      const pb = sampleCentre(FINE.grid, b);
      const va = FINE.grid.densityScale * sampleValue(FINE, a);
      const vb = FINE.grid.densityScale * sampleValue(FINE, b);
      for (let s = 0; s <= 16; s++) {
        const t = s / 16;
        const p = pa.map((x, k) =>
          k === axis ? x + t * ((pb[k] ?? 0) - x) : x,
        ) as unknown as Vec3;
        lines.push({ p: f32Vec(p), expected: va + t * (vb - va) });
      }
    }
    const gpu = await gpuDensity(
      FINE,
      lines.map((l) => l.p),
    );
    lines.forEach(({ p, expected }, i) => {
      expect(Math.abs((gpu[i] ?? NaN) - expected)).toBeLessThanOrEqual(tolerance);
      expect(
        Math.abs(gridDensityTrilinear(FINE.grid, FINE.volume, p) - expected),
      ).toBeLessThanOrEqual(tolerance);
    });
  });

  it('clamps to the edge: the outer half cell at each corner holds the corner sample bit for bit', async () => {
    const { boundsMin: lo, boundsMax: hi, dimensions: n } = FINE.grid;
    const h = [0, 1, 2].map((a) => ((hi[a as 0] - lo[a as 0]) / n[a as 0]) * 0.3);
    const corners: { p: Vec3; cell: Vec3 }[] = [];
    for (let c = 0; c < 8; c++) {
      const upper = [0, 1, 2].map((a) => (c >> a) & 1);
      corners.push({
        p: f32Vec(upper.map((u, a) => (u ? hi[a as 0] - (h[a] ?? 0) : lo[a as 0] + (h[a] ?? 0)))),
        cell: upper.map((u, a) => (u ? n[a as 0] - 1 : 0)) as unknown as Vec3,
      });
      // On the corner itself (inside the closed box).
      corners.push({
        p: upper.map((u, a) => (u ? hi[a as 0] : lo[a as 0])) as unknown as Vec3,
        cell: upper.map((u, a) => (u ? n[a as 0] - 1 : 0)) as unknown as Vec3,
      });
    }
    const gpu = await gpuDensity(
      FINE,
      corners.map((c) => c.p),
    );
    corners.forEach(({ p, cell }, i) => {
      const expected = Math.fround(FINE.grid.densityScale * sampleValue(FINE, cell));
      expect(gpu[i], `GPU at ${p.join(', ')}`).toBe(expected);
      expect(Math.fround(gridDensityTrilinear(FINE.grid, FINE.volume, p))).toBe(expected);
    });
  });

  it('is constant along the normal of each face within its outer half cell (clamp-to-edge)', async () => {
    const { boundsMin: lo, boundsMax: hi, dimensions: n } = FINE.grid;
    const base: Vec3 = [0.3, 1.7, 3.1];
    const points: Vec3[] = [];
    for (const axis of [0, 1, 2] as const) {
      const half = (0.5 * (hi[axis] - lo[axis])) / n[axis];
      for (const fraction of [0, 0.25, 0.5, 0.99]) {
        points.push(f32Vec(base.map((x, a) => (a === axis ? lo[axis] + fraction * half : x))));
        points.push(f32Vec(base.map((x, a) => (a === axis ? hi[axis] - fraction * half : x))));
      }
    }
    const gpu = await gpuDensity(FINE, points);
    for (let axis = 0; axis < 3; axis++) {
      for (const side of [0, 1]) {
        const group = [0, 1, 2, 3].map((f) => gpu[axis * 8 + f * 2 + side]);
        expect(new Set(group).size, `GPU, axis ${axis}, side ${side}: ${group.join(', ')}`).toBe(1);
        const twin = [0, 1, 2, 3].map((f) =>
          gridDensityTrilinear(FINE.grid, FINE.volume, points[axis * 8 + f * 2 + side] as Vec3),
        );
        expect(Math.max(...twin) - Math.min(...twin)).toBeLessThanOrEqual(1e-12);
      }
    }
  });

  it('is exactly 0 one f32 step outside each face and > 0 on the face (closed box)', async () => {
    const { boundsMin: lo, boundsMax: hi } = FINE.grid;
    const next = (x: number, up: boolean): number => {
      const f = new Float32Array([x]);
      const w = new Int32Array(f.buffer);
      w[0] = (w[0] ?? 0) + (x >= 0 === up ? 1 : -1);
      return f[0] ?? NaN;
    };
    const centre: Vec3 = [0.5, 1.75, 3.25];
    const outside: Vec3[] = [];
    const onFace: Vec3[] = [];
    for (const axis of [0, 1, 2] as const) {
      for (const [face, up] of [
        [lo[axis], false],
        [hi[axis], true],
      ] as const) {
        outside.push(f32Vec(centre.map((x, a) => (a === axis ? next(face, up) : x))));
        onFace.push(f32Vec(centre.map((x, a) => (a === axis ? face : x))));
      }
    }
    const far: Vec3[] = [
      [-1e30, 0, 0],
      [F32_MAX, F32_MAX, F32_MAX],
      [0.5, 1.75, -F32_MAX],
    ];
    const gpu = await gpuDensity(FINE, [...outside, ...far, ...onFace]);
    [...outside, ...far].forEach((p, i) => {
      expect(gpu[i], `GPU at ${p.join(', ')}`).toBe(0);
      expect(gridDensityTrilinear(FINE.grid, FINE.volume, p)).toBe(0);
    });
    onFace.forEach((p, i) => {
      expect(
        gpu[outside.length + far.length + i],
        `GPU on the face at ${p.join(', ')}`,
      ).toBeGreaterThan(0);
      expect(gridDensityTrilinear(FINE.grid, FINE.volume, p)).toBeGreaterThan(0);
    });
  });
});

describe('gridMajorantLookup and gridMajorantBuild: WGSL vs twin, and the bound', () => {
  it('coarse cell values agree exactly away from coarse faces (one correctly rounded product)', async () => {
    const { boundsMin: lo, boundsMax: hi, dimensions: m } = MAJORANT.grid;
    const points = fc.sample(
      fc.tuple(fc.nat(1e6), fc.nat(1e6), fc.nat(1e6)).map((r) =>
        f32Vec(
          r.map((x, a) => {
            const s = (x / 1e6) * m[a as 0];
            // Keep 1% of a cell away from every coarse face.
            const inCell = 0.01 + 0.98 * (s - Math.floor(s));
            const cell = Math.min(Math.floor(s), m[a as 0] - 1);
            return lo[a as 0] + ((cell + inCell) * (hi[a as 0] - lo[a as 0])) / m[a as 0];
          }),
        ),
      ),
      { numRuns: 1024, seed: 5 },
    );
    const gpu = await gpuMajorantLookup(MAJORANT, points);
    points.forEach((p, i) => {
      const twin = gridMajorantLookup(MAJORANT.grid, MAJORANT.volume, p);
      expect(gpu[i], `at ${p.join(', ')}`).toBe(Math.fround(twin));
    });
  });

  it('bounds the trilinear density at 20000 fast-check points, bit for bit on the GPU (σt ≤ σ̄, physics.md §4.5)', async () => {
    // Points anywhere, plus points hugging fine cell faces (where a block lookup blends
    // the neighbour across a block face).
    const { boundsMin: lo, boundsMax: hi, dimensions: n } = FINE.grid;
    const nearFaces = fc
      .tuple(fc.nat(64), fc.nat(64), fc.nat(64), uniform(-1e-4, 1e-4))
      .map(([i, j, k, e]) =>
        f32Vec(
          [i, j, k].map((c, a) => {
            const face = c % (n[a as 0] + 1);
            return lo[a as 0] + ((face + e) * (hi[a as 0] - lo[a as 0])) / n[a as 0];
          }),
        ),
      );
    const points = fc.sample(fc.oneof(pointIn(MAJORANT.grid, 0.05), nearFaces), {
      numRuns: 20000,
      seed: 99,
    });
    const [density, majorant] = await Promise.all([
      gpuDensity(FINE, points),
      gpuMajorantLookup(MAJORANT, points),
    ]);
    let violations = 0;
    points.forEach((p, i) => {
      if (!((density[i] ?? NaN) <= (majorant[i] ?? NaN))) violations += 1;
      const twinDensity = gridDensityTrilinear(FINE.grid, FINE.volume, p);
      const twinMajorant = gridMajorantLookup(MAJORANT.grid, MAJORANT.volume, p);
      if (!(twinDensity <= twinMajorant)) violations += 1;
    });
    expect(violations).toBe(0);
  });

  it('a block-local maximum would NOT bound it: the neighbour samples are needed', () => {
    // One spike at fine sample 2 (x); blocks of 2 put it in block 1. A point of block 0
    // in its outer half cell (u ∈ [1, 1.5]) blends sample 2 with weight up to ½.
    const spike = makeDensityGrid([0, 0, 1, 0], [4, 1, 1], [0, 0, 0], [4, 1, 1], 1);
    const majorant = gridMajorantBuild(spike.grid, spike.volume, 2);
    const p: Vec3 = [1.9, 0.5, 0.5];
    const density = gridDensityTrilinear(spike.grid, spike.volume, p);
    expect(density).toBeCloseTo(0.4, 12);
    expect(Math.max(spike.volume[0] ?? 0, spike.volume[1] ?? 0)).toBe(0);
    expect(gridMajorantLookup(majorant.grid, majorant.volume, p)).toBe(1);
  });
});

describe('gridMajorantAlongRay: WGSL DDA vs the twin’s plane splitting', () => {
  const rays = raysThrough(MAJORANT.grid, 512, 17);

  it('512 random segments: same majorant (exact f32 product), cells visited and capped flag', async () => {
    const gpu = await gpuMajorantAlongRay(MAJORANT, rays);
    let hits = 0;
    rays.forEach((r, i) => {
      const twin = twinMajorantAlongRay(MAJORANT, r);
      const g = gpu[i] as GridMajorantSegment;
      const label = `ray ${i}: ${JSON.stringify(r)}`;
      expect(g.majorant, label).toBe(Math.fround(twin.majorant));
      expect(g.cellsVisited, label).toBe(twin.cellsVisited);
      expect(g.capped, label).toBe(0);
      if (twin.cellsVisited > 1) hits += 1;
    });
    // The sample must exercise the DDA, not only misses.
    expect(hits).toBeGreaterThan(100);
  });

  it('gridMajorantAlongSegment on the part of each ray inside the box (as the integrator calls it) = gridMajorantAlongRay, GPU and twin', async () => {
    // The part inside, from the GPU's own slab test; misses have no such part.
    const inside = await gpuSegmentInBounds(MAJORANT, rays);
    const parts = rays.flatMap((r, i) => {
      const [t0, t1] = inside[i] ?? [1, 0];
      return t0 <= t1 ? [{ ...r, tMin: t0, tMax: t1 }] : [];
    });
    expect(parts.length).toBeGreaterThan(300);
    const [alongSegment, alongRay] = await Promise.all([
      gpuMajorantAlongSegment(MAJORANT, parts),
      gpuMajorantAlongRay(MAJORANT, parts),
    ]);
    parts.forEach((r, i) => {
      const label = `segment ${i}: ${JSON.stringify(r)}`;
      expect(alongSegment[i], label).toEqual(alongRay[i]);
      const twin = gridMajorantAlongSegment(MAJORANT.grid, MAJORANT.volume, r.origin, r.direction, [
        r.tMin,
        r.tMax,
      ]);
      expect(alongSegment[i]?.majorant, label).toBe(Math.fround(twin.majorant));
      expect(alongSegment[i]?.cellsVisited, label).toBe(twin.cellsVisited);
    });
  });

  it('bounds the density at 64 points along each of 256 segments (GPU and twin)', async () => {
    const subset = rays.slice(0, 256);
    const majorants = await gpuMajorantAlongRay(MAJORANT, subset);
    const points = subset.flatMap((r) =>
      Array.from({ length: 64 }, (_, s) => {
        const t = r.tMin + ((s + 0.5) / 64) * (r.tMax - r.tMin);
        return f32Vec(r.origin.map((o, a) => o + t * (r.direction[a as 0] ?? 0)));
      }),
    );
    const density = await gpuDensity(FINE, points);
    let violations = 0;
    subset.forEach((r, i) => {
      const twinMajorant = twinMajorantAlongRay(MAJORANT, r).majorant;
      for (let s = 0; s < 64; s++) {
        const p = points[i * 64 + s] as Vec3;
        if (!((density[i * 64 + s] ?? NaN) <= (majorants[i]?.majorant ?? NaN))) violations += 1;
        if (!(gridDensityTrilinear(FINE.grid, FINE.volume, p) <= twinMajorant)) violations += 1;
      }
    });
    expect(violations).toBe(0);
  });

  it(`reports the cap: a 1×1×300 majorant grid crossed end to end stops at ${GRID_DDA_MAX_CELLS} cells; 1×1×256 does not`, async () => {
    const long = makeDensityGrid(
      Array.from({ length: 300 }, (_, i) => (i === 299 ? 5 : 1)),
      [1, 1, 300],
      [0, 0, 0],
      [1, 1, 300],
      1,
    );
    const exact = makeDensityGrid(new Array(256).fill(1), [1, 1, 256], [0, 0, 0], [1, 1, 256], 1);
    const ray: Ray = { origin: [0.5, 0.5, -1], direction: [0, 0, 1], tMin: 0, tMax: 1000 };
    const [capped] = await gpuMajorantAlongRay(long, [ray]);
    const [uncapped] = await gpuMajorantAlongRay(exact, [ray]);
    const twinCapped = twinMajorantAlongRay(long, ray);
    const twinUncapped = twinMajorantAlongRay(exact, ray);
    // Capped: the spike in the last cell was never seen, and the result says so.
    expect(capped).toEqual({ majorant: 1, cellsVisited: GRID_DDA_MAX_CELLS, capped: 1 });
    expect(twinCapped).toEqual(capped);
    expect(uncapped).toEqual({ majorant: 1, cellsVisited: 256, capped: 0 });
    expect(twinUncapped).toEqual(uncapped);
  });
});

describe('gridSegmentInBounds and gridOpticalDepthConstant: WGSL vs twin', () => {
  const constant = makeDensityGrid(new Array(8).fill(0.75), [2, 2, 2], [-1, 0, 1], [1, 3, 2], 4);
  const rays = raysThrough(constant.grid, 512, 23);

  it('segment ends agree to 5e-7 relative (f32 subtraction 0.5 ULP + division 2.5 ULP)', async () => {
    const gpu = await gpuSegmentInBounds(constant, rays);
    let inside = 0;
    rays.forEach((r, i) => {
      const twin = twinSegmentInBounds(constant, r);
      const [g0, g1] = gpu[i] as [number, number];
      const label = `ray ${i}: ${JSON.stringify(r)} GPU [${g0}, ${g1}] twin [${twin.join(', ')}]`;
      expect(g0 > g1, label).toBe(twin[0] > twin[1]);
      if (twin[0] > twin[1]) return;
      inside += 1;
      expect(Math.abs(g0 - twin[0]), label).toBeLessThanOrEqual(5e-7 * Math.abs(twin[0]) + 1e-30);
      expect(Math.abs(g1 - twin[1]), label).toBeLessThanOrEqual(5e-7 * Math.abs(twin[1]) + 1e-30);
    });
    expect(inside).toBeGreaterThan(100);
  });

  it('constant-grid τ = densityScale·ρ·chord agrees (the t ends’ error times |d|, plus 4 ULP of τ)', async () => {
    const gpu = await gpuOpticalDepthConstant(constant, rays);
    rays.forEach((r, i) => {
      const twin = twinOpticalDepthConstant(constant, r);
      const [t0, t1] = twinSegmentInBounds(constant, r);
      const speed = Math.hypot(...r.direction);
      const sigmaT = 4 * 0.75;
      // Each end is off by ≤ 5e-7·|t|; the chord by their sum; length() and the products
      // add a few ULP of τ.
      const tolerance =
        t0 > t1 ? 0 : sigmaT * speed * 5e-7 * (Math.abs(t0) + Math.abs(t1)) + 4 * 2 ** -24 * twin;
      expect(Math.abs((gpu[i] ?? NaN) - twin), `ray ${i}`).toBeLessThanOrEqual(tolerance + 1e-30);
    });
  });

  it('τ through a box along an axis is densityScale·ρ times the box width, whatever the segment beyond it', async () => {
    const through: Ray = { origin: [0, 1.5, -5], direction: [0, 0, 2], tMin: -100, tMax: 100 };
    const [gpu] = await gpuOpticalDepthConstant(constant, [through]);
    const twin = twinOpticalDepthConstant(constant, through);
    expect(twin).toBe(3);
    expect(gpu).toBe(3);
  });
});

describe('grid helper functions: WGSL vs twin (harness)', () => {
  describeShaderFunction({
    module: 'medium',
    fn: 'lerpWithinEndpoints',
    args: ['f32', 'f32', 'f32'],
    result: 'f32',
    twin: lerpWithinEndpoints,
    tolerance: { ulps: 2, relative: 1e-7, reason: 'WGSL mix = a·(1−t) + b·t: 3 roundings' },
    cases: [
      { name: 't = 0 gives a exactly', args: [0.3, 1.7, 0], expected: 0.30000001192092896 },
      { name: 't = 1 gives b', args: [0.3, 1.7, 1], expected: 1.7000000476837158 },
      { name: 'midpoint', args: [1, 3, 0.5], expected: 2 },
      { name: 'a = b stays a (never above the largest end)', args: [0.7, 0.7, 0.3] },
      { name: 'decreasing', args: [5, 1, 0.25], expected: 4 },
      { name: 'large values', args: [1e30, 3e30, 0.5], expected: 2e30 },
    ],
  });

  describeShaderFunction({
    module: 'medium',
    fn: 'gridRayParameter',
    args: ['f32', 'f32'],
    result: 'f32',
    twin: gridRayParameter,
    tolerance: { ulps: 3, reason: 'one f32 division: 2.5 ULP; the clamp is exact' },
    cases: [
      { name: 'offset 2, slope 0.5', args: [2, 0.5], expected: 4 },
      { name: 'negative slope', args: [3, -1.5], expected: -2 },
      { name: 'offset 0', args: [0, 0.1], expected: 0 },
      { name: 'tiny slope: clamped to 1e18, no overflow', args: [1, 1e-30], expected: 1e18 },
      { name: 'tiny negative slope', args: [1, -1e-30], expected: -1e18 },
      { name: 'f32 max offset over slope 1e-3', args: [F32_MAX, 1e-3], expected: 1e18 },
      { name: 'just below the clamp', args: [1e17, 0.5], expected: 2e17 },
    ],
  });

  describeShaderFunction({
    module: 'medium',
    fn: 'gridHasVolume',
    args: ['u32', 'u32', 'u32', 'f32', 'f32', 'f32', 'f32', 'f32', 'f32'],
    result: 'u32',
    twin: ((nx: number, ny: number, nz: number, ...b: number[]) =>
      gridHasVolume({
        dimensions: [nx, ny, nz],
        boundsMin: [b[0] ?? 0, b[1] ?? 0, b[2] ?? 0],
        boundsMax: [b[3] ?? 0, b[4] ?? 0, b[5] ?? 0],
        densityScale: 1,
      })
        ? 1
        : 0) as never,
    wrapper: {
      wgsl: `fn caseUnderTest(nx: u32, ny: u32, nz: u32, x0: f32, y0: f32, z0: f32, x1: f32, y1: f32, z1: f32) -> u32 {
  return select(0u, 1u, gridHasVolume(DensityGrid(vec3u(nx, ny, nz), vec3f(x0, y0, z0), vec3f(x1, y1, z1), 1.0)));
}`,
      imports: ['DensityGrid', 'gridHasVolume'],
    },
    tolerance: { ulps: 0, reason: 'a boolean' },
    cases: [
      { name: 'unit box, 1×1×1', args: [1, 1, 1, 0, 0, 0, 1, 1, 1], expected: 1 },
      { name: 'a zero dimension', args: [4, 0, 4, 0, 0, 0, 1, 1, 1], expected: 0 },
      { name: 'zero-size bounds on z', args: [2, 2, 2, 0, 0, 1, 1, 1, 1], expected: 0 },
      { name: 'inverted bounds', args: [2, 2, 2, 0, 0, 0, 1, -1, 1], expected: 0 },
      { name: 'bounds beyond 1e18 m', args: [2, 2, 2, -1e19, 0, 0, 1, 1, 1], expected: 0 },
      { name: 'bounds at ±1e18 m', args: [2, 2, 2, -1e18, 0, 0, 1e18, 1, 1], expected: 1 },
    ],
  });
});
