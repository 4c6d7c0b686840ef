// The four tabulated Mie phase functions of the mie-sample exercise (chapter 3), built
// by the library's float64 solver (src/reference/mie.ts, mieTabulatePhase) in the
// library's layout (shaders/mie.wesl, PhaseTable): per node k the complements 1 − μ_k
// and 1 + μ_k, the density p_k (sr⁻¹, linear in μ between nodes) and the CDF C_k
// measured from the forward direction (C_0 = 0 at μ = 1, C_K = 1 at μ = −1). Only the
// node count differs: 64 nodes instead of 513, so that the student's helpers stay a
// few kilobytes of WGSL. The tables are computed when this module loads (a few
// milliseconds), never typed in, and the GPU gets each entry rounded to f32, as the
// library's tables (phaseTableToF32); every CPU-side distribution below is that of the
// f32 table, so the grader tests the student against exactly what the GPU reads.
import {
  mieTabulatePhase,
  phaseTableAngles,
  phaseTableToF32,
  phaseTabulatedSampleMu,
  type PhaseTable,
  type RefractiveIndex,
} from '../../src/reference/mie.ts';

/** Intervals per table (K); each table has K + 1 nodes. Odd, see SMALL_PARTICLE. */
export const MIE_EXERCISE_INTERVALS = 63;
export const MIE_EXERCISE_NODES = MIE_EXERCISE_INTERVALS + 1;

/** Wavelength of every table, green light (µm). */
const WAVELENGTH_UM = 0.55;

export interface ExerciseTable {
  /** Index the student's function receives (`table: u32`). */
  index: number;
  /** In the statement's words. */
  label: string;
  radiusUm: number;
  m: RefractiveIndex;
  /** Node angles θ_k from 0 to π: 'forward' is the library's π(k/K)², 'uniform' πk/K. */
  grid: 'forward' | 'uniform';
}

/**
 * The tables, in index order. Water m = 1.333 (Hale & Querry 1973 at 550 nm); soot
 * m = 1.75 + 0.44i (chapter 3's soot preset). The near-Rayleigh particle has a grid
 * uniform in θ with an odd K, so that its middle interval is symmetric about θ = π/2:
 * Rayleigh's lobe ∝ 1 + μ² is even in μ, so the two densities of that interval agree to
 * 4e-6 (x = 0.011; the asymmetric corrections are O(x²) times μ ≈ ±0.025), a nearly flat interval
 * where the textbook quadratic formula divides a rounding error by (b − a) ≈ 0.
 */
export const EXERCISE_TABLES: readonly ExerciseTable[] = [
  {
    index: 0,
    label: 'a water droplet of radius 1.5 µm (x ≈ 17.1)',
    radiusUm: 1.5,
    m: { n: 1.333, kappa: 0 },
    grid: 'forward',
  },
  {
    index: 1,
    label: 'a particle of radius 1 nm near the Rayleigh limit (x ≈ 0.011, m = 1.5)',
    radiusUm: 0.001,
    m: { n: 1.5, kappa: 0 },
    grid: 'uniform',
  },
  {
    index: 2,
    label: 'an absorbing soot particle of radius 87.5 nm (x ≈ 1, m = 1.75 + 0.44i)',
    radiusUm: 0.0875,
    m: { n: 1.75, kappa: 0.44 },
    grid: 'forward',
  },
  {
    index: 3,
    label: 'a cloud droplet of radius 8.75 µm (x ≈ 100), strongly forward',
    radiusUm: 8.75,
    m: { n: 1.333, kappa: 0 },
    grid: 'forward',
  },
];

/** Index of the near-Rayleigh table and of its nearly flat middle interval. */
export const SMALL_PARTICLE = 1;
export const FLAT_INTERVAL = (MIE_EXERCISE_INTERVALS - 1) / 2;

function gridAngles(grid: ExerciseTable['grid']): Float64Array {
  if (grid === 'forward') return phaseTableAngles(MIE_EXERCISE_INTERVALS);
  return Float64Array.from(
    { length: MIE_EXERCISE_NODES },
    (_, k) => (Math.PI * k) / MIE_EXERCISE_INTERVALS,
  );
}

/** Size parameter x = 2πr/λ of a table. */
export function sizeParameter(table: ExerciseTable): number {
  return (2 * Math.PI * table.radiusUm) / WAVELENGTH_UM;
}

/** The f32-rounded tables, as the GPU reads them (index order). */
export const TABLES: readonly PhaseTable[] = EXERCISE_TABLES.map((t) =>
  phaseTableToF32(mieTabulatePhase(sizeParameter(t), t.m, gridAngles(t.grid))),
);

function tableAt(index: number): PhaseTable {
  const table = TABLES[index];
  if (!table) throw new Error(`mie-sample: no table ${index}`);
  return table;
}

/**
 * CDF of the sampled μ, F(μ) = P(M ≤ μ) = 1 − C(1 − μ), where C is the table's CDF from the
 * forward direction, the integral of the linear density: inside interval k, with
 * s = ((1 − μ) − (1 − μ_k))/((1 − μ_{k+1}) − (1 − μ_k)), a = p_k, b = p_{k+1},
 * C = C_k + (C_{k+1} − C_k)·(2as + (b − a)s²)/(a + b) (the quadratic the student inverts).
 */
