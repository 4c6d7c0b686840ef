// `scatterbook slab`: the slab Monte Carlo of physics.md §7 from the command line. Runs
// the kernel shaders/kernels/slab.wesl on the GPU through Dawn (SwiftShader where there
// is no GPU), or with --backend cpu the float64 twin replaying the same walks, and
// prints the diffuse reflectance R_d, the total transmittance T_t, their standard errors
// (from the spread of the batch means, src/subsurface/slabKernel.ts) and the radial
// reflectance profile R(r). Units: coefficients in 1/L and lengths in L for any one
// length unit L (the published benchmarks use cm).
import { parseArgs } from 'node:util';
import { fileURLToPath } from 'node:url';
import { loadShaderLibrary } from '../gpu/shaderSourcesNode.ts';
import {
  appendBatches,
  planBatches,
  runSlabCpu,
  runSlabGpu,
  summarize,
  type ChannelEstimate,
  type SlabBatches,
  type SlabRun,
} from '../subsurface/slabKernel.ts';
import { SLAB_MAX_BINS, SLAB_MAX_COLLISIONS } from '../reference/slab.ts';

const SHADERS_DIRECTORY = fileURLToPath(new URL('../../shaders', import.meta.url));

export const SLAB_USAGE = `Usage:
  scatterbook slab --sigma-a A --sigma-s S --thickness D|inf [--g G] [--eta N]
                   [--incidence-cos MU] [--photons N] [--seed K] [--bins B]
                   [--r-min R] [--r-max R] [--max-collisions C] [--backend gpu|cpu] [--json]

Monte Carlo photon transport through a homogeneous slab (or a half-space, --thickness inf)
lit by a collimated, infinitely narrow beam (physics.md §7): HG scattering, survival
weighting with Russian roulette, exact Fresnel boundaries with the same ambient index on
both sides. Prints R_d (diffuse reflectance, without the specular R_sp), R_d + R_sp, T_t
(total transmittance, unscattered part included), their standard errors from the spread
of the batch means, the cost, and the radial reflectance profile R(r) per unit area.

--sigma-a, --sigma-s  absorption and scattering coefficients (1/L, ≥ 0)
--thickness           slab thickness (L, > 0), or inf for a half-space
--g                   HG asymmetry in (−1, 1) (default 0, isotropic)
--eta                 relative index n_medium/n_outside (default 1, matched)
--incidence-cos       cosine of the beam with the surface normal, in (0, 1] (default 1)
--photons             number of photon packets (default 65536, at most ${2 ** 26})
--seed                seed of the PCG streams (default 1)
--bins                radial bins of the profile, 2 … ${SLAB_MAX_BINS} (default 24)
--r-min, --r-max      profile range (L): bin 0 is [0, r-min), the others log-spaced up to
                      r-max (defaults 0.01 and 100 transport mean free paths 1/(σa + σs(1 − g)))
--max-collisions      cap on free flights per packet, 1 … ${SLAB_MAX_COLLISIONS} (default ${SLAB_MAX_COLLISIONS});
                      packets that reach it are counted and reported
--backend gpu         the WGSL kernel through Dawn (default); cpu: the float64 twin
--json                machine-readable output

Example (benchmark A of physics.md §7, van de Hulst: R_d = 0.09739, T_t = 0.66096):
  scatterbook slab --sigma-a 10 --sigma-s 90 --g 0.75 --thickness 0.02 --photons 1000000`;

/** Wrong command line: exit status 2. */
export class SlabUsageError extends Error {}

/** Batches per dispatch: bounds one GPU submission (SwiftShader runs it on the CPU). */
const BATCHES_PER_DISPATCH = 256;
const MAX_PHOTONS = 2 ** 26;

interface SlabOptions {
  run: SlabRun;
  backend: 'gpu' | 'cpu';
  json: boolean;
}

function number(
  values: Record<string, string | boolean | undefined>,
  name: string,
  fallback?: number,
): number {
  const raw = values[name];
  if (raw === undefined || raw === true) {
    if (fallback === undefined) throw new SlabUsageError(`missing --${name}`);
    return fallback;
  }
  const text = String(raw).trim();
  const value = /^[+]?inf(inity)?$/i.test(text) ? Infinity : Number(text);
  if (text === '' || Number.isNaN(value))
    throw new SlabUsageError(`--${name} must be a number, got ${JSON.stringify(raw)}`);
  return value;
}

function check(condition: boolean, message: string): void {
  if (!condition) throw new SlabUsageError(message);
}

