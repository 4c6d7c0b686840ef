// The data set of <sb-transfer-function>: a 3D Shepp–Logan head phantom in
// Hounsfield units, generated deterministically at page load (nothing is shipped).
//
// Provenance. The ten ellipsoids are the 3D extension of the Shepp–Logan head
// phantom (Shepp & Logan 1974, "The Fourier reconstruction of a head section", IEEE
// Trans. Nucl. Sci. 21(3)) given by Kak & Slaney (1988, "Principles of Computerized
// Tomographic Imaging", ch. 3), in the form tabulated by Toft (1996, "The Radon
// Transform", pp. 199–200) and distributed with the widely used MATLAB function
// phantom3d (M. Smith, 2006): semi-axes, centres and Euler angles (φ, θ, ψ) in a
// cube [−1, 1]³. Their gray levels are the original 2D phantom's, 2, −0.98, −0.02,
// −0.02 and 0.01 for the six small ones, which are attenuation coefficients relative
// to water (water = 1): HU = 1000·(μ/μ_water − 1) gives air −1000 HU, skull +1000 HU,
// brain +20 HU, ventricles 0 HU (like CSF) and lesions +30 HU. One ellipsoid is ours,
// not the phantom's: a 6 mm scalp of soft tissue (+40 HU) around the skull, so that a
// "skin" surface and the bone below it are different surfaces.
//
// The phantom fills a 24 cm cube (a head CT's field of view). World axes follow the
// book's camera (y up): the phantom's z (cranio-caudal) is world +y, its y is world −z.

/** Voxels per axis of the generated grid. */
export const PHANTOM_SIZE = 96;
/** Half the edge of the phantom's cube (m): a 24 cm field of view. */
export const PHANTOM_HALF_EXTENT = 0.12;
/** Sub-samples per axis and voxel: the partial-volume effect of a real scanner's voxels. */
export const PHANTOM_SUPERSAMPLING = 2;
/** DICOM rescale intercept of CT: stored value = HU + 1024, so stored values are ≥ 0. */
export const CT_RESCALE_INTERCEPT = -1024;
export const HU_AIR = -1000;
export const HU_SCALP = 40;

/** One ellipsoid: gray level, semi-axes, centre (in the rotated frame, as phantom3d), Euler angles (°). */
export interface Ellipsoid {
  name: string;
  gray: number;
  axes: readonly [number, number, number];
  centre: readonly [number, number, number];
  angles: readonly [number, number, number];
}

/** Kak & Slaney's 3D Shepp–Logan ellipsoids with the original gray levels. */
export const SHEPP_LOGAN_3D: readonly Ellipsoid[] = [
  { name: 'skull', gray: 2, axes: [0.69, 0.92, 0.81], centre: [0, 0, 0], angles: [0, 0, 0] },
  {
    name: 'brain',
    gray: -0.98,
    axes: [0.6624, 0.874, 0.78],
    centre: [0, -0.0184, 0],
    angles: [0, 0, 0],
  },
  {
    name: 'right ventricle',
    gray: -0.02,
    axes: [0.11, 0.31, 0.22],
    centre: [0.22, 0, 0],
    angles: [-18, 0, 10],
  },
  {
    name: 'left ventricle',
    gray: -0.02,
    axes: [0.16, 0.41, 0.28],
    centre: [-0.22, 0, 0],
    angles: [18, 0, 10],
  },
  {
    name: 'lesion e',
    gray: 0.01,
    axes: [0.21, 0.25, 0.41],
    centre: [0, 0.35, -0.15],
    angles: [0, 0, 0],
  },
  {
    name: 'lesion f',
    gray: 0.01,
    axes: [0.046, 0.046, 0.05],
    centre: [0, 0.1, 0.25],
    angles: [0, 0, 0],
  },
  {
    name: 'lesion g',
    gray: 0.01,
    axes: [0.046, 0.046, 0.05],
    centre: [0, -0.1, 0.25],
    angles: [0, 0, 0],
  },
  {
    name: 'lesion h',
    gray: 0.01,
    axes: [0.046, 0.023, 0.05],
    centre: [-0.08, -0.605, 0],
    angles: [0, 0, 0],
  },
  {
    name: 'lesion i',
    gray: 0.01,
    axes: [0.023, 0.023, 0.02],
    centre: [0, -0.606, 0],
    angles: [0, 0, 0],
  },
  {
    name: 'lesion j',
    gray: 0.01,
    axes: [0.023, 0.046, 0.02],
    centre: [0.06, -0.605, 0],
    angles: [0, 0, 0],
  },
];