export function tableMuCdf(index: number, mu: number): number {
  const table = tableAt(index);
  const t = Math.min(2, Math.max(0, 1 - mu));
  let k = 0;
  while (k < MIE_EXERCISE_INTERVALS - 1 && (table.oneMinusMu[k + 1] ?? 2) <= t) k++;
  const lower = table.oneMinusMu[k] ?? 0;
  const width = (table.oneMinusMu[k + 1] ?? 2) - lower;
  const s = width > 0 ? Math.min(1, Math.max(0, (t - lower) / width)) : 0;
  const a = table.pdf[k] ?? 0;
  const b = table.pdf[k + 1] ?? 0;
  const fraction = a + b > 0 ? (2 * a * s + (b - a) * s * s) / (a + b) : s;
  const ck = table.cdf[k] ?? 0;
  const c = ck + ((table.cdf[k + 1] ?? 1) - ck) * fraction;
  return Math.min(1, Math.max(0, 1 - c));
}

/** Inverse of tableMuCdf (float64, the library's twin sampler at ξ = 1 − p). */
export function tableMuInverseCdf(index: number, p: number): number {
  return phaseTabulatedSampleMu(tableAt(index), 1 - p).mu;
}

/** Mean cosine g of a table (exact for the piecewise-linear density). */
export function tableMeanCosine(index: number): number {
  const table = tableAt(index);
  let g = 0;
  for (let k = 0; k < MIE_EXERCISE_INTERVALS; k++) {
    // ∫ μ p dμ over the interval, with p linear in μ: the mass times the density-weighted
    // mean of μ, (μ_k (2a + b) + μ_{k+1} (a + 2b)) / (3(a + b)).
    const a = table.pdf[k] ?? 0;
    const b = table.pdf[k + 1] ?? 0;
    const muK = 1 - (table.oneMinusMu[k] ?? 0);
    const muK1 = 1 - (table.oneMinusMu[k + 1] ?? 0);
    const mass = (table.cdf[k + 1] ?? 0) - (table.cdf[k] ?? 0);
    if (a + b > 0) g += (mass * (muK * (2 * a + b) + muK1 * (a + 2 * b))) / (3 * (a + b));
  }
  return g;
}

/** An f32 as a WGSL literal that parses back to the same f32 (9 significant digits). */
function f32Literal(value: number): string {
  const text = Math.fround(value).toPrecision(9);
  return /[.e]/.test(text) ? text : `${text}.0`;
}

function wgslArray(name: string, pick: (table: PhaseTable) => Float64Array): string {
  const rows = TABLES.map(
    (table, i) => `  // table ${i}\n  ${Array.from(pick(table), f32Literal).join(', ')},`,
  );
  return `const ${name} = array<f32, ${TABLES.length * MIE_EXERCISE_NODES}>(\n${rows.join('\n')}\n);`;
}

/**
 * The WGSL the student's function is linked with: the four tables as module-scope
 * constants and one accessor per column. Indices are clamped (table to 0…3, k to 0…K),
 * so reading node K + 1 gives node K, as the statement says.
 */
export const TABLE_WGSL = `// Four Mie phase functions tabulated by the book's library (mieTabulatePhase), each
// with MIE_TABLE_INTERVALS + 1 nodes from the forward (k = 0, mu = 1) to the backward
// direction (k = MIE_TABLE_INTERVALS, mu = -1).
const MIE_TABLE_INTERVALS: u32 = ${MIE_EXERCISE_INTERVALS}u;
const MIE_TABLE_NODES: u32 = ${MIE_EXERCISE_NODES}u;
${wgslArray('MIE_TABLE_ONE_MINUS_MU', (t) => t.oneMinusMu)}
${wgslArray('MIE_TABLE_ONE_PLUS_MU', (t) => t.onePlusMu)}
${wgslArray('MIE_TABLE_PDF', (t) => t.pdf)}
${wgslArray('MIE_TABLE_CDF', (t) => t.cdf)}
fn mieTableIndex(table: u32, k: u32) -> u32 {
  return min(table, ${TABLES.length - 1}u) * MIE_TABLE_NODES + min(k, MIE_TABLE_INTERVALS);
}
/// 1 - mu_k of node k (increasing from 0 to 2).
fn tableOneMinusMu(table: u32, k: u32) -> f32 {
  return MIE_TABLE_ONE_MINUS_MU[mieTableIndex(table, k)];
}
/// 1 + mu_k of node k (decreasing from 2 to 0).
fn tableOnePlusMu(table: u32, k: u32) -> f32 {
  return MIE_TABLE_ONE_PLUS_MU[mieTableIndex(table, k)];
}
/// The density p_k at node k, in 1/sr.
fn tablePdf(table: u32, k: u32) -> f32 {
  return MIE_TABLE_PDF[mieTableIndex(table, k)];
}
/// The CDF C_k at node k, from the forward direction (C_0 = 0, C_K = 1).
fn tableCdf(table: u32, k: u32) -> f32 {
  return MIE_TABLE_CDF[mieTableIndex(table, k)];
}`;