/** Parses and checks the options; every mistake is a SlabUsageError with a clear message. */
export function parseSlabOptions(argv: readonly string[]): SlabOptions {
  let parsed;
  try {
    parsed = parseArgs({
      args: [...argv],
      allowPositionals: true,
      options: {
        'sigma-a': { type: 'string' },
        'sigma-s': { type: 'string' },
        g: { type: 'string' },
        thickness: { type: 'string' },
        eta: { type: 'string' },
        'incidence-cos': { type: 'string' },
        photons: { type: 'string' },
        seed: { type: 'string' },
        bins: { type: 'string' },
        'r-min': { type: 'string' },
        'r-max': { type: 'string' },
        'max-collisions': { type: 'string' },
        backend: { type: 'string' },
        json: { type: 'boolean' },
      },
    });
  } catch (error) {
    throw new SlabUsageError((error as Error).message);
  }
  const { values, positionals } = parsed;
  check(positionals.length === 0, `slab takes only options, got ${positionals.join(' ')}`);
  const sigmaA = number(values, 'sigma-a');
  const sigmaS = number(values, 'sigma-s');
  const thickness = number(values, 'thickness');
  const g = number(values, 'g', 0);
  const eta = number(values, 'eta', 1);
  const incidenceCos = number(values, 'incidence-cos', 1);
  const photons = number(values, 'photons', 65536);
  const seed = number(values, 'seed', 1);
  const bins = number(values, 'bins', 24);
  const maxCollisions = number(values, 'max-collisions', SLAB_MAX_COLLISIONS);
  check(
    Number.isFinite(sigmaA) && sigmaA >= 0,
    `--sigma-a must be a finite number ≥ 0, got ${sigmaA}`,
  );
  check(
    Number.isFinite(sigmaS) && sigmaS >= 0,
    `--sigma-s must be a finite number ≥ 0, got ${sigmaS}`,
  );
  check(sigmaA + sigmaS > 0, '--sigma-a and --sigma-s are both 0: there is no medium to simulate');
  check(thickness > 0, `--thickness must be > 0 (or inf for a half-space), got ${thickness}`);
  check(Number.isFinite(g) && g > -1 && g < 1, `--g must lie in (−1, 1), got ${g}`);
  check(Number.isFinite(eta) && eta > 0, `--eta must be a finite number > 0, got ${eta}`);
  check(
    incidenceCos > 0 && incidenceCos <= 1,
    `--incidence-cos must lie in (0, 1], got ${incidenceCos}`,
  );
  check(
    Number.isInteger(photons) && photons >= 1 && photons <= MAX_PHOTONS,
    `--photons must be an integer in [1, ${MAX_PHOTONS}], got ${photons}`,
  );
  check(
    Number.isInteger(seed) && seed >= 0 && seed <= 0xffffffff,
    `--seed must be an integer in [0, 4294967295], got ${seed}`,
  );
  check(
    Number.isInteger(bins) && bins >= 2 && bins <= SLAB_MAX_BINS,
    `--bins must be an integer in [2, ${SLAB_MAX_BINS}], got ${bins}`,
  );
  check(
    Number.isInteger(maxCollisions) && maxCollisions >= 1 && maxCollisions <= SLAB_MAX_COLLISIONS,
    `--max-collisions must be an integer in [1, ${SLAB_MAX_COLLISIONS}], got ${maxCollisions}`,
  );
  const transportFreePath = 1 / (sigmaA + sigmaS * (1 - g));
  const rMin = number(values, 'r-min', 0.01 * transportFreePath);
  const rMax = number(values, 'r-max', 100 * transportFreePath);
  check(Number.isFinite(rMin) && rMin > 0, `--r-min must be a finite number > 0, got ${rMin}`);
  check(
    Number.isFinite(rMax) && rMax > rMin,
    `--r-max must be finite and > --r-min (${rMin}), got ${rMax}`,
  );
  const backend = values.backend ?? 'gpu';
  check(
    backend === 'gpu' || backend === 'cpu',
    `--backend must be gpu or cpu, got ${JSON.stringify(backend)}`,
  );
  return {
    run: {
      channels: [{ sigmaA, sigmaS }],
      g,
      thickness,
      eta,
      incidenceCos,
      maxCollisions,
      seed,
      threadOffset: 0,
      profile: { bins, rMin, rMax },
      ...planBatches(photons),
    },
    backend: backend as 'gpu' | 'cpu',
    json: values.json ?? false,
  };
}

interface SlabOutcome {
  estimate: ChannelEstimate;
  milliseconds: number;
  timing: string;
}

async function simulate(options: SlabOptions): Promise<SlabOutcome> {
  const { run } = options;
  if (options.backend === 'cpu') {
    const start = performance.now();
    const estimate = summarize(run, runSlabCpu(run))[0]!;
    return { estimate, milliseconds: performance.now() - start, timing: 'CPU wall time' };
  }
  const { nodeDevice, releaseNodeDevice } = await import('../gpu/nodeDevice.ts');
  try {
    const device = await nodeDevice();
    const library = loadShaderLibrary(SHADERS_DIRECTORY);
    let batches: SlabBatches | null = null;
    let gpuMs = 0;
    let wallMs = 0;
    let timestamps = true;
    for (let first = 0; first < run.batches; first += BATCHES_PER_DISPATCH) {
      const part: SlabRun = {
        ...run,
        batches: Math.min(BATCHES_PER_DISPATCH, run.batches - first),
        threadOffset: first * 64,
      };
      const result = await runSlabGpu(device, library, part);
      batches = batches ? appendBatches(batches, result.batches) : result.batches;
      if (result.gpuMs === null) timestamps = false;
      gpuMs += result.gpuMs ?? 0;
      wallMs += result.wallMs;
    }
    return {
      estimate: summarize(run, batches!)[0]!,
      milliseconds: timestamps ? gpuMs : wallMs,
      timing: timestamps ? 'GPU timestamp queries' : 'wall time (no timestamp queries)',
    };
  } finally {
    await releaseNodeDevice();
  }
}

