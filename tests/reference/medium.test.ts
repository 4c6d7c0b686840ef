// The float64 density-grid twin (src/reference/medium.ts) against facts that hold
// for every grid: trilinear interpolation reproduces linear fields exactly, passes
// through the samples, is clamped to the edge and vanishes outside the box; the
// majorant grid bounds it everywhere; the segment majorant equals a brute-force
// scan of the cells a segment meets; a constant grid's τ is densityScale·ρ times the chord.
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  GRID_DDA_MAX_CELLS,
  gridDensityTrilinear,
  gridIsConstant,
  gridMajorantAlongRay,
  gridMajorantBuild,
  gridMajorantLookup,
  gridOpticalDepthConstant,
  gridSegmentInBounds,
  makeDensityGrid,
  type DensityGrid,
  type DensityGridData,
  type Vec3,
} from '../../src/reference/medium.ts';

/** Uniform on [min, max] without fast-check's bias towards the ends. */
const uniform = (min: number, max: number) =>
  fc.noBias(fc.integer({ min: 0, max: 2 ** 30 })).map((i) => min + ((max - min) * i) / 2 ** 30);
const unit3 = (lo: number, hi: number) =>
  fc.tuple(uniform(lo, hi), uniform(lo, hi), uniform(lo, hi));

/** A grid of 1–6 samples per axis in a box of random position and size, values in [0, 3]. */
const gridArbitrary = fc
  .record({
    dimensions: fc.tuple(
      fc.integer({ min: 1, max: 6 }),
      fc.integer({ min: 1, max: 6 }),
      fc.integer({ min: 1, max: 6 }),
    ),
    boundsMin: unit3(-5, 5),
    size: unit3(0.1, 4),
    densityScale: uniform(0.01, 10),
    seed: fc.nat(),
  })
  .map(({ dimensions, boundsMin, size, densityScale, seed }) => {
    const count = dimensions[0] * dimensions[1] * dimensions[2];
    const values = Array.from({ length: count }, (_, i) => {
      // A few zeros and spikes among smooth-ish values.
      const h = Math.sin(seed * 12.9898 + i * 78.233) * 43758.5453;
      const r = h - Math.floor(h);
      return r < 0.1 ? 0 : r > 0.95 ? 3 : r;
    });
    return makeDensityGrid(
      values,
      dimensions,
      boundsMin,
      boundsMin.map((m, a) => m + (size[a] ?? 1)) as unknown as Vec3,
      densityScale,
    );
  });

/** A point at fractions s of the box (s outside [0, 1] is outside the box). */
function at(grid: DensityGrid, s: readonly number[]): Vec3 {
  return s.map(
    (x, a) => grid.boundsMin[a as 0] + x * (grid.boundsMax[a as 0] - grid.boundsMin[a as 0]),
  ) as unknown as Vec3;
}

function centre(grid: DensityGrid, cell: readonly number[]): Vec3 {
  return at(
    grid,
    cell.map((c, a) => (c + 0.5) / grid.dimensions[a as 0]),
  );
}

function linearGrid(dimensions: Vec3, coefficients: readonly number[]): DensityGridData {
  const grid = makeDensityGrid(
    new Array(dimensions[0] * dimensions[1] * dimensions[2]).fill(0),
    dimensions,
    [-1, 0, 2],
    [3, 1.5, 3],
    2,
  );
  const [c0, cx, cy, cz] = coefficients as [number, number, number, number];
  for (let k = 0; k < dimensions[2]; k++)
    for (let j = 0; j < dimensions[1]; j++)
      for (let i = 0; i < dimensions[0]; i++) {
        const [x, y, z] = centre(grid.grid, [i, j, k]);
        grid.volume[i + dimensions[0] * (j + dimensions[1] * k)] = c0 + cx * x + cy * y + cz * z;
      }
  return grid;
}

