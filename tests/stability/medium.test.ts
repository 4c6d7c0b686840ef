// Hard cases of the 3D density grids of shaders/medium.wesl, each with its input and
// expected output, run through both implementations (WGSL on Dawn and the float64
// twin): degenerate grids (1×1×1, all zero, zero-size bounds, negative values, huge
// densityScale), rays parallel to the axes and lying on faces, rays that miss the box, zero-length
// and reversed segments, a zero direction, and a fuzz over f32 extremes. Never NaN or
// Inf, never a negative σt, σ̄ or τ, never more cells than the cap (physics.md §9, §10).
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  GRID_DDA_MAX_CELLS,
  gridDensityTrilinear,
  gridMajorantBuild,
  gridMajorantLookup,
  makeDensityGrid,
  type DensityGridData,
  type GridMajorantSegment,
  type Vec3,
} from '../../src/reference/medium.ts';
import {
  f32Ray,
  gpuDensity,
  gpuMajorantAlongRay,
  gpuMajorantLookup,
  gpuOpticalDepthConstant,
  gpuSegmentInBounds,
  type Ray,
  twinMajorantAlongRay,
  twinOpticalDepthConstant,
  twinSegmentInBounds,
} from '../support/densityGridGpu.ts';
import { F32_MAX, F32_MIN_SUBNORMAL } from '../support/f32.ts';

const cube = (n: number, value: number): number[] => new Array(n * n * n).fill(value);

/** 1×1×1, ρ = 2, densityScale = 0.5: σt = 1 in the unit box. */
const ONE = makeDensityGrid([2], [1, 1, 1], [0, 0, 0], [1, 1, 1], 0.5);
/** All samples 0. */
const ZERO = makeDensityGrid(cube(3, 0), [3, 3, 3], [0, 0, 0], [1, 1, 1], 4);
/** Zero-size bounds: boundsMin.y = boundsMax.y, so the box has no volume. */
const FLAT = makeDensityGrid(cube(2, 1), [2, 2, 2], [0, 0, 0], [1, 0, 1], 1);
/**
 * densityScale = 1e20 /m and ρ = 1e30: the density (dimensionless) is clamped to 1e18, the
 * coefficient is not (a bound on it would be a unit of length, issue 20), so σt = 1e38.
 */
const HUGE = makeDensityGrid(cube(2, 1e30), [2, 2, 2], [0, 0, 0], [1, 1, 1], 1e20);
/** Negative samples and densityScale are not physical: clamped to σt = 0. */
const NEGATIVE = makeDensityGrid(cube(2, -1), [2, 2, 2], [0, 0, 0], [1, 1, 1], -2);
/** A row of four majorant cells with values 1, 2, 3, 4 along x in [0, 4]×[0, 1]². */
const ROW = makeDensityGrid([1, 2, 3, 4], [4, 1, 1], [0, 0, 0], [4, 1, 1], 1);

/**
 * Expected values here are exact or 1e38 = 1e20·1e18, which the GPU computes from
 * f32(1e20)·f32(1e18) (each within 1.6e-8): 2e-7 relative covers that and one or two f32 roundings.
 */
const CLOSE_RELATIVE = 2e-7;

function close(actual: number, expected: number): boolean {
  return actual === expected || Math.abs(actual - expected) <= CLOSE_RELATIVE * Math.abs(expected);
}

/** A ray as the GPU sees it (rounded to f32). */
const ray = (origin: Vec3, direction: Vec3, tMin: number, tMax: number): Ray =>
  f32Ray({ origin, direction, tMin, tMax });

