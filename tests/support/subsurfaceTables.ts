// The published tables of physics.md §6 and §7 as data, for the dipole, Fresnel and
// slab tests: the F_dr table (§6.1), the derived dipole quantities of the Jensen et al.
// 2001 materials (§6.1, computed there from the measured table with the Jensen fit),
// the Skimmilk R profile, the better-dipole and Christensen–Burley values (§6.2, §6.3)
// and the Monte Carlo benchmarks (§7).
import { JENSEN_2001_MATERIALS } from '../../src/subsurface/materials.ts';

/** physics.md §6.1: η, the Jensen fit, the exact internal and exact external F_dr [✔]. */
export const FDR_TABLE: readonly (readonly [number, number, number, number])[] = [
  [1.0, 0.0016, 0, 0],
  [1.1, 0.193332, 0.194345, 0.025157],
  [1.2, 0.335987, 0.336306, 0.04428],
  [1.3, 0.444763, 0.444457, 0.061132],
  [1.33, 0.472357, 0.471949, 0.065931],
  [1.4, 0.529489, 0.528985, 0.076812],
  [1.5, 0.596733, 0.596346, 0.091778],
  [2.0, 0.7902, 0.790149, 0.160597],
];

/** One row of the derived table of physics.md §6.1 (lengths in mm). */
export interface DerivedDipoleRow {
  material: string;
  channel: 0 | 1 | 2;
  sigmaTPrime: number;
  albedoPrime: number;
  sigmaTr: number;
  zr: number;
  zv: number;
  total: number;
  /** R_d(r = 0) in mm⁻². */
  atZero: number;
}

// material, then per channel R, G, B: σt', α', σtr, z_r, z_v, R_d total, R_d(0).
const DERIVED: Record<string, readonly (readonly number[])[]> = {
  apple: [
    [2.293, 0.998692, 0.143656, 0.43611, 1.949158, 0.846416, 0.437309],
    [2.3934, 0.998579, 0.156246, 0.417816, 1.867393, 0.840675, 0.47626],
    [2.016, 0.977183, 0.527454, 0.496032, 2.216974, 0.527855, 0.3176],
  ],
  chicken1: [
    [0.165, 0.909091, 0.086168, 6.060606, 27.087389, 0.313679, 0.00181031],
    [0.287, 0.731707, 0.257482, 3.484321, 15.572889, 0.155805, 0.00373175],
    [0.57, 0.666667, 0.57, 1.754386, 7.841086, 0.126444, 0.0127359],
  ],
  chicken2: [
    [0.208, 0.913462, 0.105981, 4.807692, 21.487592, 0.321239, 0.00290501],
    [0.338, 0.739645, 0.298717, 2.95858, 13.223134, 0.159938, 0.00526636],
    [0.52, 0.615385, 0.55857, 1.923077, 8.595037, 0.107632, 0.00941331],
  ],
  cream: [
    [7.3802, 0.999973, 0.066544, 0.135498, 0.605596, 0.975737, 4.55089],
    [5.4728, 0.999488, 0.21441, 0.182722, 0.81666, 0.900016, 2.4981],
    [3.1663, 0.994852, 0.393487, 0.315826, 1.411559, 0.724732, 0.823513],
  ],
  ketchup: [
    [0.241, 0.746888, 0.210007, 4.149378, 18.545308, 0.163836, 0.00271994],
    [1.04, 0.067308, 1.739655, 0.961538, 4.297518, 0.006337, 0.00290819],
    [1.48, 0.02027, 2.537321, 0.675676, 3.019878, 0.00183, 0.00172771],
  ],
  marble: [
    [2.1921, 0.999042, 0.117517, 0.456184, 2.864527, 0.830191, 0.390746],
    [2.6241, 0.998438, 0.179656, 0.381083, 2.392946, 0.79096, 0.558789],
    [3.0071, 0.997639, 0.253083, 0.332546, 2.088168, 0.75261, 0.731893],
  ],
  potato: [
    [0.6824, 0.996483, 0.070095, 1.465416, 6.549559, 0.764422, 0.0384488],
    [0.709, 0.987306, 0.138358, 1.410437, 6.303835, 0.6125, 0.0403807],
    [0.67, 0.820896, 0.491121, 1.492537, 6.670775, 0.212707, 0.0246537],
  ],
  skimmilk: [
    [0.7014, 0.998004, 0.054276, 1.42572, 6.37214, 0.814946, 0.0408225],
    [1.2225, 0.997955, 0.095754, 0.817996, 3.655967, 0.812984, 0.123992],
    [1.9142, 0.992582, 0.285561, 0.522411, 2.334876, 0.682295, 0.298902],
  ],
  skin1: [
    [0.772, 0.958549, 0.272235, 1.295337, 5.789403, 0.435956, 0.0444311],
    [1.05, 0.838095, 0.731779, 0.952381, 4.25659, 0.227331, 0.0628239],
    [1.49, 0.677852, 1.464787, 0.671141, 2.99961, 0.130999, 0.0892566],
  ],
  skin2: [
    [1.103, 0.988214, 0.207405, 0.906618, 4.052057, 0.622631, 0.0979838],
    [1.66, 0.957831, 0.590424, 0.60241, 2.692421, 0.433271, 0.205073],
    [1.935, 0.925065, 0.917456, 0.516796, 2.309777, 0.343458, 0.258069],
  ],
  spectralon: [
    [11.6, 1, 0, 0.086207, 0.385295, 1, 11.244],
    [20.4, 1, 0, 0.04902, 0.219089, 1, 34.7748],
    [14.9, 1, 0, 0.067114, 0.299961, 1, 18.5514],
  ],
  wholemilk: [
    [2.5511, 0.999569, 0.091753, 0.391988, 1.751958, 0.907698, 0.542963],
    [3.2124, 0.999253, 0.152083, 0.311294, 1.391302, 0.880868, 0.859976],
    [3.784, 0.9963, 0.398658, 0.264271, 1.181136, 0.759413, 1.18155],
  ],
};

