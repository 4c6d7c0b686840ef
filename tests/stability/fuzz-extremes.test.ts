// A systematic fuzz of the scalar-argument library functions at f32 extremes, on the float64
// twin and on the GPU (Dawn, one kernel per function). Every argument is drawn from a fixed set
// of f32 extremes (±0, ±subnormals, the smallest normal, tiny and huge magnitudes, F32_MAX,
// u at 0 and 1 − 2^-24 and outside [0, 1)); the combinations are sampled with a fixed seed.
//
// Checked for every case: no NaN on either side, ever (a value outside a domain has a defined
// result); inside the documented domain (each argument's kind below) a finite result inside the
// documented range (transmittances and probabilities in [0, 1], densities ≥ 0, samples inside
// their support); and the GPU agrees with the twin in kind: both finite or both the same
// infinity, and the same sign unless both are within 1e-6 of each other (rounding around 0).
// WGSL lets a GPU flush subnormal inputs and results to 0, so the GPU may match the twin on the
// inputs with subnormals flushed instead, and a result below 2^-126 counts as 0.
//
// The kind of an argument: 'any' (every f32 is in the domain), 'nonneg' (a coefficient or
// length, ≥ 0), 'unit' (a random number u ∈ [0, 1)), 'signed1' ([−1, 1]: a cosine, g),
// 'open1' ((−1, 1)), 'eta' (a relative index in [1, 3]).
import { beforeAll, describe, expect, it } from 'vitest';
import {
  evaluateOnGpu,
  functionsOf,
  specFor,
  type Argument,
} from '../../src/gpu/functionEvaluator.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

type Kind = 'any' | 'nonneg' | 'unit' | 'signed1' | 'open1' | 'eta';

interface FuzzTarget {
  /** module.fn of a library function whose arguments are all f32 (or vecNf, flattened). */
  name: string;
  /** One kind per flattened f32 argument. */
  kinds: readonly Kind[];
  /** Inclusive range of every result component inside the domain; a function of the inputs. */
  range?: (args: readonly number[]) => readonly [number, number];
}

const F32_MAX = 3.4028234663852886e38;
const SUBNORMAL = 2 ** -149;
const NORMAL_MIN = 2 ** -126;
const ONE_BELOW = 1 - 2 ** -24;
const unitInterval = (): readonly [number, number] => [0, 1];
const nonNegative = (): readonly [number, number] => [0, F32_MAX];

/** The f32 extremes every argument is drawn from. */
const EXTREMES: readonly number[] = [
  0,
  -0,
  SUBNORMAL,
  -SUBNORMAL,
  2 ** -130,
  NORMAL_MIN,
  1e-38,
  1e-30,
  1e-20,
  1e-10,
  1e-7,
  1e-3,
  0.5,
  ONE_BELOW,
  1,
  1 + 2 ** -23,
  2,
  10,
  1e7,
  1e10,
  1e20,
  1e30,
  1e36,
  1e37,
  F32_MAX,
  -F32_MAX,
  -1e30,
  -1,
  -0.5,
  -1e-20,
  -ONE_BELOW,
  3,
].map(Math.fround);