describe('gridDensityTrilinear (cell-centred, clamp-to-edge, 0 outside)', () => {
  it('passes through every sample: σt at a sample centre is densityScale times the sample', () => {
    fc.assert(
      fc.property(gridArbitrary, ({ grid, volume }) => {
        const [nx, ny, nz] = grid.dimensions;
        for (let k = 0; k < nz; k++)
          for (let j = 0; j < ny; j++)
            for (let i = 0; i < nx; i++) {
              const expected = grid.densityScale * (volume[i + nx * (j + ny * k)] ?? NaN);
              const value = gridDensityTrilinear(grid, volume, centre(grid, [i, j, k]));
              // The centre's coordinates carry float64 rounding: a few 1e-16 of u.
              if (Math.abs(value - expected) > 1e-12 * (1 + expected)) return false;
            }
        return true;
      }),
      { numRuns: 200 },
    );
  });

  it('reproduces a linear field exactly inside the hull of the centres (trilinear is exact for degree 1)', () => {
    const data = linearGrid([5, 4, 3], [0.5, 0.2, -0.3, 0.4]);
    const { grid, volume } = data;
    const first = centre(grid, [0, 0, 0]);
    const last = centre(grid, [4, 3, 2]);
    fc.assert(
      fc.property(unit3(0, 1), (s) => {
        const p = s.map(
          (x, a) => first[a as 0] + x * (last[a as 0] - first[a as 0]),
        ) as unknown as Vec3;
        // The stored values are f32: compare with the field through f32 rounding (≤ 1e-7 relative).
        const expected = 2 * (0.5 + 0.2 * p[0] - 0.3 * p[1] + 0.4 * p[2]);
        return Math.abs(gridDensityTrilinear(grid, volume, p) - expected) <= 2e-7 * 4;
      }),
    );
  });

  it('is linear between neighbouring centres along each axis (midpoint = mean of the ends)', () => {
    fc.assert(
      fc.property(gridArbitrary, uniform(0, 1), fc.nat(), ({ grid, volume }, t, pick) => {
        for (const axis of [0, 1, 2] as const) {
          if (grid.dimensions[axis] < 2) continue;
          const cell = grid.dimensions.map((n) => pick % n);
          cell[axis] = pick % (grid.dimensions[axis] - 1);
          const a = centre(grid, cell);
          const b = centre(
            grid,
            cell.map((c, k) => (k === axis ? c + 1 : c)),
          );
          const lerp = (w: number): Vec3 =>
            a.map((x, k) => x + w * ((b[k] ?? 0) - x)) as unknown as Vec3;
          const fa = gridDensityTrilinear(grid, volume, a);
          const fb = gridDensityTrilinear(grid, volume, b);
          const ft = gridDensityTrilinear(grid, volume, lerp(t));
          if (Math.abs(ft - (fa + t * (fb - fa))) > 1e-12 * (1 + Math.abs(fa) + Math.abs(fb)))
            return false;
        }
        return true;
      }),
      { numRuns: 300 },
    );
  });

  it('clamps to the edge: in the outer half cell σt does not change along the face normal', () => {
    fc.assert(
      fc.property(
        gridArbitrary,
        unit3(0, 1),
        uniform(0, 0.5),
        fc.constantFrom(0, 1, 2),
        fc.boolean(),
        ({ grid, volume }, s, depth, axis, upper) => {
          const n = grid.dimensions[axis];
          const onFace = [...s];
          onFace[axis] = upper ? 1 : 0;
          const inside = [...s];
          inside[axis] = upper ? 1 - depth / n : depth / n;
          const a = gridDensityTrilinear(grid, volume, at(grid, onFace));
          const b = gridDensityTrilinear(grid, volume, at(grid, inside));
          return Math.abs(a - b) <= 1e-12 * (1 + a);
        },
      ),
    );
  });

  it('is 0 outside the closed box and ≥ 0 inside; the faces belong to the box', () => {
    fc.assert(
      fc.property(gridArbitrary, unit3(-1, 2), ({ grid, volume }, s) => {
        const inside = s.every((x) => x >= 0 && x <= 1);
        const value = gridDensityTrilinear(grid, volume, at(grid, s));
        return inside ? value >= 0 : value === 0;
      }),
    );
    const ones = makeDensityGrid([1, 1, 1, 1, 1, 1, 1, 1], [2, 2, 2], [0, 0, 0], [1, 1, 1], 1);
    expect(gridDensityTrilinear(ones.grid, ones.volume, [1, 1, 1])).toBe(1);
    expect(gridDensityTrilinear(ones.grid, ones.volume, [1 + 1e-12, 0.5, 0.5])).toBe(0);
  });
});