/** Our addition: the scalp, 0.05 (6 mm) outside the skull on each semi-axis. */
export const SCALP: Ellipsoid = {
  name: 'scalp',
  gray: 0,
  axes: [0.74, 0.97, 0.86],
  centre: [0, 0, 0],
  angles: [0, 0, 0],
};

type Matrix = readonly [number, number, number, number, number, number, number, number, number];

/** phantom3d's z-x-z Euler rotation A(φ, θ, ψ), row-major. */
export function eulerMatrix(angles: readonly [number, number, number]): Matrix {
  const [phi, theta, psi] = angles.map((a) => (a * Math.PI) / 180) as [number, number, number];
  const [cf, sf, ct, st, cp, sp] = [
    Math.cos(phi),
    Math.sin(phi),
    Math.cos(theta),
    Math.sin(theta),
    Math.cos(psi),
    Math.sin(psi),
  ];
  return [
    cp * cf - ct * sf * sp,
    cp * sf + ct * cf * sp,
    sp * st,
    -sp * cf - ct * sf * cp,
    -sp * sf + ct * cf * cp,
    cp * st,
    st * sf,
    -st * cf,
    ct,
  ];
}

/**
 * Each ellipsoid as 20 numbers in one flat array, for the 7 million point tests of
 * a 96³ grid with 2³ sub-samples: a bounding sphere (centre Aᵀc, radius² = the
 * longest semi-axis²), the rotation A (row-major), the centre c in the rotated
 * frame, 1/r² per axis and the gray level.
 */
const STRIDE = 20;

function pack(list: readonly Ellipsoid[]): Float64Array {
  const packed = new Float64Array(STRIDE * list.length);
  list.forEach((e, index) => {
    const m = eulerMatrix(e.angles);
    const [cx, cy, cz] = e.centre;
    // A p = c at the centre, so p = Aᵀc (A is a rotation).
    packed.set(
      [
        m[0] * cx + m[3] * cy + m[6] * cz,
        m[1] * cx + m[4] * cy + m[7] * cz,
        m[2] * cx + m[5] * cy + m[8] * cz,
        Math.max(...e.axes) ** 2,
        ...m,
        cx,
        cy,
        cz,
        1 / e.axes[0] ** 2,
        1 / e.axes[1] ** 2,
        1 / e.axes[2] ** 2,
        e.gray,
      ],
      STRIDE * index,
    );
  });
  return packed;
}

const PACKED = pack(SHEPP_LOGAN_3D);
const PACKED_SCALP = pack([SCALP]);

/** Whether p (phantom coordinates) is inside ellipsoid `index`: Σ ((A p − c)_k / r_k)² ≤ 1, as phantom3d. */
function inside(e: Float64Array, index: number, x: number, y: number, z: number): boolean {
  const o = STRIDE * index;
  const dx = x - e[o]!;
  const dy = y - e[o + 1]!;
  const dz = z - e[o + 2]!;
  if (dx * dx + dy * dy + dz * dz > e[o + 3]!) return false;
  const u = e[o + 4]! * x + e[o + 5]! * y + e[o + 6]! * z - e[o + 13]!;
  const v = e[o + 7]! * x + e[o + 8]! * y + e[o + 9]! * z - e[o + 14]!;
  const w = e[o + 10]! * x + e[o + 11]! * y + e[o + 12]! * z - e[o + 15]!;
  return u * u * e[o + 16]! + v * v * e[o + 17]! + w * w * e[o + 18]! <= 1;
}

/**
 * The phantom's value in HU at a point of its own cube [−1, 1]³: air outside the
 * scalp, +40 HU in the scalp, else 1000·(Σ gray levels − 1).
 */
export function phantomHounsfield(x: number, y: number, z: number): number {
  if (!inside(PACKED_SCALP, 0, x, y, z)) return HU_AIR;
  if (!inside(PACKED, 0, x, y, z)) return HU_SCALP;
  let mu = PACKED[19]!;
  for (let k = 1; k < SHEPP_LOGAN_3D.length; k++)
    if (inside(PACKED, k, x, y, z)) mu += PACKED[STRIDE * k + 19]!;
  return 1000 * (mu - 1);
}

/** World point (m) → the phantom's cube: world (X, Y, Z) = h·(x, z, −y). */
export function worldToPhantom(p: readonly [number, number, number]): [number, number, number] {
  const h = PHANTOM_HALF_EXTENT;
  return [p[0] / h, -p[2] / h, p[1] / h];
}

export interface PhantomVolume {
  size: number;
  /** Stored values (HU − CT_RESCALE_INTERCEPT), x fastest, then y, then z (world axes). */
  stored: Float32Array;
  /** The same voxels in HU. */
  hounsfield: Float32Array;
}

