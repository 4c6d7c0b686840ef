// The command line (src/cli/main.ts), run as a child process the way a user runs it:
// `list`, `eval` on both backends with and without --json, GPU vs CPU agreement for a
// few functions (each within its shader test's tolerance), and the error messages for
// bad input. Also the signature reading of src/gpu/functionEvaluator.ts in process,
// on a small library of its own, including the vecNf wrapper on the GPU.
import { execFile } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { beforeAll, describe, expect, it } from 'vitest';
import {
  evaluateOnGpu,
  flattenCall,
  functionsOf,
  specFor,
  UnsupportedSignatureError,
} from '../../src/gpu/functionEvaluator.ts';
import { pcgHash } from '../../src/reference/rng.ts';
import {
  opticalThicknessGrid1D,
  opticalThicknessSine,
  transmittanceHomogeneous,
} from '../../src/reference/transmittance.ts';
import { nodeDevice } from '../support/nodeGpu.ts';

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
      ['scripts/gpu-env.sh', 'node_modules/.bin/tsx', 'src/cli/main.ts', ...args],
      { cwd: ROOT, env: { ...process.env, NO_COLOR: '1' }, timeout: 60_000 },
      (error, stdout, stderr) => {
        const code = error ? (typeof error.code === 'number' ? error.code : -1) : 0;
        resolve({ code, stdout, stderr });
      },
    );
  });
}

interface EvalJson {
  function: string;
  backend: string;
  results: unknown[];
}

function parse(run: Run): EvalJson {
  expect(run.code, run.stderr).toBe(0);
  return JSON.parse(run.stdout) as EvalJson;
}

/** Both backends on the same calls, in parallel. */
async function bothBackends(target: string, calls: unknown[][]): Promise<[EvalJson, EvalJson]> {
  const args = JSON.stringify(calls);
  const [gpu, cpu] = await Promise.all([
    cli('eval', target, '--args', args, '--backend', 'gpu', '--json'),
    cli('eval', target, '--args', args, '--backend', 'cpu', '--json'),
  ]);
  return [parse(gpu), parse(cpu)];
}

const relativeOrAbsolute = (a: number, b: number, relative: number, absolute: number): boolean =>
  Math.abs(a - b) <= Math.max(relative * Math.abs(b), absolute);

describe('scatterbook list', () => {
  it('--json lists every module with each function’s signature and backends', async () => {
    const run = await cli('list', '--json');
    expect(run.code, run.stderr).toBe(0);
    const { modules } = JSON.parse(run.stdout) as {
      modules: {
        name: string;
        functions: { name: string; signature: string; backends: string[] }[];
      }[];
    };
    const find = (module: string, fn: string) =>
      modules.find((m) => m.name === module)?.functions.find((f) => f.name === fn);
    expect(modules.map((m) => m.name)).toEqual(
      expect.arrayContaining(['medium', 'rng', 'transmittance']),
    );
    expect(find('transmittance', 'transmittanceHomogeneous')).toEqual({
      name: 'transmittanceHomogeneous',
      signature: 'transmittanceHomogeneous(sigmaT: f32, distance: f32) -> f32',
      backends: ['gpu', 'cpu'],
    });
    // A texture argument: the twin only.
    expect(find('medium', 'gridDensityTrilinear')?.backends).toEqual(['cpu']);
    expect(find('rng', 'rngNextFloat')?.backends).toEqual(['cpu']);
  });

  it('prints a readable table without --json', async () => {
    const run = await cli('list');
    expect(run.code, run.stderr).toBe(0);
    expect(run.stdout).toMatch(/^transmittance$/m);
    expect(run.stdout).toMatch(
      /gpu cpu\s+transmittanceHomogeneous\(sigmaT: f32, distance: f32\) -> f32/,
    );
  });
});

