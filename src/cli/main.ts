// scatterbook: the book's command line. `eval` calls one function of the shader
// library on a list of inputs, either the WGSL function on the GPU (Dawn in Node;
// SwiftShader where there is no GPU) or its float64 twin in src/reference/ on the
// CPU; `list` shows the library's modules and functions and which backends can
// call each; `render` renders a scene file (src/cli/render.ts). Run it with
// `npm run cli -- eval …` (scripts/gpu-env.sh sets up Dawn).
//
// The GPU backend reads the function's WGSL signature from the linked library with
// the WESL parser and evaluates it through src/gpu/functionEvaluator.ts, the code the
// shader tests use; it takes f32, u32, i32, vecNf and array<f32, N> arguments.
//
// `render` must start fast (issue 19): the modules only `eval`, `list` and `slab` use (the
// WESL parser among them) are imported by those commands, not at start-up.
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';
import type { Argument, FunctionSignature } from '../gpu/functionEvaluator.ts';

/** The GPU function evaluator and the WGSL signature reader (WESL's parser). */
type Evaluator = typeof import('../gpu/functionEvaluator.ts');
const loadEvaluator = (): Promise<Evaluator> => import('../gpu/functionEvaluator.ts');
import type { ShaderLibrary } from '../gpu/link.ts';
import { loadShaderLibrary } from '../gpu/shaderSourcesNode.ts';
import { RENDER_HELP, RENDER_SYNOPSIS, RenderInputError, runRender } from './render.ts';
import { StartupTimer } from './startup.ts';

/** Start-up phases, from the process's start (render --stats). */
const timer = new StartupTimer();
timer.record('load program', 0);

const SHADERS_DIRECTORY = fileURLToPath(new URL('../../shaders', import.meta.url));
// From the project root, so that it holds for src/cli/main.ts and the prebuilt bundle in
// .cache/cli/ (scripts/cli.mjs) alike.
const REFERENCE_DIRECTORY = fileURLToPath(new URL('../../src/reference', import.meta.url));

const USAGE = `Usage:
  scatterbook eval MODULE.FUNCTION --args JSON [--backend gpu|cpu] [--json]
  scatterbook list [--json]
  scatterbook slab --sigma-a A --sigma-s S --thickness D|inf [--g G] [--eta N] … (slab --help)
${RENDER_SYNOPSIS}

eval    Calls a shader library function once per inner array of --args, e.g.
          scatterbook eval transmittance.transmittanceHomogeneous --args '[[1, 2], [0.5, 4]]'
        --backend gpu (default): the WGSL function in f32 on the GPU (inputs rounded
          to f32); arguments f32, u32, i32, vecNf (an array of N numbers) and
          array<f32, N> (up to N numbers, padded with 0).
        --backend cpu: the float64 twin in src/reference/MODULE.ts, on the values as
          given (objects for structs, {"value": n} for an RNG state).
list    Lists every module, its functions' WGSL signatures and the backends that can
        call each.
slab    Monte Carlo photon transport through a slab or half-space (physics.md §7):
          R_d, T_t with standard errors and the radial profile; see slab --help.
--json  Prints JSON: for eval { "function", "backend", "results": [one per call] }.
${RENDER_HELP}`;

/** Wrong command line or input: exit status 2. */
class UsageError extends Error {}

type Backend = 'gpu' | 'cpu';
type Json = null | boolean | number | string | Json[] | { [key: string]: Json };

interface EvalResult {
  function: string;
  backend: Backend;
  results: unknown[];
}

const F32_MAX = 3.4028234663852886e38;

function libraryModules(library: ShaderLibrary): string[] {
  return Object.keys(library)
    .filter((path) => /^[^/]+\.wesl$/.test(path))
    .map((path) => path.replace(/\.wesl$/, ''))
    .sort();
}

function referencePath(module: string): string {
  return `${REFERENCE_DIRECTORY}/${module}.ts`;
}

async function loadTwins(module: string): Promise<Record<string, unknown> | null> {
  if (!existsSync(referencePath(module))) return null;
  return (await import(`../reference/${module}.ts`)) as Record<string, unknown>;
}