describe('gridDensityTrilinear and gridMajorantLookup on degenerate grids (both implementations)', () => {
  const cases: { name: string; grid: DensityGridData; p: Vec3; expected: number }[] = [
    {
      name: '1×1×1 grid at the centre: densityScale·ρ = 1',
      grid: ONE,
      p: [0.5, 0.5, 0.5],
      expected: 1,
    },
    { name: '1×1×1 grid at a corner (closed box)', grid: ONE, p: [1, 1, 1], expected: 1 },
    { name: '1×1×1 grid on a face', grid: ONE, p: [0, 0.3, 0.9], expected: 1 },
    { name: '1×1×1 grid just outside', grid: ONE, p: [1.0000001, 0.5, 0.5], expected: 0 },
    { name: 'all-zero grid', grid: ZERO, p: [0.4, 0.6, 0.2], expected: 0 },
    {
      name: 'zero-size bounds: a point on the flat box',
      grid: FLAT,
      p: [0.5, 0, 0.5],
      expected: 0,
    },
    {
      name: 'huge densityScale and ρ: ρ clamped to 1e18, densityScale 1e20 not clamped',
      grid: HUGE,
      p: [0.3, 0.6, 0.9],
      expected: 1e38,
    },
    {
      name: 'negative densityScale and ρ: σt = 0',
      grid: NEGATIVE,
      p: [0.5, 0.5, 0.5],
      expected: 0,
    },
    { name: 'point at +f32 max', grid: ONE, p: [F32_MAX, F32_MAX, F32_MAX], expected: 0 },
    { name: 'point at −f32 max', grid: ONE, p: [-F32_MAX, 0.5, 0.5], expected: 0 },
    { name: 'subnormal point inside', grid: ONE, p: [F32_MIN_SUBNORMAL, 0.5, 0.5], expected: 1 },
  ];
  const points = cases.map((c) => c.p);

  it.each(cases)('density: $name', async ({ grid, p, expected }) => {
    const [gpu] = await gpuDensity(grid, [p]);
    const twin = gridDensityTrilinear(grid.grid, grid.volume, p);
    expect(Number.isFinite(gpu)).toBe(true);
    expect(close(gpu ?? NaN, expected), `GPU ${gpu}`).toBe(true);
    expect(close(twin, expected), `twin ${twin}`).toBe(true);
  });

  it('majorant lookups of each grid’s majorant grid bound the density and stay finite', async () => {
    for (const { name, grid } of cases) {
      const majorant = gridMajorantBuild(grid.grid, grid.volume, 2);
      const [gpuMajorant, gpuDensityValues] = await Promise.all([
        gpuMajorantLookup(majorant, points),
        gpuDensity(grid, points),
      ]);
      points.forEach((p, i) => {
        const m = gpuMajorant[i] ?? NaN;
        const twin = gridMajorantLookup(majorant.grid, majorant.volume, p);
        expect(Number.isFinite(m) && m >= 0, `${name}: GPU majorant ${m}`).toBe(true);
        expect(m >= (gpuDensityValues[i] ?? NaN), `${name}: GPU bound at ${p.join(', ')}`).toBe(
          true,
        );
        expect(twin >= gridDensityTrilinear(grid.grid, grid.volume, p), `${name}: twin bound`).toBe(
          true,
        );
      });
    }
  });
});

interface RayCase {
  name: string;
  ray: Ray;
  expected: GridMajorantSegment;
}

