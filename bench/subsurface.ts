// Benchmark: the slab Monte Carlo of physics.md §7 against the published benchmarks
// (van de Hulst slab, Giovanelli half-space, the H-function half-space at normal and
// oblique incidence) on the GPU kernel and the float64 twin, with z-scores from the
// runs' own batch standard errors; and the diffusion models of physics.md §6 against a
// Monte Carlo reference on the dipole-profile widget's default scene (Skin 1, η = 1.3,
// isotropic scattering at σs′): each model's total R_d and profile error next to its
// cost. Timing is reported, never asserted. The published values and the H-function
// solver are the tests' (tests/support/subsurfaceTables.ts, hFunction.ts), so the bench
// and the tests compare against the same numbers.
import { linkKernel } from '../src/gpu/link.ts';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import {
  appendBatches,
  planBatches,
  runSlabCpu,
  runSlabGpu,
  summarize,
  type ChannelEstimate,
  type SlabBatches,
  type SlabRun,
} from '../src/subsurface/slabKernel.ts';
import { findMaterial } from '../src/subsurface/materials.ts';
import { evaluateProfilesGpu } from '../src/widgets/dipole-profile/profileKernel.ts';
import {
  compareTotal,
  evaluateProfilesCpu,
  inputsFrom,
  materialValues,
  slabRunFor,
  type ProfileCurves,
} from '../src/widgets/dipole-profile/model.ts';
import { halfSpaceReflectance } from '../tests/support/hFunction.ts';
import { SLAB_BENCHMARKS, type SlabBenchmark } from '../tests/support/subsurfaceTables.ts';
import { median, type BenchTable } from './table.ts';

const LIBRARY = loadShaderLibrary(new URL('../shaders', import.meta.url).pathname);
/** Batches per dispatch, as the command line: bounds one submission on SwiftShader. */
const BATCHES_PER_DISPATCH = 256;

interface Timed {
  estimate: ChannelEstimate;
  milliseconds: number;
}

async function gpuRun(
  device: GPUDevice,
  run: SlabRun,
): Promise<{ batches: SlabBatches; ms: number }> {
  let batches: SlabBatches | null = null;
  let ms = 0;
  for (let first = 0; first < run.batches; first += BATCHES_PER_DISPATCH) {
    const part = {
      ...run,
      batches: Math.min(BATCHES_PER_DISPATCH, run.batches - first),
      threadOffset: run.threadOffset + first * 64,
    };
    const result = await runSlabGpu(device, LIBRARY, part);
    batches = batches ? appendBatches(batches, result.batches) : result.batches;
    ms += result.gpuMs ?? result.wallMs;
  }
  return { batches: batches!, ms };
}

function benchmarkRun(b: SlabBenchmark, photons: number, incidenceCos = b.incidenceCos): SlabRun {
  return {
    channels: [{ sigmaA: b.sigmaA, sigmaS: b.sigmaS }],
    g: b.g,
    thickness: b.thickness,
    eta: b.eta,
    incidenceCos,
    maxCollisions: 65536,
    seed: 12345,
    threadOffset: 0,
    profile: { bins: 24, rMin: 1e-4, rMax: 10 },
    ...planBatches(photons),
  };
}

interface Case {
  benchmark: SlabBenchmark;
  incidenceCos: number;
  label: string;
  quantities: {
    name: string;
    published: number;
    pick: (e: ChannelEstimate) => { mean: number; se: number };
  }[];
}