const TARGETS: readonly FuzzTarget[] = [
  { name: 'transmittance.saturatingProduct', kinds: ['any', 'any'], range: nonNegative },
  { name: 'transmittance.saturatingSum', kinds: ['any', 'any'], range: nonNegative },
  { name: 'transmittance.saturatingQuotient', kinds: ['any', 'any'], range: nonNegative },
  { name: 'transmittance.segmentLength', kinds: ['any', 'any'], range: nonNegative },
  { name: 'transmittance.transmittanceFromOpticalThickness', kinds: ['any'], range: unitInterval },
  { name: 'transmittance.opticalThicknessHomogeneous', kinds: ['any', 'any'], range: nonNegative },
  { name: 'transmittance.transmittanceHomogeneous', kinds: ['any', 'any'], range: unitInterval },
  {
    name: 'transmittance.opticalThicknessSine',
    kinds: ['nonneg', 'nonneg', 'nonneg', 'any', 'any', 'any'],
    range: nonNegative,
  },
  {
    name: 'scatter.shadowTransmittanceExact',
    kinds: ['nonneg', 'nonneg', 'nonneg', 'nonneg'],
    range: unitInterval,
  },
  { name: 'scatter.oneMinusExpOfThickness', kinds: ['any'], range: unitInterval },
  {
    name: 'scatter.singleScatterHomogeneousSlab',
    kinds: ['nonneg', 'nonneg', 'nonneg', 'nonneg', 'nonneg', 'nonneg', 'nonneg'],
    range: nonNegative,
  },
  { name: 'scatter.equiangularPdf', kinds: ['nonneg', 'any', 'any', 'any'], range: nonNegative },
  { name: 'raymarch.oneMinusExpOverX', kinds: ['any'], range: unitInterval },
  { name: 'raymarch.oneMinusExpOverRate', kinds: ['any', 'any'], range: nonNegative },
  { name: 'raymarch.linearEmission', kinds: ['nonneg', 'nonneg', 'nonneg'], range: nonNegative },
  { name: 'tracking.sampleFreeFlight', kinds: ['nonneg', 'unit'], range: nonNegative },
  {
    name: 'tracking.transmittanceTrackLength',
    kinds: ['nonneg', 'nonneg', 'unit'],
    range: unitInterval,
  },
  { name: 'tracking.nullCollisionWeight', kinds: ['any', 'any'] },
  {
    name: 'integrator.sampleTruncatedExponential',
    kinds: ['any', 'any', 'any'],
    range: ([, length]) => [0, Math.max(length ?? 0, 0)],
  },
  { name: 'integrator.truncatedExponentialPdf', kinds: ['any', 'any', 'any'], range: nonNegative },
  {
    name: 'integrator.transmittanceBeer',
    kinds: ['any', 'any', 'any', 'any'],
    range: unitInterval,
  },
  {
    name: 'integrator.averageComponent',
    kinds: ['any', 'any', 'any'],
    range: () => [-F32_MAX, F32_MAX],
  },
  { name: 'dipole.fresnelDiffuseReflectanceFit', kinds: ['eta'] },
  { name: 'dipole.dipoleBoundary', kinds: ['eta'], range: nonNegative },
  { name: 'dipole.dipoleDistance', kinds: ['any', 'any'], range: nonNegative },
  { name: 'dipole.dipoleSourceTerm', kinds: ['any', 'any', 'any'], range: nonNegative },
  {
    name: 'dipole.exponentialDifferenceOverRate',
    kinds: ['any', 'any', 'any'],
    range: nonNegative,
  },
  { name: 'dipole.burleyShapeSearchlight', kinds: ['unit'], range: nonNegative },
  { name: 'dipole.burleyShapeDiffuse', kinds: ['unit'], range: nonNegative },
  { name: 'dipole.burleyShapeDmfp', kinds: ['unit'], range: nonNegative },
  { name: 'dipole.burleyProfile', kinds: ['unit', 'any', 'any'], range: nonNegative },
  { name: 'dipole.burleyRadialDensity', kinds: ['unit', 'any', 'any'], range: nonNegative },
  { name: 'dipole.burleyRadialCdf', kinds: ['any', 'any'], range: unitInterval },
  { name: 'fresnel.fresnelDielectric', kinds: ['signed1', 'eta'], range: unitInterval },
  { name: 'volume.opacityToOpticalDepth', kinds: ['unit'], range: nonNegative },
  { name: 'volume.opacityCorrected', kinds: ['any', 'any'], range: unitInterval },
  { name: 'phase.hgEval', kinds: ['open1', 'signed1'], range: nonNegative },
  { name: 'phase.rayleighEval', kinds: ['signed1'], range: nonNegative },
  { name: 'phase.rayleighSampleMu', kinds: ['any'], range: () => [-1, 1] },
  { name: 'phase.cbrtReal', kinds: ['any'] },
  { name: 'directions.sampleUniformSphere', kinds: ['any', 'any'], range: () => [-1, 1] },
  { name: 'slab.slabSpecularReflectance', kinds: ['eta', 'signed1'], range: unitInterval },
  { name: 'slab.slabDistanceToBoundary', kinds: ['nonneg', 'any', 'nonneg'], range: nonNegative },
  { name: 'slab.slabRadius', kinds: ['any', 'any'], range: nonNegative },
  { name: 'photons.sunConeSolidAngle', kinds: ['unit'], range: nonNegative },
  { name: 'photons.sunRadiance', kinds: ['nonneg', 'unit'], range: nonNegative },
  { name: 'photons.photonKernel', kinds: ['nonneg', 'any'], range: nonNegative },
  { name: 'bssrdf.bssrdfExitFactor', kinds: ['signed1', 'eta'], range: nonNegative },
  { name: 'lights.spotFalloff', kinds: ['signed1', 'signed1', 'signed1'], range: unitInterval },
  {
    name: 'medium.lerpWithinEndpoints',
    kinds: ['any', 'any', 'unit'],
    range: ([a, b]) => [Math.min(a ?? 0, b ?? 0), Math.max(a ?? 0, b ?? 0)],
  },
  { name: 'inverse.softplus', kinds: ['any'], range: nonNegative },
  { name: 'inverse.sigmoid', kinds: ['any'], range: unitInterval },
];

const CASES_PER_FUNCTION = 400;

function inKind(kind: Kind, x: number): boolean {
  switch (kind) {
    case 'any':
      return true;
    case 'nonneg':
      return x >= 0;
    case 'unit':
      return x >= 0 && x < 1;
    case 'signed1':
      return x >= -1 && x <= 1;
    case 'open1':
      return x > -1 && x < 1;
    case 'eta':
      return x >= 1 && x <= 3;
  }
}

/** A small deterministic generator (an LCG), so that a failure names a reproducible case. */
function generator(seed: number): () => number {
  let state = seed >>> 0;
  return () => {
    state = (Math.imul(state, 1664525) + 1013904223) >>> 0;
    return state / 2 ** 32;
  };
}

