// `scatterbook slab` (src/cli/slab.ts) run as a child process the way a user runs it:
// --json on both backends for benchmark A of physics.md §7 (same seeds, so the two
// replay the same walks and agree far within their standard error, and both meet van
// de Hulst's values within 5σ), the text report, and the error messages for bad input.
import { execFile } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { beforeAll, describe, expect, it } from 'vitest';
import { expectMatches } from '../support/slabBenchmarks.ts';
import { parseSlabOptions, SLAB_USAGE, SlabUsageError } from '../../src/cli/slab.ts';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));

interface Run {
  code: number;
  stdout: string;
  stderr: string;
}

function cli(...args: string[]): Promise<Run> {
  return new Promise((resolve) => {
    execFile(
      'sh',
      ['scripts/gpu-env.sh', 'node_modules/.bin/tsx', 'src/cli/main.ts', 'slab', ...args],
      { cwd: ROOT, env: { ...process.env, NO_COLOR: '1' }, timeout: 90_000 },
      (error, stdout, stderr) => {
        const code = error ? (typeof error.code === 'number' ? error.code : -1) : 0;
        resolve({ code, stdout, stderr });
      },
    );
  });
}

interface SlabJson {
  backend: string;
  setup: Record<string, number | string>;
  photons: number;
  batches: number;
  Rsp: number;
  Rd: number;
  RdSE: number;
  RdPlusRsp: number;
  Tt: number;
  TtSE: number;
  Tu: number;
  collisionsPerPhoton: number;
  capped: number;
  milliseconds: number;
  timing: string;
  profile: { rInner: number; rOuter: number; r: number; R: number; SE: number }[];
}

const BENCHMARK_A = ['--sigma-a', '10', '--sigma-s', '90', '--g', '0.75', '--thickness', '0.02'];

// The child processes run together (each costs about a second of CPU to start).
let gpu: SlabJson;
let cpu: SlabJson;
let text: Run;
let badCommand: Run;
beforeAll(async () => {
  const args = [...BENCHMARK_A, '--photons', '16384', '--seed', '3', '--bins', '12', '--json'];
  const [g, c, bad, t] = await Promise.all([
    cli(...args),
    cli(...args, '--backend', 'cpu'),
    cli('--sigma-a', '1', '--sigma-s', '1', '--thickness', '1', '--g', '1.5'),
    cli(
      '--sigma-a',
      '10',
      '--sigma-s',
      '90',
      '--thickness',
      'inf',
      '--eta',
      '1.5',
      '--photons',
      '1024',
      '--backend',
      'cpu',
    ),
  ]);
  expect(g.code, g.stderr).toBe(0);
  expect(c.code, c.stderr).toBe(0);
  gpu = JSON.parse(g.stdout) as SlabJson;
  cpu = JSON.parse(c.stdout) as SlabJson;
  text = t;
  badCommand = bad;
}, 120_000);

describe('scatterbook slab: benchmark A on both backends (physics.md §7)', () => {
  it('--json prints the setup, R_d, T_t with standard errors, the cost and the profile', () => {
    expect(gpu.backend).toBe('gpu');
    expect(cpu.backend).toBe('cpu');
    expect(gpu.setup).toMatchObject({ sigmaA: 10, sigmaS: 90, g: 0.75, thickness: 0.02, eta: 1 });
    expect(gpu.photons).toBeGreaterThanOrEqual(16384);
    expect(gpu.batches).toBeGreaterThanOrEqual(64);
    expect(gpu.Rsp).toBe(0);
    expect(gpu.capped).toBe(0);
    expect(gpu.milliseconds).toBeGreaterThan(0);
    expect(gpu.profile).toHaveLength(12);
    expect(gpu.profile[0]!.rInner).toBe(0);
    expect(gpu.profile.every((bin) => bin.R >= 0 && bin.SE >= 0)).toBe(true);
  });

  it('both backends meet van de Hulst (R_d = 0.09739, T_t = 0.66096) within 5σ', () => {
    for (const run of [gpu, cpu]) {
      expectMatches({ mean: run.Rd, se: run.RdSE }, 0.09739, 5, `${run.backend} R_d`);
      expectMatches({ mean: run.Tt, se: run.TtSE }, 0.66096, 5, `${run.backend} T_t`);
    }
  });

  it('the same seed replays the same walks: GPU and CPU differ by far less than one standard error', () => {
    expect(Math.abs(gpu.Rd - cpu.Rd)).toBeLessThan(0.2 * cpu.RdSE);
    expect(Math.abs(gpu.Tt - cpu.Tt)).toBeLessThan(0.2 * cpu.TtSE);
    expect(gpu.photons).toBe(cpu.photons);
  });

  it('without --json prints a readable report (here a half-space with n = 1.5 on the CPU)', () => {
    expect(text.code, text.stderr).toBe(0);
    expect(text.stdout).toContain('float64 twin on the CPU');
    expect(text.stdout).toMatch(/thickness = inf \(half-space\)/);
    expect(text.stdout).toMatch(/R_sp \(specular\)\s+0\.0400000/);
    expect(text.stdout).toMatch(/R_d \+ R_sp\s+0\.2\d+ ± /);
    expect(text.stdout).toContain('radial profile R(r)');
  });
});