describe('gridMajorantBuild and gridMajorantLookup', () => {
  it('bound the trilinear density everywhere, for any block size (σt ≤ σ̄, physics.md §4.5)', () => {
    fc.assert(
      fc.property(
        gridArbitrary,
        fc.integer({ min: 1, max: 4 }),
        fc.array(unit3(-0.1, 1.1), { minLength: 50, maxLength: 50 }),
        ({ grid, volume }, block, points) => {
          const majorant = gridMajorantBuild(grid, volume, block);
          return points.every((s) => {
            const p = at(grid, s);
            return (
              gridDensityTrilinear(grid, volume, p) <=
              gridMajorantLookup(majorant.grid, majorant.volume, p)
            );
          });
        },
      ),
      { numRuns: 300 },
    );
  });

  it('also right next to block faces, where lookups blend the sample across the face', () => {
    fc.assert(
      fc.property(
        gridArbitrary,
        fc.integer({ min: 1, max: 3 }),
        fc.nat(),
        unit3(0, 1),
        uniform(-1e-9, 1e-9),
        ({ grid, volume }, block, pick, s, e) => {
          const majorant = gridMajorantBuild(grid, volume, block);
          return [0, 1, 2].every((axis) => {
            const n = grid.dimensions[axis as 0];
            const face = (pick % Math.max(1, Math.ceil(n / block))) * block;
            const q = [...s];
            q[axis] = Math.min(Math.max(face / n + e, 0), 1);
            const p = at(grid, q);
            return (
              gridDensityTrilinear(grid, volume, p) <=
              gridMajorantLookup(majorant.grid, majorant.volume, p)
            );
          });
        },
      ),
      { numRuns: 300 },
    );
  });

  it('covers the fine box and is exact for a constant grid; a block as large as the grid holds the global maximum', () => {
    fc.assert(
      fc.property(gridArbitrary, fc.integer({ min: 1, max: 5 }), ({ grid, volume }, block) => {
        const majorant = gridMajorantBuild(grid, volume, block);
        const covers = [0, 1, 2].every(
          (a) =>
            majorant.grid.boundsMin[a as 0] === grid.boundsMin[a as 0] &&
            majorant.grid.boundsMax[a as 0] >= grid.boundsMax[a as 0],
        );
        const whole = gridMajorantBuild(grid, volume, 6);
        return covers && whole.volume.length === 1 && whole.volume[0] === Math.max(...volume);
      }),
    );
    const constant = makeDensityGrid(new Array(27).fill(0.6), [3, 3, 3], [0, 0, 0], [3, 3, 3], 2);
    const majorant = gridMajorantBuild(constant.grid, constant.volume, 2);
    expect(gridIsConstant(constant.volume)).toBe(true);
    expect(majorant.grid.dimensions).toEqual([2, 2, 2]);
    expect(Array.from(majorant.volume)).toEqual(new Array(8).fill(Math.fround(0.6)));
  });
});

/** Brute force: the cells whose box the segment meets over a positive length. */
function bruteForceSegmentMajorant(
  majorant: DensityGridData,
  origin: Vec3,
  direction: Vec3,
  tMin: number,
  tMax: number,
) {
  const { grid, volume } = majorant;
  const [mx, my, mz] = grid.dimensions;
  let largest = 0;
  let cells = 0;
  for (let k = 0; k < mz; k++)
    for (let j = 0; j < my; j++)
      for (let i = 0; i < mx; i++) {
        const cell: DensityGrid = {
          dimensions: [1, 1, 1],
          boundsMin: at(grid, [i / mx, j / my, k / mz]),
          boundsMax: at(grid, [(i + 1) / mx, (j + 1) / my, (k + 1) / mz]),
          densityScale: 1,
        };
        const [t0, t1] = gridSegmentInBounds(cell, origin, direction, tMin, tMax);
        if (t1 > t0) {
          cells += 1;
          largest = Math.max(largest, volume[i + mx * (j + my * k)] ?? 0);
        }
      }
  return { majorant: grid.densityScale * largest, cellsVisited: cells };
}

const segmentArbitrary = (grid: DensityGrid) =>
  fc
    .record({
      from: unit3(-0.5, 1.5),
      to: unit3(0, 1),
      tMin: uniform(-0.5, 0.8),
      length: uniform(0, 1.5),
    })
    .map(({ from, to, tMin, length }) => {
      const origin = at(grid, from);
      const target = at(grid, to);
      return {
        origin,
        direction: target.map((t, a) => t - origin[a as 0]) as unknown as Vec3,
        tMin,
        tMax: tMin + length,
      };
    });