/** Every argument at 0, 1 − 2^-24 and F32_MAX together, then sampled combinations. */
function drawCases(target: FuzzTarget, seed: number): number[][] {
  const random = generator(seed);
  const calls: number[][] = [0, ONE_BELOW, F32_MAX, SUBNORMAL, -1].map((v) =>
    target.kinds.map(() => Math.fround(v)),
  );
  while (calls.length < CASES_PER_FUNCTION) {
    calls.push(target.kinds.map(() => EXTREMES[Math.floor(random() * EXTREMES.length)] as number));
  }
  return calls;
}

const flush = (x: number): number => (Math.abs(x) < NORMAL_MIN ? 0 : x);

function sameKind(gpu: number, twin: number): boolean {
  const f32Twin = Math.fround(twin);
  if (Number.isNaN(gpu) || Number.isNaN(twin)) return false;
  if (!Number.isFinite(gpu) || !Number.isFinite(f32Twin)) return gpu === f32Twin;
  const g = flush(gpu);
  const t = flush(f32Twin);
  if (Math.sign(g) === Math.sign(t)) return true;
  return Math.abs(gpu - twin) <= 1e-6;
}

interface Found {
  name: string;
  args: readonly number[];
  gpu: readonly number[];
  twin: readonly number[];
  problem: string;
}

describe('fuzz at f32 extremes: every scalar library function, twin and WGSL (Dawn)', () => {
  const found: Found[] = [];
  const checked = new Map<string, number>();

  beforeAll(async () => {
    const device = await nodeDevice();
    const twinModules = new Map<string, Record<string, unknown>>();
    for (const [index, target] of TARGETS.entries()) {
      const [module, fn] = target.name.split('.') as [string, string];
      const signature = functionsOf(SHADER_LIBRARY, module).find((s) => s.fn === fn);
      if (!signature) throw new Error(`${target.name} is not in the library`);
      const spec = specFor(signature);
      if (spec.args.length !== target.kinds.length)
        throw new Error(
          `${target.name}: ${spec.args.length} arguments, ${target.kinds.length} kinds`,
        );
      if (!twinModules.has(module))
        twinModules.set(module, (await import(`../../src/reference/${module}.ts`)) as never);
      const twin = twinModules.get(module)?.[fn];
      if (typeof twin !== 'function') throw new Error(`${target.name} has no twin`);
      const calls = drawCases(target, 0x5eed + index);
      const gpu = await evaluateOnGpu(device, SHADER_LIBRARY, spec, calls);
      const vectorParams = signature.params.map((p) =>
        p.type.text.startsWith('vec') ? p.type.components : 0,
      );
      const callTwin = (flat: readonly number[]): number[] => {
        const grouped: Argument[] = [];
        let k = 0;
        for (const components of vectorParams) {
          if (components > 0) {
            grouped.push(flat.slice(k, k + components).map(Math.fround));
            k += components;
          } else grouped.push(Math.fround(flat[k++] as number));
        }
        const value = (twin as (...a: Argument[]) => number | readonly number[])(...grouped);
        return typeof value === 'number' ? [value] : [...value];
      };
      calls.forEach((args, c) => {
        const g = gpu[c] ?? [];
        const raw = callTwin(args);
        const flushed = callTwin(args.map(flush));
        const report = (problem: string): void => {
          found.push({ name: target.name, args, gpu: g, twin: raw, problem });
        };
        const inDomain = args.every((x, k) => inKind(target.kinds[k] as Kind, x));
        g.forEach((value, k) => {
          const t = raw[k] ?? NaN;
          const tf = flushed[k] ?? NaN;
          if (Number.isNaN(value)) report('NaN on the GPU');
          if (Number.isNaN(t)) report('NaN in the twin');
          if (!inDomain) return;
          if (!Number.isFinite(value)) report('not finite on the GPU');
          if (!Number.isFinite(Math.fround(t))) report('not finite in the twin (as f32)');
          if (target.range) {
            const [lo, hi] = target.range(args);
            // A GPU may flush a subnormal endpoint or result to 0.
            const inside = (x: number): boolean =>
              (x >= lo && x <= hi) || (flush(x) === 0 && flush(lo) <= 0 && flush(hi) >= 0);
            if (!inside(value)) report(`GPU outside [${lo}, ${hi}]`);
            if (!(t >= lo && t <= hi)) report(`twin outside [${lo}, ${hi}]`);
          }
          if (!sameKind(value, t) && !sameKind(value, tf)) report('GPU and twin differ in kind');
        });
      });
      checked.set(target.name, calls.length);
    }
  }, 120_000);

  it('finds no NaN, no Inf, no value outside its documented range and no disagreement in kind', () => {
    expect(checked.size).toBe(TARGETS.length);
    // At most two examples of each function's each problem, so that one message names them all.
    const shown = new Map<string, number>();
    const lines = found
      .filter((f) => {
        const key = `${f.name}: ${f.problem}`;
        shown.set(key, (shown.get(key) ?? 0) + 1);
        return (shown.get(key) ?? 0) <= 2;
      })
      .map(
        (f) =>
          `${f.name}(${f.args.join(', ')}): ${f.problem}; GPU ${f.gpu.join(', ')}, twin ${f.twin.join(', ')}`,
      );
    expect(lines, `${found.length} findings`).toEqual([]);
  });
});