describe('scatterbook eval: GPU vs CPU', () => {
  it('transmittanceHomogeneous: --json output and Beer’s law on both backends (WGSL exp: 2e-5 relative)', async () => {
    const calls = [
      [1, 2],
      [0.5, 4],
      [0, 1],
      [3, 1],
      [1e6, 1],
    ];
    const [gpu, cpu] = await bothBackends('transmittance.transmittanceHomogeneous', calls);
    expect(Object.keys(gpu)).toEqual(['function', 'backend', 'results']);
    expect(gpu.function).toBe('transmittance.transmittanceHomogeneous');
    expect(gpu.backend).toBe('gpu');
    expect(cpu.backend).toBe('cpu');
    calls.forEach(([sigma, d], i) => {
      const exact = transmittanceHomogeneous(sigma ?? NaN, d ?? NaN);
      expect(cpu.results[i]).toBe(exact);
      expect(relativeOrAbsolute(gpu.results[i] as number, exact, 2e-5, 2 ** -126)).toBe(true);
    });
  });

  it('opticalThicknessSine agrees within WGSL sin’s 2^-11 absolute error (5e-4 relative)', async () => {
    const calls = [
      [1, 0.8, 3, 0, 0, 1],
      [2, 0.5, 1.5, 0.3, 0.25, 4],
    ];
    const [gpu, cpu] = await bothBackends('transmittance.opticalThicknessSine', calls);
    calls.forEach((call, i) => {
      const exact = opticalThicknessSine(
        ...(call as [number, number, number, number, number, number]),
      );
      expect(cpu.results[i]).toBe(exact);
      expect(relativeOrAbsolute(gpu.results[i] as number, exact, 5e-4, 1e-6)).toBe(true);
    });
  });

  it('opticalThicknessGrid1D: an array<f32, 16> argument, padded with zeros (≤ 16 ULP sum)', async () => {
    const cells = [0.5, 1.5, 0.8, 1.2];
    const [gpu, cpu] = await bothBackends('transmittance.opticalThicknessGrid1D', [
      [cells, 4, 0.25, 0.1, 0.9],
    ]);
    const exact = opticalThicknessGrid1D([...cells, ...new Array(12).fill(0)], 4, 0.25, 0.1, 0.9);
    expect(cpu.results[0]).toBeCloseTo(exact, 15);
    expect(relativeOrAbsolute(gpu.results[0] as number, exact, 1e-6, 1e-7)).toBe(true);
  });

  it('pcgHash: u32 in and out, bit for bit on both backends', async () => {
    const words = [0, 1, 42, 0xdeadbeef, 0xffffffff];
    const [gpu, cpu] = await bothBackends(
      'rng.pcgHash',
      words.map((w) => [w]),
    );
    expect(gpu.results).toEqual(words.map(pcgHash));
    expect(cpu.results).toEqual(words.map(pcgHash));
  });

  it('prints a table with the parameter names without --json', async () => {
    const run = await cli('eval', 'transmittance.transmittanceHomogeneous', '--args', '[[1, 2]]');
    expect(run.code, run.stderr).toBe(0);
    expect(run.stdout).toContain('WGSL, f32, on the GPU');
    expect(run.stdout).toMatch(/#\s+sigmaT\s+distance\s+result/);
    expect(run.stdout).toMatch(/1\s+1\s+2\s+0\.13533/);
  });

  it('the CPU backend takes structs as JSON objects (a homogeneous Medium1D)', async () => {
    const medium = {
      kind: 0,
      sigma0: 2,
      amplitude: 0,
      frequency: 0,
      phase: 0,
      cellSize: 0,
      cellCount: 0,
      cells: [],
    };
    const run = await cli(
      'eval',
      'medium.mediumOpticalDepth',
      '--args',
      JSON.stringify([[medium, 1, 3.5]]),
      '--backend',
      'cpu',
      '--json',
    );
    expect(parse(run).results).toEqual([5]);
  });
});

describe('scatterbook: clear errors (exit status 2)', () => {
  const cases: { name: string; args: string[]; message: RegExp }[] = [
    {
      name: 'unknown module, listing the modules',
      args: ['eval', 'fog.density', '--args', '[[1]]'],
      message: /unknown module "fog"; modules: .*transmittance/,
    },
    {
      name: 'unknown module on the CPU backend',
      args: ['eval', 'fog.density', '--args', '[[1]]', '--backend', 'cpu'],
      message: /unknown module "fog"/,
    },
    {
      name: 'unknown function, listing the functions',
      args: ['eval', 'transmittance.beer', '--args', '[[1]]'],
      message:
        /module transmittance has no function "beer"; its functions: .*transmittanceHomogeneous/,
    },
    {
      name: 'unknown function on the CPU backend',
      args: ['eval', 'rng.nope', '--args', '[[1]]', '--backend', 'cpu'],
      message: /module rng has no function "nope"/,
    },
    {
      name: 'bad JSON',
      args: ['eval', 'transmittance.transmittanceHomogeneous', '--args', '[[1, 2]'],
      message: /--args is not valid JSON/,
    },
    {
      name: 'not an array of calls',
      args: ['eval', 'transmittance.transmittanceHomogeneous', '--args', '[1, 2]'],
      message: /--args must be a JSON array of calls/,
    },
    {
      name: 'wrong arity',
      args: ['eval', 'transmittance.transmittanceHomogeneous', '--args', '[[1, 2], [3]]'],
      message:
        /call 2 has 1 argument; transmittanceHomogeneous\(sigmaT: f32, distance: f32\) -> f32 takes 2/,
    },
    {
      name: 'wrong arity on the CPU backend',
      args: [
        'eval',
        'transmittance.transmittanceHomogeneous',
        '--args',
        '[[1, 2, 3]]',
        '--backend',
        'cpu',
      ],
      message: /call 1 has 3 arguments; .* takes 2/,
    },
    {
      name: 'a struct on the GPU names the type and suggests --backend cpu',
      args: ['eval', 'medium.mediumExtinction', '--args', '[[{}, 1]]'],
      message: /parameter medium has type Medium1D \(a struct\).*--backend cpu/s,
    },
    {
      name: 'a texture on the GPU names the type',
      args: ['eval', 'medium.gridDensityTrilinear', '--args', '[[1, 2, 3]]'],
      message: /parameter grid has type DensityGrid.*--backend cpu/s,
    },
    {
      name: 'a pointer on the GPU names the type',
      args: ['eval', 'rng.rngNextFloat', '--args', '[[1]]'],
      message: /parameter state has type ptr<function, u32> \(a pointer\).*--backend cpu/s,
    },
    {
      name: 'a function that exists only under a link condition, on the GPU',
      args: ['eval', 'integrator.sceneGridDensity', '--args', '[[0, 0, 0]]'],
      message: /exists only in kernels linked with a condition \(@if\).*--backend cpu/s,
    },
    {
      name: 'a u32 out of range',
      args: ['eval', 'rng.pcgHash', '--args', '[[-1]]'],
      message: /argument 1 \(value: u32\) must be an integer in \[0, 4294967295\]/,
    },
    {
      name: 'a number where an array is expected',
      args: ['eval', 'transmittance.opticalThicknessGrid1D', '--args', '[[1, 4, 0.25, 0, 1]]'],
      message: /argument 1 \(sigma: array<f32, GRID1D_MAX_CELLS>\) must be an array of numbers/,
    },
    {
      name: 'an unknown backend',
      args: ['eval', 'rng.pcgHash', '--args', '[[1]]', '--backend', 'tpu'],
      message: /--backend must be gpu or cpu/,
    },
    { name: 'a missing --args', args: ['eval', 'rng.pcgHash'], message: /missing --args/ },
    { name: 'an unknown command', args: ['frobnicate'], message: /unknown command "frobnicate"/ },
    {
      name: 'no MODULE.FUNCTION',
      args: ['eval', 'pcgHash', '--args', '[[1]]'],
      message: /expected MODULE.FUNCTION/,
    },
  ];
  let runs: Run[] = [];
  beforeAll(async () => {
    // Two at a time: each run starts tsx and Dawn (1–2 s of CPU), and 17 at once on a
    // two-core machine under load took longer than a minute.
    runs = new Array<Run>(cases.length);
    let next = 0;
    const worker = async (): Promise<void> => {
      for (let i = next++; i < cases.length; i = next++) runs[i] = await cli(...cases[i]!.args);
    };
    await Promise.all([worker(), worker()]);
  }, 180_000);

  cases.forEach((c, i) => {
    it(c.name, () => {
      const run = runs[i] as Run;
      expect(run.code).toBe(2);
      expect(run.stdout).toBe('');
      expect(run.stderr).toMatch(c.message);
    });
  });
});

describe('conditional declarations (what an evaluation kernel, linked with no conditions, keeps)', () => {
  it('reads names as false, and !, &&, || and parentheses', () => {
    const cases: [string, boolean][] = [
      ['gridMedia', false],
      ['!gridMedia', true],
      ['true', true],
      ['a || !b', true],
      ['!a && (b || !c)', true],
      ['!(a || b) && c', false],
      ['!(oneHomogeneousMedium || oneGridMedium)', true],
    ];
    const library = {
      'c.wesl': cases
        .map(([condition], i) => `@if(${condition}) fn f${i}() -> f32 { return 1.0; }`)
        .join('\n'),
    };
    const functions = functionsOf(library, 'c');
    expect(functions.map((f) => !f.conditional)).toEqual(cases.map(([, holds]) => holds));
  });
});

describe('functionEvaluator signatures (in process, a library of its own)', () => {
  const library = {
    'vectors.wesl': [
      'const SIZE: u32 = 3u;',
      'struct Pair { a: f32, b: f32 }',
      'fn scaleVector(v: vec3f, s: f32) -> vec3f { return v * s; }',
      'fn dotWith(v: vec2<f32>, w: vec2f) -> f32 { return dot(v, w); }',
      'fn sumOf(values: array<f32, SIZE>, offset: i32) -> f32 { return values[0] + values[1] + values[2] + f32(offset); }',
      'fn firstOf(p: Pair) -> f32 { return p.a; }',
      'fn makePair(a: f32) -> Pair { return Pair(a, a); }',
      '@if(someCondition) fn onlyUnderCondition(x: f32) -> f32 { return x; }',
      '@if(!someCondition) fn unlessCondition(x: f32) -> f32 { return x; }',
    ].join('\n'),
  };

  it('reads parameter names and types, resolving array lengths from constants', () => {
    const functions = functionsOf(library, 'vectors');
    expect(functions.map((f) => f.text)).toEqual([
      'scaleVector(v: vec3f, s: f32) -> vec3f',
      'dotWith(v: vec2<f32>, w: vec2f) -> f32',
      'sumOf(values: array<f32, SIZE>, offset: i32) -> f32',
      'firstOf(p: Pair) -> f32',
      'makePair(a: f32) -> Pair',
      'onlyUnderCondition(x: f32) -> f32',
      'unlessCondition(x: f32) -> f32',
    ]);
    expect(functions[2]?.params[0]?.type.components).toBe(3);
    expect(specFor(functions[2] as never).args).toEqual(['f32[3]', 'i32']);
    expect(() => specFor(functions[3] as never)).toThrow(UnsupportedSignatureError);
    expect(() => specFor(functions[3] as never)).toThrow(/parameter p has type Pair \(a struct\)/);
    expect(() => specFor(functions[4] as never)).toThrow(/its result has type Pair/);
    // An evaluation kernel links with no conditions, where this function does not exist.
    // (@if(!c) holds there, so that one is evaluable.)
    expect(functions.map((f) => f.conditional)).toEqual([
      false,
      false,
      false,
      false,
      false,
      true,
      false,
    ]);
    expect(() => specFor(functions[5] as never)).toThrow(/exists only under a link condition/);
    expect(specFor(functions[6] as never).args).toEqual(['f32']);
  });

  it('passes vecNf arguments through a wrapper and returns vecNf results (on the GPU)', async () => {
    const [scale, dotWith, sumOf] = functionsOf(library, 'vectors') as [never, never, never];
    const device = await nodeDevice();
    const scaled = await evaluateOnGpu(device, library, specFor(scale), [
      flattenCall(scale, [[1, -2, 0.5], 4]),
    ]);
    expect(scaled).toEqual([[4, -8, 2]]);
    const dots = await evaluateOnGpu(device, library, specFor(dotWith), [
      flattenCall(dotWith, [
        [1, 2],
        [3, 4],
      ]),
    ]);
    expect(dots).toEqual([[11]]);
    const sums = await evaluateOnGpu(device, library, specFor(sumOf), [
      flattenCall(sumOf, [[1, 2, 3], -2]),
    ]);
    expect(sums).toEqual([[4]]);
  });
});