describe('gridMajorantAlongRay', () => {
  const fine = makeDensityGrid(
    Array.from({ length: 6 * 5 * 4 }, (_, i) => (i * 0.37) % 1.9),
    [6, 5, 4],
    [-2, 0, 1],
    [1, 2.5, 3],
    1.5,
  );
  const majorant = gridMajorantBuild(fine.grid, fine.volume, 2);

  it('equals a brute-force scan of every coarse cell the segment meets (majorant and count)', () => {
    fc.assert(
      fc.property(segmentArbitrary(majorant.grid), ({ origin, direction, tMin, tMax }) => {
        const dda = gridMajorantAlongRay(
          majorant.grid,
          majorant.volume,
          origin,
          direction,
          tMin,
          tMax,
        );
        const brute = bruteForceSegmentMajorant(majorant, origin, direction, tMin, tMax);
        if (tMax === tMin) return dda.cellsVisited <= 1;
        return (
          dda.majorant === brute.majorant &&
          dda.cellsVisited === brute.cellsVisited &&
          dda.capped === 0
        );
      }),
      { numRuns: 500 },
    );
  });

  it('bounds the density at every point of the segment', () => {
    fc.assert(
      fc.property(
        segmentArbitrary(majorant.grid),
        fc.array(uniform(0, 1), { minLength: 40, maxLength: 40 }),
        ({ origin, direction, tMin, tMax }, ts) => {
          const bound = gridMajorantAlongRay(
            majorant.grid,
            majorant.volume,
            origin,
            direction,
            tMin,
            tMax,
          ).majorant;
          return ts.every((s) => {
            const t = tMin + s * (tMax - tMin);
            const p = origin.map((o, a) => o + t * direction[a as 0]) as unknown as Vec3;
            return gridDensityTrilinear(fine.grid, fine.volume, p) <= bound;
          });
        },
      ),
    );
  });

  it(`visits at most ${GRID_DDA_MAX_CELLS} cells and says when it stopped early`, () => {
    const long = makeDensityGrid(new Array(400).fill(1), [400, 1, 1], [0, 0, 0], [400, 1, 1], 1);
    const r = gridMajorantAlongRay(long.grid, long.volume, [-1, 0.5, 0.5], [1, 0, 0], 0, 1000);
    expect(r).toEqual({ majorant: 1, cellsVisited: GRID_DDA_MAX_CELLS, capped: 1 });
    const short = gridMajorantAlongRay(long.grid, long.volume, [-1, 0.5, 0.5], [1, 0, 0], 0, 100);
    expect(short).toEqual({ majorant: 1, cellsVisited: 99, capped: 0 });
  });
});

describe('gridOpticalDepthConstant (the one grid with a cheap exact τ)', () => {
  const constant = makeDensityGrid(new Array(12).fill(0.8), [3, 2, 2], [0, -1, 2], [2, 1, 5], 2.5);
  const sigmaT = Math.fround(2.5) * Math.fround(0.8);

  it('is densityScale·ρ times the chord inside the box (axis-aligned: the box width)', () => {
    expect(
      gridOpticalDepthConstant(constant.grid, constant.volume, [1, 0, -10], [0, 0, 3], -50, 50),
    ).toBeCloseTo(sigmaT * 3, 12);
    expect(
      gridOpticalDepthConstant(constant.grid, constant.volume, [1, 0, 3], [0, 0, 1], 0, 0.5),
    ).toBeCloseTo(sigmaT * 0.5, 12);
    expect(
      gridOpticalDepthConstant(constant.grid, constant.volume, [5, 0, 3], [0, 0, 1], -9, 9),
    ).toBe(0);
  });

  it('equals a midpoint-rule integral of gridDensityTrilinear along the segment (error ≤ 2σt·|d|·Δt)', () => {
    fc.assert(
      fc.property(segmentArbitrary(constant.grid), ({ origin, direction, tMin, tMax }) => {
        const n = 4000;
        const dt = (tMax - tMin) / n;
        let sum = 0;
        for (let i = 0; i < n; i++) {
          const t = tMin + (i + 0.5) * dt;
          sum += gridDensityTrilinear(
            constant.grid,
            constant.volume,
            origin.map((o, a) => o + t * direction[a as 0]) as unknown as Vec3,
          );
        }
        const speed = Math.hypot(...direction);
        const quadrature = sum * dt * speed;
        const exact = gridOpticalDepthConstant(
          constant.grid,
          constant.volume,
          origin,
          direction,
          tMin,
          tMax,
        );
        // Only the two cells that hold the box faces are mis-integrated, each by ≤ σt·|d|·Δt.
        return Math.abs(quadrature - exact) <= 2 * sigmaT * speed * dt + 1e-12;
      }),
      { numRuns: 200 },
    );
  });

  it('is additive along the ray and the same in both directions', () => {
    fc.assert(
      fc.property(
        segmentArbitrary(constant.grid),
        uniform(0, 1),
        ({ origin, direction, tMin, tMax }, split) => {
          const tau = (a: number, b: number) =>
            gridOpticalDepthConstant(constant.grid, constant.volume, origin, direction, a, b);
          const tSplit = tMin + split * (tMax - tMin);
          const whole = tau(tMin, tMax);
          const reverse = gridOpticalDepthConstant(
            constant.grid,
            constant.volume,
            origin.map((o, a) => o + tMax * direction[a as 0]) as unknown as Vec3,
            direction.map((d) => -d) as unknown as Vec3,
            0,
            tMax - tMin,
          );
          return (
            Math.abs(tau(tMin, tSplit) + tau(tSplit, tMax) - whole) <= 1e-12 * (1 + whole) &&
            Math.abs(reverse - whole) <= 1e-12 * (1 + whole)
          );
        },
      ),
    );
  });
});