describe('scatterbook slab: clear errors', () => {
  // Parsed in process (each child process costs a second of CPU on a shared machine);
  // one bad command line below goes through the process to check the exit status.
  const cases: { name: string; args: string[]; message: RegExp }[] = [
    {
      name: 'missing --sigma-a',
      args: ['--sigma-s', '1', '--thickness', '1'],
      message: /missing --sigma-a/,
    },
    {
      name: 'missing --thickness',
      args: ['--sigma-a', '1', '--sigma-s', '1'],
      message: /missing --thickness/,
    },
    {
      name: 'not a number',
      args: ['--sigma-a', 'abc', '--sigma-s', '1', '--thickness', '1'],
      message: /--sigma-a must be a number, got "abc"/,
    },
    {
      name: 'negative σa',
      args: ['--sigma-a=-1', '--sigma-s', '1', '--thickness', '1'],
      message: /--sigma-a must be a finite number ≥ 0/,
    },
    {
      name: 'no medium',
      args: ['--sigma-a', '0', '--sigma-s', '0', '--thickness', '1'],
      message: /no medium to simulate/,
    },
    {
      name: 'g = 1',
      args: ['--sigma-a', '1', '--sigma-s', '1', '--thickness', '1', '--g', '1'],
      message: /--g must lie in \(−1, 1\)/,
    },
    {
      name: 'thickness 0',
      args: ['--sigma-a', '1', '--sigma-s', '1', '--thickness', '0'],
      message: /--thickness must be > 0/,
    },
    {
      name: 'η ≤ 0',
      args: ['--sigma-a', '1', '--sigma-s', '1', '--thickness', '1', '--eta', '0'],
      message: /--eta must be a finite number > 0/,
    },
    {
      name: 'incidence cosine 0',
      args: ['--sigma-a', '1', '--sigma-s', '1', '--thickness', '1', '--incidence-cos', '0'],
      message: /--incidence-cos must lie in \(0, 1\]/,
    },
    {
      name: 'fractional photons',
      args: ['--sigma-a', '1', '--sigma-s', '1', '--thickness', '1', '--photons', '1.5'],
      message: /--photons must be an integer/,
    },
    {
      name: 'too many bins',
      args: ['--sigma-a', '1', '--sigma-s', '1', '--thickness', '1', '--bins', '65'],
      message: /--bins must be an integer in \[2, 64\]/,
    },
    {
      name: 'r-max below r-min',
      args: [
        '--sigma-a',
        '1',
        '--sigma-s',
        '1',
        '--thickness',
        '1',
        '--r-min',
        '2',
        '--r-max',
        '1',
      ],
      message: /--r-max must be finite and > --r-min/,
    },
    {
      name: 'unknown backend',
      args: ['--sigma-a', '1', '--sigma-s', '1', '--thickness', '1', '--backend', 'tpu'],
      message: /--backend must be gpu or cpu/,
    },
    {
      name: 'unknown option',
      args: ['--sigma-a', '1', '--sigma-s', '1', '--thickness', '1', '--colour', 'red'],
      message: /Unknown option '--colour'/,
    },
    {
      name: 'a stray positional',
      args: ['benchmark', '--sigma-a', '1', '--sigma-s', '1', '--thickness', '1'],
      message: /slab takes only options/,
    },
  ];
  cases.forEach((c) => {
    it(c.name, () => {
      expect(() => parseSlabOptions(c.args)).toThrow(SlabUsageError);
      expect(() => parseSlabOptions(c.args)).toThrow(c.message);
    });
  });

  it('defaults: g = 0, η = 1, μ0 = 1, 65536 photons, profile from 0.01 to 100 transport mean free paths', () => {
    const { run, backend } = parseSlabOptions([
      '--sigma-a',
      '1',
      '--sigma-s',
      '4',
      '--thickness',
      'inf',
    ]);
    expect(backend).toBe('gpu');
    expect(run).toMatchObject({ g: 0, eta: 1, incidenceCos: 1, thickness: Infinity });
    expect(run.batches * 64 * run.photonsPerThread).toBeGreaterThanOrEqual(65536);
    expect(run.profile.rMin).toBeCloseTo(0.002, 12);
    expect(run.profile.rMax).toBeCloseTo(20, 12);
  });

  it('through the process: exit status 2, nothing on stdout, the reason and a pointer to --help on stderr', () => {
    const run = badCommand;
    expect(run.code).toBe(2);
    expect(run.stdout).toBe('');
    expect(run.stderr).toMatch(/--g must lie in \(−1, 1\), got 1\.5/);
    expect(run.stderr).toContain('scatterbook slab --help');
  });

  it('the usage names every option', () => {
    for (const option of [
      '--sigma-a',
      '--sigma-s',
      '--thickness',
      '--g',
      '--eta',
      '--incidence-cos',
      '--photons',
      '--json',
      '--backend',
    ])
      expect(SLAB_USAGE).toContain(option);
  });
});
