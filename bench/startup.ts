// Benchmark: the start-up of `npm run render` (issue 19: process start to the first render
// pass submitted, goal under 0.5 s). Runs the command as a user does (scripts/gpu-env.sh,
// node scripts/cli.mjs: the prebuilt bundle) on the peer scenes (bench/peers.ts) at 1 spp,
// reads the start-up phases it writes with --stats (src/cli/startup.ts) and prints their
// medians. The same command under tsx (SCATTERBOOK_TSX=1) is timed alongside, and with
// --baseline=DIR an older checkout's `render` under tsx (e.g. made with
// `git worktree add /tmp/base <commit>` and a node_modules link), so that before and after
// come from one run on one machine; its process time is all it reports (older commands
// write no start-up phases). Runs of the modes alternate, so load drifts alike for each.
import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { cpus, loadavg, tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { StartupReport } from '../src/cli/startup.ts';
import { peerScenes } from './peers.ts';
import { median, type BenchTable } from './table.ts';

const ROOT = fileURLToPath(new URL('..', import.meta.url));

type Mode = 'bundle' | 'tsx' | 'baseline';

interface Sample {
  processMs: number;
  startup: StartupReport | null;
}

function run(
  command: string,
  args: string[],
  cwd: string,
  env: NodeJS.ProcessEnv,
): Promise<{ ms: number }> {
  return new Promise((resolve, reject) => {
    const start = performance.now();
    const child = spawn(command, args, { cwd, env, stdio: ['ignore', 'ignore', 'pipe'] });
    let stderr = '';
    child.stderr.on('data', (chunk: Buffer) => (stderr += chunk.toString()));
    child.on('error', reject);
    child.on('close', (code) =>
      code === 0
        ? resolve({ ms: performance.now() - start })
        : reject(new Error(`${args.join(' ')} exited with ${code}: ${stderr.slice(-2000)}`)),
    );
  });
}

async function sample(mode: Mode, scene: string, work: string, baseline?: string): Promise<Sample> {
  const out = join(work, 'image.pfm');
  const stats = join(work, 'stats.json');
  rmSync(stats, { force: true });
  const flags = [scene, '--out', out, '--spp', '1', '--stats', stats];
  const { ms } =
    mode === 'baseline'
      ? await run(
          'sh',
          ['scripts/gpu-env.sh', 'node_modules/.bin/tsx', 'src/cli/main.ts', 'render', ...flags],
          baseline!,
          process.env,
        )
      : await run(
          'sh',
          ['scripts/gpu-env.sh', 'node', 'scripts/cli.mjs', 'render', ...flags],
          ROOT,
          {
            ...process.env,
            ...(mode === 'tsx' ? { SCATTERBOOK_TSX: '1' } : {}),
          },
        );
  const written = JSON.parse(readFileSync(stats, 'utf8')) as { startup?: StartupReport };
  return { processMs: ms, startup: written.startup ?? null };
}

const duration = (report: StartupReport, name: string): number | null => {
  const span = report.phases[name];
  return span ? span.end - span.start : null;
};

/** The median of the values that are there, or null. */
function medianOf(values: (number | null | undefined)[]): number | null {
  const present = values.filter((v): v is number => typeof v === 'number');
  return present.length > 0 ? median(present) : null;
}

export async function benchStartup(options: {
  /** Processes per scene and mode. */
  runs: number;
  /** How many of the peer scenes (in bench/peers.ts's order). */
  scenes: number;
  /** An older checkout to time alongside (its `render` under tsx). */
  baseline?: string;
}): Promise<BenchTable> {
  const work = mkdtempSync(join(tmpdir(), 'scatterbook-startup-'));
  const modes: Mode[] = ['bundle', 'tsx', ...(options.baseline ? (['baseline'] as const) : [])];
  const loadBefore = loadavg()[0]!;
  const rows: BenchTable['rows'] = [];
  try {
    for (const { name, json } of peerScenes(64).slice(0, options.scenes)) {
      const scene = join(work, 'scene.json');
      writeFileSync(scene, JSON.stringify(json));
      // Not counted: builds the bundle and fills the linked-WGSL cache, as any earlier run would.
      for (const mode of modes) await sample(mode, scene, work, options.baseline);
      const samples = new Map<Mode, Sample[]>(modes.map((m) => [m, []]));
      for (let k = 0; k < options.runs; k++)
        for (const mode of modes)
          samples.get(mode)!.push(await sample(mode, scene, work, options.baseline));
      for (const mode of modes) {
        const list = samples.get(mode)!;
        const reports = list.map((s) => s.startup).filter((r): r is StartupReport => r !== null);
        const of = (f: (r: StartupReport) => number | null): number | null =>
          medianOf(reports.map(f));
        rows.push({
          scene: name,
          command:
            mode === 'bundle'
              ? 'npm run render (bundle)'
              : mode === 'tsx'
                ? 'same, under tsx'
                : 'baseline checkout (tsx)',
          'process s': median(list.map((s) => s.processMs)) / 1000,
          'first pass submitted ms': of((r) => r.firstPassSubmittedMs),
          'CPU ms by then': of((r) => r.firstPassCpuMs),
          'Node bootstrap ms': of((r) => r.nodeBootstrapMs),
          'program loaded ms': of((r) => r.phases['load program']?.end ?? null),
          'webgpu + device ms': of((r) => {
            const a = duration(r, 'import webgpu');
            const b = duration(r, 'adapter and device');
            return a === null || b === null ? null : a + b;
          }),
          'scene + shader library ms': of((r) => {
            const a = duration(r, 'read scene');
            const b = duration(r, 'shader library');
            return a === null || b === null ? null : a + b;
          }),
          'scene kernel compile ms': of((r) => duration(r, 'compile scene kernel')),
          'accumulate kernel compile ms': of((r) => duration(r, 'compile accumulate kernel')),
          'compiled → first pass ms': of((r) => {
            const compiled = Math.max(
              r.phases['compile scene kernel']?.end ?? NaN,
              r.phases['compile accumulate kernel']?.end ?? NaN,
            );
            return r.firstPassSubmittedMs === null || !Number.isFinite(compiled)
              ? null
              : r.firstPassSubmittedMs - compiled;
          }),
        });
      }
    }
  } finally {
    rmSync(work, { recursive: true, force: true });
  }
  return {
    title: 'Start-up of `npm run render`: process start to the first render pass submitted',
    notes: [
      `Medians of ${options.runs} processes per scene and command at 1 spp (64×64), after one uncounted run each; the modes alternate run by run. Load average (1 min) ${loadBefore.toFixed(2)} before, ${loadavg()[0]!.toFixed(2)} after, with ${cpus().length} cores.`,
      'Phases from `render --stats` (startup): ms since the process started (performance.timeOrigin). "CPU ms by then": the process\'s CPU time (all threads) at the first pass, which load stretches less than wall time. "process s" is the whole process seen from outside (sh, node, the render, writing the image, exit).',
      'The scene kernel and the accumulate kernel compile at once; SwiftShader compiling the scene kernel is the floor (Dawn in the webgpu package has no persistent pipeline cache: its requestDevice passes no DawnCacheDeviceDescriptor).',
    ],
    rows,
  };
}