function cases(): Case[] {
  const [a, b, c] = SLAB_BENCHMARKS as [SlabBenchmark, SlabBenchmark, SlabBenchmark];
  return [
    {
      benchmark: a,
      incidenceCos: 1,
      label: 'A slab τ = 2, g = 0.75, matched (van de Hulst)',
      quantities: [
        { name: 'R_d', published: a.reflectance, pick: (e) => e.diffuseReflectance },
        { name: 'T_t', published: a.transmittance!, pick: (e) => e.transmittance },
        { name: 'T_u = e^−2', published: Math.exp(-2), pick: (e) => e.unscattered },
      ],
    },
    {
      benchmark: b,
      incidenceCos: 1,
      label: 'B half-space, n = 1.5 (Giovanelli)',
      quantities: [
        { name: 'R_d + R_sp', published: b.reflectance, pick: (e) => e.totalReflectance },
      ],
    },
    {
      benchmark: c,
      incidenceCos: 1,
      label: 'C half-space, matched, μ0 = 1 (H-function)',
      quantities: [{ name: 'R_d', published: c.reflectance, pick: (e) => e.diffuseReflectance }],
    },
    {
      benchmark: c,
      incidenceCos: 0.5,
      label: 'C half-space, matched, μ0 = 0.5 (H-function)',
      quantities: [
        {
          name: 'R_d',
          published: halfSpaceReflectance(0.9, 0.5),
          pick: (e) => e.diffuseReflectance,
        },
      ],
    },
  ];
}