let cached: PhantomVolume | null = null;

/**
 * The phantom on a size³ grid of cell-centred voxels over the world cube
 * [−h, h]³. A voxel whose centre value equals its six neighbours' lies inside one
 * region and keeps it; a voxel on a boundary is the mean of PHANTOM_SUPERSAMPLING³
 * point values (the partial-volume effect). Then the scanner's blur
 * (blurPointSpread). At 96³ every ellipsoid's shortest
 * semi-axis (0.02) exceeds the lattice's covering radius (√3/2 voxel = 0.018), so
 * each one contains a voxel centre and none is lost. Deterministic; computed once
 * per page.
 */
export function phantomVolume(size = PHANTOM_SIZE): PhantomVolume {
  if (cached && cached.size === size) return cached;
  const n = size;
  const at = (i: number, j: number, k: number): number => i + n * (j + n * k);
  // Voxel centres first: world (X, Y, Z) ↦ phantom (X, −Z, Y).
  const centres = new Float32Array(n * n * n);
  const coordinate = (index: number, offset: number): number => -1 + (2 * (index + offset)) / n;
  for (let k = 0; k < n; k++)
    for (let j = 0; j < n; j++)
      for (let i = 0; i < n; i++)
        centres[at(i, j, k)] = phantomHounsfield(
          coordinate(i, 0.5),
          -coordinate(k, 0.5),
          coordinate(j, 0.5),
        );
  const hounsfield = new Float32Array(centres);
  const s = PHANTOM_SUPERSAMPLING;
  const offsets = Array.from({ length: s }, (_, q) => (q + 0.5) / s);
  const neighbours = [
    [1, 0, 0],
    [-1, 0, 0],
    [0, 1, 0],
    [0, -1, 0],
    [0, 0, 1],
    [0, 0, -1],
  ] as const;
  for (let k = 0; k < n; k++)
    for (let j = 0; j < n; j++)
      for (let i = 0; i < n; i++) {
        const own = centres[at(i, j, k)]!;
        const uniform = neighbours.every(([di, dj, dk]) => {
          const [a, b, c] = [i + di, j + dj, k + dk];
          if (a < 0 || b < 0 || c < 0 || a >= n || b >= n || c >= n) return true;
          return centres[at(a, b, c)] === own;
        });
        if (uniform) continue;
        let sum = 0;
        for (const dz of offsets)
          for (const dy of offsets)
            for (const dx of offsets)
              sum += phantomHounsfield(coordinate(i, dx), -coordinate(k, dz), coordinate(j, dy));
        hounsfield[at(i, j, k)] = sum / s ** 3;
      }
  blurPointSpread(hounsfield, n);
  const stored = hounsfield.map((hu) => Math.max(hu - CT_RESCALE_INTERCEPT, 0));
  cached = { size, stored, hounsfield };
  return cached;
}

/**
 * The scanner's blur: a reconstructed CT voxel is not a box average but has a
 * point-spread function about a voxel wide. A separable [1, 2, 1]/4 filter along
 * each axis (clamped at the faces) stands in for it; it also spreads the few
 * discrete partial-volume levels of the sub-sampling into the continuous ramps a
 * real scan's histogram shows.
 */
function blurPointSpread(values: Float32Array, n: number): void {
  const line = new Float32Array(n);
  const strides = [1, n, n * n];
  for (const stride of strides) {
    for (let base = 0; base < n * n * n; base++) {
      // Start a line at every voxel whose coordinate along this axis is 0.
      if (Math.floor(base / stride) % n !== 0) continue;
      for (let q = 0; q < n; q++) line[q] = values[base + q * stride]!;
      for (let q = 0; q < n; q++) {
        const before = line[Math.max(q - 1, 0)]!;
        const after = line[Math.min(q + 1, n - 1)]!;
        values[base + q * stride] = 0.25 * before + 0.5 * line[q]! + 0.25 * after;
      }
    }
  }
}

export interface Histogram {
  /** Left edges of the bins (HU). */
  edges: number[];
  width: number;
  counts: number[];
}

/** Counts of voxel values in bins of `width` HU from `low` to `high` (values outside go to the end bins). */
export function histogram(
  values: ArrayLike<number>,
  low = -1024,
  high = 1200,
  width = 16,
): Histogram {
  const bins = Math.ceil((high - low) / width);
  const counts = new Array<number>(bins).fill(0);
  for (let i = 0; i < values.length; i++) {
    const bin = Math.min(Math.max(Math.floor((values[i]! - low) / width), 0), bins - 1);
    counts[bin]! += 1;
  }
  return { edges: counts.map((_, b) => low + b * width), width, counts };
}