describe('gridMajorantAlongRay: axis-parallel rays, rays on faces, misses, empty segments', () => {
  const result = (majorant: number, cellsVisited: number, capped = 0): GridMajorantSegment => ({
    majorant,
    cellsVisited,
    capped,
  });
  const cases: RayCase[] = [
    {
      name: 'along +x through the row',
      ray: ray([-1, 0.5, 0.5], [1, 0, 0], 0, 10),
      expected: result(4, 4),
    },
    {
      name: 'along −x through the row',
      ray: ray([5, 0.5, 0.5], [-1, 0, 0], 0, 10),
      expected: result(4, 4),
    },
    {
      name: 'along +x, x from 1.5 to 2.5',
      ray: ray([1.5, 0.5, 0.5], [1, 0, 0], 0, 1),
      expected: result(3, 2),
    },
    {
      name: 'lying on the face y = 0 (closed box)',
      ray: ray([-1, 0, 0.5], [1, 0, 0], 0, 10),
      expected: result(4, 4),
    },
    {
      name: 'lying on the face y = 1 (closed box)',
      ray: ray([-1, 1, 1], [1, 0, 0], 0, 10),
      expected: result(4, 4),
    },
    {
      name: 'parallel to the face y = 1, just outside',
      ray: ray([-1, 1.000001, 0.5], [1, 0, 0], 0, 10),
      expected: result(0, 0),
    },
    {
      name: 'along +y on the interior plane x = 2: the cell above it',
      ray: ray([2, -1, 0.5], [0, 1, 0], 0, 5),
      expected: result(3, 1),
    },
    {
      name: 'along −x from the interior face x = 2: the cell below it',
      ray: ray([2, 0.5, 0.5], [-1, 0, 0], 0, 0.5),
      expected: result(2, 1),
    },
    {
      name: 'zero length on x = 2 moving −x: the cell below',
      ray: ray([2, 0.5, 0.5], [-1, 0, 0], 0, 0),
      expected: result(2, 1),
    },
    {
      name: 'zero length on x = 2 moving +x: the cell above',
      ray: ray([2, 0.5, 0.5], [1, 0, 0], 0, 0),
      expected: result(3, 1),
    },
    {
      name: 'zero direction inside: one cell',
      ray: ray([0.5, 0.5, 0.5], [0, 0, 0], 0, 1),
      expected: result(1, 1),
    },
    {
      name: 'zero direction outside: miss',
      ray: ray([0.5, 3, 0.5], [0, 0, 0], 0, 1),
      expected: result(0, 0),
    },
    {
      name: 'reversed segment (tMax < tMin)',
      ray: ray([-1, 0.5, 0.5], [1, 0, 0], 5, 1),
      expected: result(0, 0),
    },
    {
      name: 'segment ends before the box',
      ray: ray([-3, 0.5, 0.5], [1, 0, 0], 0, 2),
      expected: result(0, 0),
    },
    {
      name: 'segment starts after the box',
      ray: ray([-3, 0.5, 0.5], [1, 0, 0], 8, 20),
      expected: result(0, 0),
    },
    {
      name: 'diagonal miss above the box',
      ray: ray([-1, 2, 0.5], [1, 0.1, 0], 0, 20),
      expected: result(0, 0),
    },
    {
      name: 'direction component 1e-30: no overflow',
      ray: ray([-1, 0.5, 0.5], [1, 1e-30, 0], 0, 10),
      expected: result(4, 4),
    },
    {
      name: 'segment over ±f32 max (clamped to ±1e17)',
      ray: ray([-1, 0.5, 0.5], [1, 0, 0], -F32_MAX, F32_MAX),
      expected: result(4, 4),
    },
    {
      name: 'direction 1e20: the whole row within t ≤ 1e-19',
      ray: ray([-1, 0.5, 0.5], [1e20, 0, 0], 0, 1),
      expected: result(4, 4),
    },
    {
      name: 'starting inside, leaving through the corner (1 cell at a time)',
      ray: ray([0.5, 0.5, 0.5], [1, 1, 1], 0, 10),
      expected: result(1, 1),
    },
  ];

  it.each(cases)('$name', async ({ ray: r, expected }) => {
    const [gpu] = await gpuMajorantAlongRay(ROW, [r]);
    const twin = twinMajorantAlongRay(ROW, r);
    expect(gpu).toEqual(expected);
    expect(twin).toEqual(expected);
  });

  it('degenerate majorant grids: empty box → miss; all-zero grid → majorant 0 over the visited cells', async () => {
    const r = ray([-1, 0.5, 0.5], [1, 0, 0], 0, 10);
    const flat = gridMajorantBuild(FLAT.grid, FLAT.volume, 1);
    const zero = gridMajorantBuild(ZERO.grid, ZERO.volume, 1);
    const huge = gridMajorantBuild(HUGE.grid, HUGE.volume, 1);
    const [gFlat] = await gpuMajorantAlongRay(flat, [r]);
    const [gZero] = await gpuMajorantAlongRay(zero, [r]);
    const [gHuge] = await gpuMajorantAlongRay(huge, [r]);
    expect(gFlat).toEqual(result(0, 0));
    expect(twinMajorantAlongRay(flat, r)).toEqual(result(0, 0));
    expect(gZero).toEqual(result(0, 3));
    expect(twinMajorantAlongRay(zero, r)).toEqual(result(0, 3));
    expect(close(gHuge?.majorant ?? NaN, 1e38)).toBe(true);
    const twinHuge = twinMajorantAlongRay(huge, r);
    expect(close(twinHuge.majorant, 1e38)).toBe(true);
  });
});