function parseTarget(target: string | undefined): { module: string; fn: string } {
  const match = /^([A-Za-z][A-Za-z0-9_-]*)\.([A-Za-z_][A-Za-z0-9_]*)$/.exec(target ?? '');
  if (!match)
    throw new UsageError(
      `expected MODULE.FUNCTION (e.g. transmittance.transmittanceHomogeneous), got ${target === undefined ? 'nothing' : JSON.stringify(target)}`,
    );
  return { module: match[1] ?? '', fn: match[2] ?? '' };
}

function parseCalls(text: string | undefined): Json[][] {
  if (text === undefined)
    throw new UsageError("missing --args: a JSON array of calls, e.g. --args '[[1, 2], [0.5, 4]]'");
  let value: unknown;
  try {
    value = JSON.parse(text);
  } catch (error) {
    throw new UsageError(`--args is not valid JSON: ${(error as Error).message}`);
  }
  if (!Array.isArray(value) || !value.every(Array.isArray))
    throw new UsageError(
      '--args must be a JSON array of calls, each an array of arguments, e.g. [[1, 2], [0.5, 4]] (one call: [[1, 2]])',
    );
  if (value.length === 0) throw new UsageError('--args holds no calls');
  return value as Json[][];
}

/** Checks one argument against its WGSL type and returns it as the evaluator takes it. */
function gpuArgument(
  signature: FunctionSignature,
  call: number,
  index: number,
  value: Json,
): Argument {
  const param = signature.params[index];
  if (!param) throw new UsageError(`call ${call}: no parameter ${index + 1}`);
  const where = `call ${call}, argument ${index + 1} (${param.name}: ${param.type.text})`;
  const isNumber = (x: unknown): x is number => typeof x === 'number' && Number.isFinite(x);
  const type = param.type.text;
  if (type === 'f32' || type === 'u32' || type === 'i32') {
    if (!isNumber(value))
      throw new UsageError(`${where} must be a number, got ${JSON.stringify(value)}`);
    if (type === 'f32' && Math.abs(value) > F32_MAX)
      throw new UsageError(`${where}: ${value} is beyond the largest f32 (${F32_MAX})`);
    if (type === 'u32' && !(Number.isInteger(value) && value >= 0 && value <= 0xffffffff))
      throw new UsageError(`${where} must be an integer in [0, 4294967295], got ${value}`);
    if (type === 'i32' && !(Number.isInteger(value) && value >= -0x80000000 && value <= 0x7fffffff))
      throw new UsageError(
        `${where} must be an integer in [-2147483648, 2147483647], got ${value}`,
      );
    return value;
  }
  const n = param.type.components;
  const isVector = type.startsWith('vec');
  if (!Array.isArray(value) || !value.every(isNumber))
    throw new UsageError(`${where} must be an array of numbers, got ${JSON.stringify(value)}`);
  if (isVector ? value.length !== n : value.length > n)
    throw new UsageError(
      `${where} needs ${isVector ? '' : 'at most '}${n} numbers, got ${value.length}`,
    );
  if (value.some((x) => Math.abs(x) > F32_MAX))
    throw new UsageError(`${where} holds a value beyond the largest f32 (${F32_MAX})`);
  return value;
}

function checkArity(label: string, call: number, given: number, expected: number): void {
  if (given !== expected)
    throw new UsageError(
      `call ${call} has ${given} argument${given === 1 ? '' : 's'}; ${label} takes ${expected}`,
    );
}

function findSignature(
  { functionsOf }: Evaluator,
  library: ShaderLibrary,
  module: string,
  fn: string,
): FunctionSignature {
  const functions = functionsOf(library, module);
  const signature = functions.find((s) => s.fn === fn);
  if (!signature)
    throw new UsageError(
      `module ${module} has no function "${fn}"; its functions: ${functions.map((s) => s.fn).join(', ')}`,
    );
  return signature;
}