function jsonReport(options: SlabOptions, outcome: SlabOutcome): unknown {
  const { run } = options;
  const e = outcome.estimate;
  const channel = run.channels[0]!;
  return {
    backend: options.backend,
    setup: {
      sigmaA: channel.sigmaA,
      sigmaS: channel.sigmaS,
      g: run.g,
      thickness: Number.isFinite(run.thickness) ? run.thickness : 'inf',
      eta: run.eta,
      incidenceCos: run.incidenceCos,
      seed: run.seed,
      maxCollisions: run.maxCollisions,
    },
    photons: e.photons,
    batches: e.batches,
    Rsp: e.specular,
    Rd: e.diffuseReflectance.mean,
    RdSE: e.diffuseReflectance.se,
    RdPlusRsp: e.totalReflectance.mean,
    Tt: e.transmittance.mean,
    TtSE: e.transmittance.se,
    Tu: e.unscattered.mean,
    TuSE: e.unscattered.se,
    collisionsPerPhoton: e.collisionsPerPhoton,
    capped: e.capped,
    cappedWeight: e.cappedWeight,
    milliseconds: outcome.milliseconds,
    timing: outcome.timing,
    profile: e.profile.density.map((bin, k) => ({
      rInner: e.profile.edges[k],
      rOuter: e.profile.edges[k + 1],
      r: e.profile.centres[k],
      R: bin.mean,
      SE: bin.se,
    })),
  };
}

const fmt = (value: number, digits = 6): string =>
  value === 0
    ? '0'
    : Math.abs(value) >= 1e-3 && Math.abs(value) < 1e5
      ? value.toPrecision(digits)
      : value.toExponential(digits - 1);

function textReport(options: SlabOptions, outcome: SlabOutcome): string {
  const { run } = options;
  const e = outcome.estimate;
  const channel = run.channels[0]!;
  const where =
    options.backend === 'gpu' ? 'WGSL kernel on the GPU through Dawn' : 'float64 twin on the CPU';
  const lines = [
    `slab Monte Carlo (${where})`,
    `  σa = ${channel.sigmaA}, σs = ${channel.sigmaS}, g = ${run.g}, thickness = ${Number.isFinite(run.thickness) ? run.thickness : 'inf (half-space)'}, η = ${run.eta}, μ0 = ${run.incidenceCos}`,
    `  ${e.photons} photons in ${e.batches} batches, seed ${run.seed}`,
    '',
    `  R_sp (specular)        ${fmt(e.specular)}`,
    `  R_d  (diffuse)         ${fmt(e.diffuseReflectance.mean)} ± ${fmt(e.diffuseReflectance.se, 2)}`,
    `  R_d + R_sp             ${fmt(e.totalReflectance.mean)} ± ${fmt(e.totalReflectance.se, 2)}`,
    `  T_t  (total transm.)   ${fmt(e.transmittance.mean)} ± ${fmt(e.transmittance.se, 2)}`,
    `  T_u  (unscattered)     ${fmt(e.unscattered.mean)} ± ${fmt(e.unscattered.se, 2)}`,
    '',
    `  collisions per photon  ${fmt(e.collisionsPerPhoton, 4)}`,
    `  capped photons         ${e.capped} (weight left ${fmt(e.cappedWeight, 3)} per photon)`,
    `  time                   ${outcome.milliseconds.toFixed(1)} ms (${outcome.timing})`,
    '',
    '  radial profile R(r), reflected weight per unit area (1/L²), ± one standard error',
    `  ${'r_inner'.padEnd(12)} ${'r_outer'.padEnd(12)} ${'R(r)'.padEnd(12)} SE`,
    ...e.profile.density.map(
      (bin, k) =>
        `  ${fmt(e.profile.edges[k]!, 4).padEnd(12)} ${fmt(e.profile.edges[k + 1]!, 4).padEnd(12)} ${fmt(bin.mean, 5).padEnd(12)} ${fmt(bin.se, 2)}`,
    ),
  ];
  return lines.join('\n');
}

/** Runs `scatterbook slab ARGS`; returns the exit status. */
export async function slabCommand(argv: readonly string[]): Promise<number> {
  if (argv.includes('--help') || argv.includes('-h')) {
    console.log(SLAB_USAGE);
    return 0;
  }
  let options: SlabOptions;
  try {
    options = parseSlabOptions(argv);
  } catch (error) {
    if (error instanceof SlabUsageError) {
      console.error(`scatterbook slab: ${error.message}\n\nRun scatterbook slab --help for usage.`);
      return 2;
    }
    throw error;
  }
  try {
    const outcome = await simulate(options);
    console.log(
      options.json
        ? JSON.stringify(jsonReport(options, outcome), null, 2)
        : textReport(options, outcome),
    );
    return 0;
  } catch (error) {
    console.error(`scatterbook slab: ${(error as Error).message}`);
    return 1;
  }
}