describe('gridOpticalDepthConstant and gridSegmentInBounds: hard cases (both implementations)', () => {
  const cases: {
    name: string;
    grid: DensityGridData;
    ray: Ray;
    tau: number;
    segment: [number, number] | null;
  }[] = [
    {
      name: 'along +x through the unit box, |d| = 2',
      grid: ONE,
      ray: ray([-1, 0.5, 0.5], [2, 0, 0], -10, 10),
      tau: 1,
      segment: [0.5, 1],
    },
    {
      name: 'body diagonal: chord √3',
      grid: ONE,
      ray: ray([-1, -1, -1], [1, 1, 1], 0, 5),
      tau: Math.sqrt(3),
      segment: [1, 2],
    },
    {
      name: 'zero-length segment inside: τ = 0',
      grid: ONE,
      ray: ray([0.5, 0.5, 0.5], [1, 0, 0], 0, 0),
      tau: 0,
      segment: [0, 0],
    },
    {
      name: 'zero direction inside: τ = 0',
      grid: ONE,
      ray: ray([0.5, 0.5, 0.5], [0, 0, 0], 0, 4),
      tau: 0,
      segment: [0, 4],
    },
    {
      name: 'miss parallel to x',
      grid: ONE,
      ray: ray([-1, 2, 0.5], [1, 0, 0], 0, 9),
      tau: 0,
      segment: null,
    },
    {
      name: 'reversed segment',
      grid: ONE,
      ray: ray([-1, 0.5, 0.5], [1, 0, 0], 3, 0),
      tau: 0,
      segment: null,
    },
    {
      name: 'all-zero grid',
      grid: ZERO,
      ray: ray([-1, 0.5, 0.5], [1, 0, 0], 0, 9),
      tau: 0,
      segment: [1, 2],
    },
    {
      name: 'zero-size bounds: empty',
      grid: FLAT,
      ray: ray([-1, 0, 0.5], [1, 0, 0], 0, 9),
      tau: 0,
      segment: null,
    },
    {
      name: 'negative densityScale and ρ: τ = 0',
      grid: NEGATIVE,
      ray: ray([-1, 0.5, 0.5], [1, 0, 0], 0, 9),
      tau: 0,
      segment: [1, 2],
    },
    {
      name: 'huge densityScale·ρ: τ = 1e38 (σt) × chord 1',
      grid: HUGE,
      ray: ray([-1, 0.5, 0.5], [1, 0, 0], 0, 9),
      tau: 1e38,
      segment: [1, 2],
    },
    {
      name: 'segment over ±f32 max',
      grid: ONE,
      ray: ray([-1, 0.5, 0.5], [1, 0, 0], -F32_MAX, F32_MAX),
      tau: 1,
      segment: [1, 2],
    },
  ];

  it.each(cases)('$name', async ({ grid, ray: r, tau, segment }) => {
    const [gpuTau] = await gpuOpticalDepthConstant(grid, [r]);
    const [gpuSegment] = await gpuSegmentInBounds(grid, [r]);
    const twinTau = twinOpticalDepthConstant(grid, r);
    const twinSegment = twinSegmentInBounds(grid, r);
    expect(close(gpuTau ?? NaN, tau), `GPU τ ${gpuTau}`).toBe(true);
    expect(close(twinTau, tau), `twin τ ${twinTau}`).toBe(true);
    for (const [name, s] of [
      ['GPU', gpuSegment],
      ['twin', twinSegment],
    ] as const) {
      if (segment === null)
        expect((s?.[0] ?? NaN) > (s?.[1] ?? NaN), `${name} segment ${s?.join(', ')} is empty`).toBe(
          true,
        );
      else
        expect(
          s?.every((t, k) => close(t, segment[k] ?? NaN)),
          `${name} segment ${s?.join(', ')}`,
        ).toBe(true);
    }
  });
});