export const DERIVED_DIPOLE_TABLE: readonly DerivedDipoleRow[] = Object.entries(DERIVED).flatMap(
  ([material, rows]) =>
    rows.map((row, channel) => {
      const [sigmaTPrime, albedoPrime, sigmaTr, zr, zv, total, atZero] = row as [
        number,
        number,
        number,
        number,
        number,
        number,
        number,
      ];
      return {
        material,
        channel: channel as 0 | 1 | 2,
        sigmaTPrime,
        albedoPrime,
        sigmaTr,
        zr,
        zv,
        total,
        atZero,
      };
    }),
);

/** σs', σa (1/mm) and η of a derived-table row, from the materials module. */
export function rowInputs(row: DerivedDipoleRow): [number, number, number] {
  const m = JENSEN_2001_MATERIALS.find((x) => x.name === row.material);
  if (!m) throw new Error(`no material ${row.material}`);
  return [m.sigmaSPrime[row.channel], m.sigmaA[row.channel], m.eta];
}

export const CHANNEL_NAMES = ['R', 'G', 'B'] as const;

/** physics.md §6.1: Skimmilk R, R_d(r) in mm⁻² at r in mm [✔]. */
export const SKIMMILK_R_PROFILE: readonly (readonly [number, number])[] = [
  [0, 4.08225497e-2],
  [0.5, 3.45720394e-2],
  [1, 2.31436913e-2],
  [2, 9.19040035e-3],
  [5, 1.66232423e-3],
  [10, 3.60425711e-4],
];

/** physics.md §6.2: the better dipole for Skimmilk R, profile at r = 0, 1, 5 mm and total. */
export const SKIMMILK_R_BETTER: {
  profile: readonly (readonly [number, number])[];
  total: number;
  classicTotal: number;
} = {
  profile: [
    [0, 2.652395e-2],
    [1, 1.746569e-2],
    [5, 1.987003e-3],
  ],
  total: 0.82034402,
  classicTotal: 0.81494596,
};

/** physics.md §6.2: exact internal Fresnel moments and the better dipole's A at η = 1.3. */
export const MOMENTS_AT_1_3 = { c1: 0.222228, c2: 0.100089, boundaryA: 2.340532 };

/** physics.md §6.3: A, searchlight s, diffuse s, dmfp s [✔]. */
export const BURLEY_SHAPE_TABLE: readonly (readonly [number, number, number, number])[] = [
  [0, 5.434, 4.14, 4.685921],
  [0.2, 3.162, 2.96, 3.528561],
  [0.5, 1.539, 1.715, 3.583521],
  [0.8, 1.05, 1.1, 8.379681],
  [0.9, 0.957, 1.035, 14.056001],
  [1.0, 0.906, 1.04, 23.651121],
];

/** physics.md §6.3 and §9 row 26. */
export const BURLEY_CDF_16D = 0.9963790093708328;
export const BURLEY_MEDIAN_R_OVER_D = 1.55218326;

/** One published Monte Carlo benchmark of physics.md §7 (cm⁻¹ and cm). */
export interface SlabBenchmark {
  name: string;
  sigmaA: number;
  sigmaS: number;
  g: number;
  thickness: number;
  eta: number;
  incidenceCos: number;
  /** Published values; `reflectance` is R_d or R_d + R_sp as `includesSpecular` says. */
  reflectance: number;
  includesSpecular: boolean;
  transmittance?: number;
  /** Decimals the published values are printed with (0.2600 has 4). */
  decimals: number;
  source: string;
}

export const SLAB_BENCHMARKS: readonly SlabBenchmark[] = [
  {
    name: 'A: slab, matched boundary (van de Hulst 1980)',
    sigmaA: 10,
    sigmaS: 90,
    g: 0.75,
    thickness: 0.02,
    eta: 1,
    incidenceCos: 1,
    reflectance: 0.09739,
    includesSpecular: false,
    transmittance: 0.66096,
    decimals: 5,
    source: 'van de Hulst 1980 tables via the MCML manual (physics.md §7 A)',
  },
  {
    name: 'B: half-space, n = 1.5 (Giovanelli 1955)',
    sigmaA: 10,
    sigmaS: 90,
    g: 0,
    thickness: Infinity,
    eta: 1.5,
    incidenceCos: 1,
    reflectance: 0.26,
    includesSpecular: true,
    decimals: 4,
    source: 'Giovanelli 1955 via the MCML manual (physics.md §7 B), R_sp = 0.04 included',
  },
  {
    name: 'C: half-space, matched, isotropic (Chandrasekhar H)',
    sigmaA: 10,
    sigmaS: 90,
    g: 0,
    thickness: Infinity,
    eta: 1,
    incidenceCos: 1,
    reflectance: 0.41494748,
    includesSpecular: false,
    decimals: 8,
    source: 'R = 1 − H(1)√(1 − ϖ), ϖ = 0.9 (physics.md §7 C)',
  },
];