async function evaluateGpu(
  evaluator: Evaluator,
  library: ShaderLibrary,
  module: string,
  fn: string,
  calls: Json[][],
): Promise<unknown[]> {
  if (!libraryModules(library).includes(module))
    throw new UsageError(
      `unknown module "${module}"; modules: ${libraryModules(library).join(', ')}`,
    );
  const { evaluateOnGpu, flattenCall, specFor, UnsupportedSignatureError } = evaluator;
  const signature = findSignature(evaluator, library, module, fn);
  if (signature.conditional)
    throw new UsageError(
      `${module}.${fn} exists only in kernels linked with a condition (@if), and the GPU backend's ` +
        `evaluation kernel links with none. Use --backend cpu to call the float64 twin.`,
    );
  let spec;
  try {
    spec = specFor(signature);
  } catch (error) {
    if (error instanceof UnsupportedSignatureError)
      throw new UsageError(
        `${error.message}, which the GPU backend cannot pass (it takes f32, u32, i32, vecNf and array<f32, N>). ` +
          `Use --backend cpu to call the float64 twin, with structs as JSON objects.`,
      );
    throw error;
  }
  const gpuCalls = calls.map((call, c) => {
    checkArity(signature.text, c + 1, call.length, signature.params.length);
    return flattenCall(
      signature,
      call.map((value, index) => gpuArgument(signature, c + 1, index, value)),
    );
  });
  const { nodeDevice, releaseNodeDevice } = await import('../gpu/nodeDevice.ts');
  try {
    const device = await nodeDevice();
    const results = await evaluateOnGpu(device, library, spec, gpuCalls);
    return results.map((components) =>
      spec.result.startsWith('vec') ? components : components[0],
    );
  } finally {
    await releaseNodeDevice();
  }
}

async function evaluateCpu(
  { functionsOf }: Evaluator,
  library: ShaderLibrary,
  module: string,
  fn: string,
  calls: Json[][],
): Promise<unknown[]> {
  const twins = await loadTwins(module);
  if (!twins) {
    const known = libraryModules(library).filter((m) => existsSync(referencePath(m)));
    throw new UsageError(
      libraryModules(library).includes(module)
        ? `module ${module} has no float64 twin (src/reference/${module}.ts)`
        : `unknown module "${module}"; modules: ${known.join(', ')}`,
    );
  }
  const twin = twins[fn];
  if (typeof twin !== 'function') {
    const names = Object.keys(twins).filter((k) => typeof twins[k] === 'function');
    throw new UsageError(
      `module ${module} has no function "${fn}"; its functions: ${names.join(', ')}`,
    );
  }
  // The WGSL signature fixes the argument count (a twin may have optional extras).
  const signature = libraryModules(library).includes(module)
    ? functionsOf(library, module).find((s) => s.fn === fn)
    : undefined;
  const expected = signature?.params.length ?? twin.length;
  return calls.map((call, c) => {
    checkArity(signature?.text ?? `${fn} (twin)`, c + 1, call.length, expected);
    return (twin as (...args: unknown[]) => unknown)(...call);
  });
}

function formatValue(value: unknown): string {
  return typeof value === 'number' ? String(value) : JSON.stringify(value);
}

function table(rows: string[][]): string {
  const widths =
    rows[0]?.map((_, k) => Math.max(...rows.map((row) => (row[k] ?? '').length))) ?? [];
  return rows
    .map((row) =>
      row
        .map((cell, k) => cell.padEnd(widths[k] ?? 0))
        .join('  ')
        .trimEnd(),
    )
    .join('\n');
}