export async function benchSubsurface(
  device: GPUDevice,
  options: { gpuPhotons: number; cpuPhotons: number; scenePhotons: number; repeats: number },
): Promise<BenchTable[]> {
  const rows: BenchTable['rows'] = [];
  for (const kase of cases()) {
    for (const backend of ['GPU', 'CPU twin'] as const) {
      const photons = backend === 'GPU' ? options.gpuPhotons : options.cpuPhotons;
      const run = benchmarkRun(kase.benchmark, photons, kase.incidenceCos);
      let timed: Timed;
      if (backend === 'GPU') {
        const { batches, ms } = await gpuRun(device, run);
        timed = { estimate: summarize(run, batches)[0]!, milliseconds: ms };
      } else {
        const start = performance.now();
        const batches = runSlabCpu(run);
        timed = { estimate: summarize(run, batches)[0]!, milliseconds: performance.now() - start };
      }
      const e = timed.estimate;
      for (const q of kase.quantities) {
        const value = q.pick(e);
        rows.push({
          benchmark: kase.label,
          backend,
          quantity: q.name,
          published: q.published,
          MC: value.mean,
          SE: value.se,
          z: (value.mean - q.published) / value.se,
          photons: e.photons,
          'collisions/photon': e.collisionsPerPhoton,
          'time ms': timed.milliseconds,
          'ns/collision': (1e6 * timed.milliseconds) / (e.photons * e.collisionsPerPhoton),
        });
      }
    }
  }
  const benchmarks: BenchTable = {
    title: 'Slab Monte Carlo against the published benchmarks (physics.md §7)',
    notes: [
      `GPU: shaders/kernels/slab.wesl through Dawn, ${options.gpuPhotons} photons, seed 12345, time from timestamp queries (wall time where there are none); CPU: the float64 twin replaying the same streams, ${options.cpuPhotons} photons, wall time.`,
      'z = (MC − published)/SE with SE from the spread of the batch means; |z| < 5 passes the tests. Published values: MCML manual (van de Hulst 1980, Giovanelli 1955) and R = 1 − H(μ0)√(1 − ϖ).',
    ],
    rows,
  };

  // ---- The widget's default scene: the diffusion models against the Monte Carlo ----
  const skin = findMaterial('skin1')!;
  const inputs = inputsFrom({
    material: 'skin1',
    ...materialValues('skin1')!,
    g: 0,
    photons: 16,
    exposure: 0,
    view: 10,
    seed: 0,
  });
  const run = slabRunFor(inputs, options.scenePhotons, 0);
  const { batches, ms: mcMs } = await gpuRun(device, run);
  const mc = summarize(run, batches);
  const code = await linkKernel(LIBRARY, LIBRARY['kernels/dipole-profile.wesl']!);
  const gpuTimes: number[] = [];
  let curves: ProfileCurves | null = null;
  for (let k = 0; k < options.repeats; k++) {
    const result = await evaluateProfilesGpu(device, code, inputs);
    gpuTimes.push(result.milliseconds);
    curves = result.curves;
  }
  const cpuTimes: number[] = [];
  for (let k = 0; k < options.repeats; k++) {
    const start = performance.now();
    evaluateProfilesCpu(inputs);
    cpuTimes.push(performance.now() - start);
  }
  const modelCost = `${median(gpuTimes).toFixed(3)} ms GPU / ${median(cpuTimes).toFixed(2)} ms CPU for 3 models × 3 channels × 160 radii`;
  const sceneRows: BenchTable['rows'] = [];
  const channels = ['R', 'G', 'B'];
  for (let c = 0; c < 3; c++) {
    const e = mc[c]!;
    // Profile error: RMS of log10(model/MC) over bins from one reduced mean free path to 20 mm
    // where the MC bin has a relative standard error below 10%.
    const lPrime = 1 / (skin.sigmaSPrime[c]! + skin.sigmaA[c]!);
    const profileError = (model: (r: number) => number): number => {
      let sum = 0;
      let n = 0;
      e.profile.density.forEach((bin, k) => {
        const r = e.profile.centres[k]!;
        if (k === 0 || r < lPrime || r > 20 || !(bin.mean > 0) || bin.se / bin.mean > 0.1) return;
        sum += Math.log10(model(r) / bin.mean) ** 2;
        n += 1;
      });
      return n > 0 ? Math.sqrt(sum / n) : NaN;
    };
    const nearSource = e.profile.density[1]!.mean;
    const interpolate =
      (values: Float64Array) =>
      (r: number): number => {
        const radii = curves!.radii;
        let i = 0;
        while (i < radii.length - 2 && radii[i + 1]! < r) i++;
        const t = Math.log(r / radii[i]!) / Math.log(radii[i + 1]! / radii[i]!);
        return Math.exp(Math.log(values[i]!) * (1 - t) + Math.log(values[i + 1]!) * t);
      };
    const models = [
      { name: 'dipole', total: curves!.dipoleTotal[c]!, profile: interpolate(curves!.dipole[c]!) },
      {
        name: 'better dipole',
        total: curves!.betterTotal[c]!,
        profile: interpolate(curves!.better[c]!),
      },
      {
        name: 'Christensen–Burley',
        total: curves!.dipoleTotal[c]!,
        profile: interpolate(curves!.burley[c]!),
      },
    ];
    sceneRows.push({
      channel: channels[c]!,
      method: 'Monte Carlo (reference)',
      'total R_d': e.diffuseReflectance.mean,
      'SE or error': e.diffuseReflectance.se,
      'relative error': null,
      z: null,
      'profile RMS log10 error': null,
      'R(0.011 mm) / MC': 1,
      cost: `${e.photons} photons, ${e.collisionsPerPhoton.toFixed(1)} collisions/photon, ${mcMs.toFixed(0)} ms GPU (3 channels)`,
    });
    for (const model of models) {
      const comparison = compareTotal(model.total, e);
      sceneRows.push({
        channel: channels[c]!,
        method: model.name,
        'total R_d': model.total,
        'SE or error': comparison.difference,
        'relative error': comparison.relative,
        z: comparison.z,
        'profile RMS log10 error': profileError(model.profile),
        'R(0.011 mm) / MC': model.profile(e.profile.centres[1]!) / nearSource,
        cost: modelCost,
      });
    }
  }
  const scene: BenchTable = {
    title:
      'Diffusion models against the Monte Carlo: the dipole-profile widget’s default scene (Skin 1, η = 1.3)',
    notes: [
      'Half-space, normal incidence, isotropic scattering at σs′ (the similarity relation the diffusion models assume); MC on the GPU with the widget’s kernel settings (41 radial bins, cap 16384 flights).',
      'Christensen–Burley is matched to the dipole (A = dipole total, ℓ = 1/σt′): same total, its own shape. Profile error: RMS of log10(model/MC) over bins from one reduced mean free path to 20 mm with MC relative SE < 10%; R(0.011 mm)/MC: the model against the MC’s first ring next to the beam.',
    ],
    rows: sceneRows,
  };
  return [benchmarks, scene];
}
