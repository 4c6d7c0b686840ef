// Distribution checks shared by the phase-registry tests (tests/reference/phase-registry
// and tests/shaders/phase-dispatch): for a rotationally symmetric phase function, the
// probability of each μ bin by quadrature of its own evaluation, histograms of sampled
// directions in μ = −wo·wi and in the azimuth around the direction of travel −wo, and
// Pearson's chi-square statistic. Tabulated entries pass the packed phase-table buffer
// (src/phase/registry.ts packPhases) that their twins read.
import {
  phaseTableAt,
  type PhaseFunctionDefinition,
  type PhaseRecord,
} from '../../src/phase/registry.ts';
import {
  directionAroundAxis,
  orthonormalBasis,
  type Vec3,
} from '../../src/reference/directions.ts';

export const MU_BINS = 20;
export const PHI_BINS = 8;

export const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

/** 16-point Gauss–Legendre nodes and weights on [−1, 1] (Newton on P_16). */
const GAUSS = (() => {
  const n = 16;
  const nodes: number[] = [];
  const weights: number[] = [];
  for (let i = 1; i <= n; i++) {
    let x = Math.cos((Math.PI * (i - 0.25)) / (n + 0.5));
    let derivative = 1;
    for (let iteration = 0; iteration < 100; iteration++) {
      let p0 = 1;
      let p1 = x;
      for (let k = 2; k <= n; k++) [p0, p1] = [p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k];
      derivative = (n * (x * p1 - p0)) / (x * x - 1);
      const step = p1 / derivative;
      x -= step;
      if (Math.abs(step) < 1e-16) break;
    }
    nodes.push(x);
    weights.push(2 / ((1 - x * x) * derivative * derivative));
  }
  return { nodes, weights };
})();

/**
 * ∫ 2π p(μ) dμ over [a, b] for p of a rotationally symmetric phase function: 64 panels
 * of 16-point Gauss–Legendre, accurate to ~1e-9 even for the HG g = 0.9 peak. A
 * tabulated p (piecewise linear in μ, hundreds of kinks under the forward peak) passes
 * its nodes as `breakpoints`: the panels then also split there, so that each is exact.
 */
export function probability(
  p: (mu: number) => number,
  a: number,
  b: number,
  breakpoints: readonly number[] = [],
): number {
  const panels = 64;
  const ends = [
    ...Array.from({ length: panels + 1 }, (_, k) => a + ((b - a) * k) / panels),
    ...breakpoints.filter((mu) => mu > a && mu < b),
  ].sort((x, y) => x - y);
  let sum = 0;
  for (let k = 0; k + 1 < ends.length; k++) {
    const lo = ends[k]!;
    const half = (ends[k + 1]! - lo) / 2;
    GAUSS.nodes.forEach((x, i) => (sum += GAUSS.weights[i]! * half * p(lo + half * (1 + x))));
  }
  return 2 * Math.PI * sum;
}

/**
 * The cosines μ_k at which the record's phase function has kinks: the nodes of its table
 * for a tabulated entry (src/phase/registry.ts phaseTableAt), none for analytic ones.
 */
export function phaseBreakpoints(
  entry: PhaseFunctionDefinition,
  record: PhaseRecord,
  tables: Float32Array,
): number[] {
  if (!entry.tabulate) return [];
  return Array.from(phaseTableAt(tables, record.table).oneMinusMu, (t) => 1 - t);
}

/** The entry's twin evaluation as a function of μ, for a fixed wo (azimuth uPhi). */
export function phaseOfMu(
  entry: PhaseFunctionDefinition,
  record: PhaseRecord,
  wo: Vec3,
  tables: Float32Array = new Float32Array(0),
  uPhi = 0.37,
): (mu: number) => number {
  const travel: Vec3 = [-wo[0], -wo[1], -wo[2]];
  return (mu) =>
    entry.twin.eval(
      record,
      wo,
      directionAroundAxis(travel, mu, Math.sqrt(1 - mu * mu), uPhi),
      tables,
    );
}

/** Expected counts of `samples` draws in MU_BINS equal bins of μ ∈ [−1, 1]. */
export function expectedMuCounts(
  p: (mu: number) => number,
  samples: number,
  breakpoints: readonly number[] = [],
): number[] {
  return Array.from(
    { length: MU_BINS },
    (_, k) =>
      samples * probability(p, -1 + (2 * k) / MU_BINS, -1 + (2 * (k + 1)) / MU_BINS, breakpoints),
  );
}

export interface DirectionHistogram {
  mu: number[];
  phi: number[];
  /** Largest | |wi| − 1 |. */
  lengthError: number;
}

/** Histograms of sampled directions wi in μ = −wo·wi and in the azimuth around −wo. */
export class DirectionHistogramBuilder {
  readonly histogram: DirectionHistogram = {
    mu: new Array<number>(MU_BINS).fill(0),
    phi: new Array<number>(PHI_BINS).fill(0),
    lengthError: 0,
  };
  private readonly tangent: Vec3;
  private readonly bitangent: Vec3;

  constructor(private readonly wo: Vec3) {
    ({ tangent: this.tangent, bitangent: this.bitangent } = orthonormalBasis([
      -wo[0],
      -wo[1],
      -wo[2],
    ]));
  }

  add(wi: Vec3): void {
    const h = this.histogram;
    h.lengthError = Math.max(h.lengthError, Math.abs(Math.hypot(...wi) - 1));
    const mu = -dot(this.wo, wi);
    h.mu[Math.max(0, Math.min(MU_BINS - 1, Math.floor(((mu + 1) / 2) * MU_BINS)))]! += 1;
    const phi = Math.atan2(dot(wi, this.bitangent), dot(wi, this.tangent));
    h.phi[
      Math.max(0, Math.min(PHI_BINS - 1, Math.floor(((phi + Math.PI) / (2 * Math.PI)) * PHI_BINS)))
    ]! += 1;
  }
}

/** Pearson's statistic Σ (observed − expected)²/expected. */
export function chiSquare(counts: readonly number[], expected: readonly number[]): number {
  return counts.reduce((s, c, k) => s + (c - expected[k]!) ** 2 / expected[k]!, 0);
}