async function runEval(
  positionals: string[],
  values: { args?: string; backend?: string; json?: boolean },
): Promise<void> {
  if (positionals.length > 2)
    throw new UsageError(`eval takes one MODULE.FUNCTION, got ${positionals.slice(1).join(' ')}`);
  const { module, fn } = parseTarget(positionals[1]);
  const backend = values.backend ?? 'gpu';
  if (backend !== 'gpu' && backend !== 'cpu')
    throw new UsageError(`--backend must be gpu or cpu, got ${JSON.stringify(backend)}`);
  const calls = parseCalls(values.args);
  // Formatted before the call: a twin may update its arguments (an RNG state).
  const argumentCells = calls.map((call) => call.map(formatValue));
  const library = loadShaderLibrary(SHADERS_DIRECTORY);
  const evaluator = await loadEvaluator();
  const results =
    backend === 'gpu'
      ? await evaluateGpu(evaluator, library, module, fn, calls)
      : await evaluateCpu(evaluator, library, module, fn, calls);
  const output: EvalResult = { function: `${module}.${fn}`, backend, results };
  if (values.json) {
    console.log(JSON.stringify(output, null, 2));
    return;
  }
  const signature = libraryModules(library).includes(module)
    ? evaluator.functionsOf(library, module).find((s) => s.fn === fn)
    : undefined;
  const names =
    signature?.params.map((p) => p.name) ??
    Array.from({ length: calls[0]?.length ?? 0 }, (_, k) => `arg${k + 1}`);
  const what =
    backend === 'gpu' ? 'WGSL, f32, on the GPU through Dawn' : 'float64 twin, on the CPU';
  console.log(`${output.function} (${what})`);
  console.log(
    table([
      ['#', ...names, 'result'],
      ...calls.map((call, c) => [
        String(c + 1),
        ...names.map((_, k) => argumentCells[c]?.[k] ?? ''),
        formatValue(results[c]),
      ]),
    ]),
  );
}

async function runList(json: boolean): Promise<void> {
  const library = loadShaderLibrary(SHADERS_DIRECTORY);
  const { functionsOf, specFor, UnsupportedSignatureError } = await loadEvaluator();
  const modules = [];
  for (const module of libraryModules(library)) {
    const twins = await loadTwins(module);
    const functions = functionsOf(library, module).map((signature) => {
      const backends: Backend[] = [];
      try {
        specFor(signature);
        backends.push('gpu');
      } catch (error) {
        if (!(error instanceof UnsupportedSignatureError)) throw error;
      }
      if (typeof twins?.[signature.fn] === 'function') backends.push('cpu');
      return { name: signature.fn, signature: signature.text, backends };
    });
    modules.push({ name: module, functions });
  }
  if (json) {
    console.log(JSON.stringify({ modules }, null, 2));
    return;
  }
  const lines: string[] = [];
  for (const module of modules) {
    lines.push(module.name);
    lines.push(
      table(module.functions.map((f) => [`  ${f.backends.join(' ') || '-'}`, f.signature])),
    );
  }
  console.log(lines.join('\n'));
}

async function main(argv: readonly string[]): Promise<number> {
  // `slab` has options of its own (src/cli/slab.ts).
  if (argv[0] === 'slab') return (await import('./slab.ts')).slabCommand(argv.slice(1));
  let parsed;
  try {
    parsed = parseArgs({
      args: [...argv],
      allowPositionals: true,
      options: {
        args: { type: 'string' },
        backend: { type: 'string' },
        json: { type: 'boolean' },
        help: { type: 'boolean', short: 'h' },
        out: { type: 'string' },
        png: { type: 'string' },
        spp: { type: 'string' },
        stats: { type: 'string' },
        kernel: { type: 'string' },
        exposure: { type: 'string' },
      },
    });
  } catch (error) {
    console.error(`scatterbook: ${(error as Error).message}\n\n${USAGE}`);
    return 2;
  }
  const { positionals, values } = parsed;
  const command = positionals[0];
  if (values.help) {
    console.log(USAGE);
    return 0;
  }
  try {
    if (command === 'eval') await runEval(positionals, values);
    else if (command === 'list') await runList(values.json ?? false);
    else if (command === 'render') await runRender(positionals, values, timer);
    else
      throw new UsageError(
        command === undefined ? 'no command' : `unknown command ${JSON.stringify(command)}`,
      );
    return 0;
  } catch (error) {
    if (error instanceof UsageError || error instanceof RenderInputError) {
      console.error(`scatterbook: ${error.message}\n\nRun scatterbook --help for usage.`);
      return 2;
    }
    console.error(`scatterbook: ${(error as Error).message}`);
    return 1;
  }
}

process.exitCode = await main(process.argv.slice(2));