describe('fuzz: f32 extremes never give NaN, Inf, negative values or more than the cap', () => {
  const extremes = fc.oneof(
    fc.constantFrom(
      0,
      -0,
      F32_MIN_SUBNORMAL,
      1e-30,
      0.5,
      1,
      2,
      1e17,
      1e18,
      1e30,
      F32_MAX,
      -1,
      -1e30,
      -F32_MAX,
    ),
    fc.float({ noNaN: true, noDefaultInfinity: true }),
  );
  const vec = fc.tuple(extremes, extremes, extremes);
  const rays = fc
    .sample(fc.tuple(vec, vec, extremes, extremes), { numRuns: 512, seed: 20261124 })
    .map(([origin, direction, tMin, tMax]) => ray(origin, direction, tMin, tMax));
  const grid = makeDensityGrid(
    Array.from({ length: 27 }, (_, i) => (i % 5) * 0.5),
    [3, 3, 3],
    [-1, 0, 1],
    [1, 1e-3, 1e6],
    7,
  );
  const majorant = gridMajorantBuild(grid.grid, grid.volume, 2);

  it('512 fuzzed rays: segment, segment majorant and constant-grid τ', async () => {
    const [segments, majorants, taus] = await Promise.all([
      gpuSegmentInBounds(grid, rays),
      gpuMajorantAlongRay(majorant, rays),
      gpuOpticalDepthConstant(grid, rays),
    ]);
    rays.forEach((r, i) => {
      const label = `ray ${i}: ${JSON.stringify(r)}`;
      const s = segments[i] ?? [NaN, NaN];
      expect(s.every(Number.isFinite), `${label} segment ${s.join(', ')}`).toBe(true);
      const m = majorants[i];
      expect(Number.isFinite(m?.majorant) && (m?.majorant ?? -1) >= 0, `${label} majorant`).toBe(
        true,
      );
      expect(m?.cellsVisited ?? Infinity, label).toBeLessThanOrEqual(GRID_DDA_MAX_CELLS);
      expect([0, 1], label).toContain(m?.capped);
      const tau = taus[i] ?? NaN;
      expect(Number.isFinite(tau) && tau >= 0, `${label} τ ${tau}`).toBe(true);
      const twin = twinMajorantAlongRay(majorant, r);
      const twinTau = twinOpticalDepthConstant(grid, r);
      expect(Number.isFinite(twin.majorant) && twin.majorant >= 0, `${label} twin majorant`).toBe(
        true,
      );
      expect(Number.isFinite(twinTau) && twinTau >= 0, `${label} twin τ`).toBe(true);
    });
  });

  it('2048 fuzzed points: density and majorant lookup', async () => {
    const points = fc
      .sample(vec, { numRuns: 2048, seed: 77 })
      .map((p) => p.map(Math.fround) as unknown as Vec3);
    const [density, lookups] = await Promise.all([
      gpuDensity(grid, points),
      gpuMajorantLookup(majorant, points),
    ]);
    points.forEach((p, i) => {
      const d = density[i] ?? NaN;
      const m = lookups[i] ?? NaN;
      expect(Number.isFinite(d) && d >= 0 && d <= m, `at ${p.join(', ')}: ${d} ≤ ${m}`).toBe(true);
      const twin = gridDensityTrilinear(grid.grid, grid.volume, p);
      expect(
        Number.isFinite(twin) &&
          twin >= 0 &&
          twin <= gridMajorantLookup(majorant.grid, majorant.volume, p),
      ).toBe(true);
    });
  });
});
