// The grading core, shared by the page (public checks on navigator.gpu) and the
// instructor's command line (public and hidden checks on Dawn in Node).
//
// A submission goes through: signature check → loop instrumentation → compilation
// (diagnostics mapped back to the student's line and column) → the checks, each one
// dispatch of a generated harness kernel that calls the student's function once per
// GPU thread. The reference solution runs through the same harness, linked with WESL
// against the shader library. A watchdog bounds every GPU wait, and device loss is
// reported instead of thrown.
import { runPipeline } from '../gpu/compute.ts';
import { gpuCore } from '../gpu/core.ts';
import {
  GpuError,
  withErrorScopes,
  type CompilationNote,
  type GpuErrorKind,
} from '../gpu/errors.ts';
import {
  argumentLoads,
  bitsToF32,
  encodeScalar,
  type ScalarType,
} from '../gpu/functionEvaluator.ts';
import { prefixedDeclarations } from '../gpu/libraryDeclarations.ts';
import { linkKernel, type ShaderLibrary } from '../gpu/link.ts';
import { loadExercise } from '../../exercises/index.ts';
import {
  signatureText,
  type CasesCheck,
  type ChiSquareCheck,
  type CheckSpec,
  type ExerciseDefinition,
  type Helpers,
  type MonteCarloCheck,
} from './exercise.ts';
import { casesForSeed } from './checks/generated.ts';
import { runDistributionCheck } from './checks/distribution.ts';
import { runTrackingCheck } from './checks/tracking.ts';
import type { CheckRuntime, RunOutput } from './checks/runtime.ts';
import {
  blankComments,
  GUARD_COUNTER,
  GUARD_FLAG,
  normalizeSource,
  paramTypeText,
  positionMapper,
  prepareSource,
} from './instrument.ts';
import {
  bernoulliMeanZ,
  bernoulliVarianceZ,
  chiSquareEquiprobable,
  mixSeed,
  sampleMoments,
  seededUniforms,
} from './stats.ts';
import { normalCritical } from '../statistics/distributions.ts';
import type { CheckResult, GradeOptions, GradeOutcome, SourceDiagnostic } from './types.ts';
import { withEngineNote } from './engineNotes.ts';
import { DEFAULT_TIMEOUT_MS } from './defaults.ts';

export const DEFAULT_SEED = 20261123;
export { DEFAULT_TIMEOUT_MS };
export const DEFAULT_LOOP_BUDGET = 4096;
const WORKGROUP_SIZE = 64;
/** Words in front of the arguments in the input buffer: call count, seed. */
const HEADER_WORDS = 2;

/** Grading could not continue; becomes the outcome of that status. */
export class GradeStop extends Error {
  constructor(readonly outcome: Exclude<GradeOutcome, { status: 'graded' }>) {
    super(outcome.message);
  }
}

/**
 * A student loop ran past its budget in one check. Only that check fails (the
 * device is fine: the instrumentation stopped the loop), so gradeProgram catches
 * it per check and words the message by the check's visibility.
 */
class LoopBudgetStop extends GradeStop {
  constructor(
    readonly budget: number,
    readonly what: string,
    readonly argsText: string,
  ) {
    super({ status: 'loop-budget', message: loopBudgetMessage(budget, what, argsText) });
  }
}

/** `argsText` is left out for hidden checks so their cases stay secret before publication. */
function loopBudgetMessage(budget: number, what: string, argsText?: string): string {
  return (
    `While ${what}, your loop ran past its budget of ${budget} iterations in one call` +
    (argsText ? ` (arguments ${argsText})` : '') +
    ', so the grader stopped it. ' +
    'Check that every loop ends: its condition must become false, or a `break` must be reached.'
  );
}

/** A program ready to run: the pipeline and where its source came from. */
interface Program {
  pipeline: GPUComputePipeline;
  role: 'student' | 'reference';
}

/** The library's PCG hash (rng.wesl's pcgHash) as sbg_pcgHash, per library. */
const harnessHashes = new WeakMap<ShaderLibrary, string>();

function harnessHash(library: ShaderLibrary): string {
  let text = harnessHashes.get(library);
  if (text === undefined) {
    text = prefixedDeclarations(library, 'rng', ['pcgHash'], 'sbg_');
    harnessHashes.set(library, text);
  }
  return text;
}

/**
 * The kernel that calls the subject once per thread: its arguments read as the
 * function evaluator (src/gpu/functionEvaluator.ts) reads them, after a header of
 * HEADER_WORDS words; the state of a `ptr<function, u32>` parameter seeded with the
 * library's PCG hash, taken from rng.wesl under the harness's sbg_ prefix (a
 * submission may declare any name of its own, even pcgHash).
 */
function harness(exercise: ExerciseDefinition, library: ShaderLibrary): string {
  const subject = exercise.subject;
  const callArgs: string[] = [];
  const args: { type: ScalarType; name: string }[] = [];
  subject.params.forEach((param, index) => {
    if (param.type === 'ptr<function, u32>') {
      callArgs.push('&sbg_state');
      return;
    }
    args.push({ type: param.type, name: `sbg_a${index}` });
    callArgs.push(`sbg_a${index}`);
  });
  const lines = argumentLoads(args, 'sbg_inputs', 'sbg_base');
  let offset = args.length;
  // A hidden medium's parameters: private variables of the helpers, filled from words
  // after the arguments (the student's function never receives them).
  for (const name of exercise.helpers?.extraInputs ?? []) {
    lines.push(`  ${name} = bitcast<f32>(sbg_inputs[sbg_base + ${offset}u]);`);
    offset += 1;
  }
  // Helper call counters, zeroed before the call and written after the result.
  const counters = exercise.helpers?.counters ?? [];
  const outputWords = outputStride(exercise);
  return [
    '@group(0) @binding(0) var<storage, read> sbg_inputs: array<u32>;',
    '@group(0) @binding(1) var<storage, read_write> sbg_outputs: array<u32>;',
    `var<private> ${GUARD_COUNTER}: u32;`,
    `var<private> ${GUARD_FLAG}: u32;`,
    harnessHash(library),
    `@compute @workgroup_size(${WORKGROUP_SIZE})`,
    'fn sbg_main(@builtin(global_invocation_id) sbg_id: vec3u) {',
    '  let sbg_i = sbg_id.x;',
    '  if (sbg_i >= sbg_inputs[0]) { return; }',
    `  let sbg_base = ${HEADER_WORDS}u + sbg_i * ${Math.max(inputStride(exercise), 1)}u;`,
    ...lines,
    '  var sbg_state = sbg_pcgHash(sbg_inputs[1] ^ sbg_pcgHash(sbg_i));',
    `  ${GUARD_COUNTER} = 0u;`,
    `  ${GUARD_FLAG} = 0u;`,
    ...counters.map((name) => `  ${name} = 0u;`),
    `  let sbg_r = ${subject.name}(${callArgs.join(', ')});`,
    `  sbg_outputs[${outputWords}u * sbg_i] = bitcast<u32>(sbg_r);`,
    `  sbg_outputs[${outputWords}u * sbg_i + 1u] = ${GUARD_FLAG};`,
    ...counters.map((name, k) => `  sbg_outputs[${outputWords}u * sbg_i + ${k + 2}u] = ${name};`),
    '}',
  ].join('\n');
}

function argumentCount(exercise: ExerciseDefinition): number {
  return exercise.subject.params.filter((p) => p.type !== 'ptr<function, u32>').length;
}

/** Input words per call: the arguments, then the helpers' extra inputs (all f32). */
function inputStride(exercise: ExerciseDefinition): number {
  return argumentCount(exercise) + (exercise.helpers?.extraInputs?.length ?? 0);
}

/** Output words per call: the result, the loop-guard flag, then the helpers' counters. */
function outputStride(exercise: ExerciseDefinition): number {
  return 2 + (exercise.helpers?.counters?.length ?? 0);
}

/** Resolves after `ms`, or never when ms is not finite. */
function watchdog(ms: number): { promise: Promise<'timeout'>; cancel: () => void } {
  let handle: ReturnType<typeof setTimeout> | undefined;
  const promise = new Promise<'timeout'>((resolve) => {
    handle = setTimeout(() => resolve('timeout'), ms);
  });
  return { promise, cancel: () => clearTimeout(handle) };
}

const lostDevices = new WeakMap<GPUDevice, GPUDeviceLostInfo>();

function deviceLostStop(what: string, info: { message: string; reason: string }): GradeStop {
  return new GradeStop({
    status: 'device-lost',
    message:
      `The GPU device was lost while ${what} (${info.message || info.reason}). ` +
      'Nothing is wrong with the page; reload the GPU and run the checks again.',
  });
}

/**
 * Awaits GPU work with a watchdog: `timeout` after `timeoutMs`, `device-lost` when
 * the device is lost before the work completes (or the work fails because of it).
 * Exported for the tests.
 */
export async function withDeviceGuards<T>(
  device: GPUDevice,
  timeoutMs: number,
  what: string,
  work: Promise<T>,
): Promise<T> {
  const timer = watchdog(timeoutMs);
  const lost = device.lost.then((info) => {
    lostDevices.set(device, info);
    return { lost: info };
  });
  try {
    const result = await Promise.race([
      work.then(
        (value) => ({ value }),
        (error: unknown) => ({ error }),
      ),
      timer.promise,
      lost,
    ]);
    if (result === 'timeout') {
      throw new GradeStop({
        status: 'timeout',
        message:
          `The GPU did not finish ${what} within ${(timeoutMs / 1000).toFixed(1)} s, so grading ` +
          'stopped. Look for a loop that does far more work than the exercise needs.',
      });
    }
    if ('lost' in result) throw deviceLostStop(what, result.lost);
    if ('error' in result) {
      const info = lostDevices.get(device);
      if (info) throw deviceLostStop(what, info);
      throw result.error;
    }
    return result.value;
  } finally {
    timer.cancel();
  }
}

/** Every wait on the device for `what`, under the watchdog and the device-loss guard. */
function guarded(device: GPUDevice, timeoutMs: number, what: string) {
  return <T>(promise: Promise<T>): Promise<T> => withDeviceGuards(device, timeoutMs, what, promise);
}

/**
 * The compiler's messages for each code a device has compiled. The GPU core caches the
 * module, and asking a cached module, already used by pipelines and dispatches, for its
 * compilation info again took 20 s in Chromium on SwiftShader (measured: the second
 * check's getCompilationInfo; a false `timeout` for a correct solution). The messages
 * of a given code never change, so they are kept with it and asked for once.
 */
const compiledNotesByDevice = new WeakMap<GPUDevice, Map<string, readonly CompilationNote[]>>();
function compiledNotes(device: GPUDevice): Map<string, readonly CompilationNote[]> {
  let notes = compiledNotesByDevice.get(device);
  if (!notes) {
    notes = new Map();
    compiledNotesByDevice.set(device, notes);
  }
  // Bounded like the core's caches: a page that grades many submissions does not grow it.
  if (notes.size > 192) notes.clear();
  return notes;
}

async function compilerNotes(
  device: GPUDevice,
  code: string,
  what: string,
  wait: <T>(promise: Promise<T>) => Promise<T>,
): Promise<readonly CompilationNote[]> {
  let notes: readonly CompilationNote[];
  try {
    const module = await withErrorScopes(device, what, () => gpuCore(device).shaderModule(code), {
      wait,
    });
    const info = await wait(module.getCompilationInfo());
    notes = info.messages
      .filter((m) => m.type !== 'info')
      .map((m) => ({ type: m.type, line: m.lineNum, column: m.linePos, message: m.message }));
  } catch (error) {
    // A module that does not compile is a validation error with the compiler's messages
    // (any other GPU error is the grader's and propagates).
    if (!(error instanceof GpuError) || error.kind !== 'validation') throw error;
    notes = error.compilation.some((note) => note.type === 'error')
      ? error.compilation
      : [...error.compilation, { type: 'error', line: 0, column: 0, message: error.detail }];
  }
  return notes;
}

/**
 * Compiles `code` through the GPU core (a module is cached by its code); compiler
 * messages become SourceDiagnostics through `map` (null: not the student's).
 */
async function compile(
  device: GPUDevice,
  code: string,
  map: (line: number, column: number) => { line: number; column: number } | null,
  timeoutMs: number,
): Promise<{ diagnostics: SourceDiagnostic[] }> {
  const what = 'compiling your shader';
  const wait = guarded(device, timeoutMs, what);
  let notes = compiledNotes(device).get(code);
  if (!notes) {
    notes = await compilerNotes(device, code, what, wait);
    compiledNotes(device).set(code, notes);
  }
  const diagnostics: SourceDiagnostic[] = [];
  for (const note of notes) {
    const mapped = map(note.line, note.column);
    diagnostics.push({
      line: mapped?.line ?? 0,
      column: mapped?.column ?? 0,
      message: mapped ? withEngineNote(note.message) : `(in the grader's harness) ${note.message}`,
      severity: note.type === 'error' ? 'error' : 'warning',
    });
  }
  return { diagnostics };
}

/** The harness's pipeline for compiled `code` (from the core's cache), or the device's refusal. */
async function createPipeline(
  device: GPUDevice,
  code: string,
  timeoutMs = DEFAULT_TIMEOUT_MS,
): Promise<{ pipeline: GPUComputePipeline; error: null } | { pipeline: null; error: string }> {
  const what = 'creating the pipeline';
  try {
    const pipeline = await withErrorScopes(
      device,
      what,
      () => gpuCore(device).computePipeline({ code, entryPoint: 'sbg_main' }),
      { wait: guarded(device, timeoutMs, what) },
    );
    return { pipeline, error: null };
  } catch (error) {
    if (error instanceof GpuError && error.kind === 'validation')
      return { pipeline: null, error: error.detail };
    throw error;
  }
}

function countLines(text: string): number {
  return text.split('\n').length;
}

/**
 * Imports are not linked for submissions: the helpers the statement allows are
 * already in front of the code. When a submission imports something else, say so.
 */
function importNote(source: string, exercise: ExerciseDefinition): string {
  const allowed = new Set((exercise.helpers?.imports ?? []).map((line) => line.trim()));
  const imports = blankComments(source).match(/^[ \t]*import[^;\n]*;?/gm) ?? [];
  const other = imports.map((line) => line.trim()).filter((line) => !allowed.has(line));
  if (other.length === 0) return '';
  // The student's text, shortened: a hostile file may hold thousands of import lines or
  // one with 60,000 blanks, which the report need not repeat.
  const shown = other
    .slice(0, 3)
    .map((line) => line.replace(/[ \t]+/g, ' '))
    .map((line) => (line.length > 80 ? `${line.slice(0, 77)}...` : line));
  if (other.length > shown.length) shown.push(`(${other.length - shown.length} more)`);
  const names = [...allowed].map((line) => line.replace(/^import\s+|;$/g, ''));
  return (
    ` (Imports other than the helpers this exercise provides are ignored: ${shown.join(' ')}. ` +
    `Available: ${names.length > 0 ? names.join(', ') : 'none; plain WGSL built-ins only'}.)`
  );
}

interface PreparedStudent {
  program: Program;
  warnings: SourceDiagnostic[];
}

/** Signature check, instrumentation and compilation of a submission. */
async function prepareStudent(
  device: GPUDevice,
  library: ShaderLibrary,
  exercise: ExerciseDefinition,
  source: string,
  timeoutMs: number,
): Promise<PreparedStudent> {
  const expected = signatureText(exercise.subject);
  // Size cap, normalisation (BOM, line breaks), refusals and loop bounds, in linear
  // time and before anything reaches the compiler; the compiler sees the text the
  // scans saw.
  const prepared = prepareSource(source, exercise.loopBudget ?? DEFAULT_LOOP_BUDGET);
  if (!prepared.ok) throw new GradeStop({ status: 'rejected', message: prepared.message });
  const { instrumented, functions } = prepared;
  const helpers = exercise.helpers;
  const prelude = helpers
    ? await linkKernel(library, [...helpers.imports, helpers.wgsl].join('\n'))
    : '';
  const linesBefore = prelude ? countLines(prelude) : 0;
  const head = prelude ? `${prelude}\n` : '';
  const mapper = (insertions: typeof instrumented.insertions) =>
    positionMapper(linesBefore, prepared.lineCount, insertions);
  // 1. The submission alone (with the helpers and the guard variables), so that its
  //    own errors are reported before any signature or harness error.
  const guards = `var<private> ${GUARD_COUNTER}: u32;\nvar<private> ${GUARD_FLAG}: u32;`;
  const alone = await compile(
    device,
    `${head}${instrumented.source}\n${guards}\n`,
    mapper(instrumented.insertions),
    timeoutMs,
  );
  const errors = alone.diagnostics.filter((d) => d.severity === 'error');
  if (errors.length > 0) {
    const first = errors[0] as SourceDiagnostic;
    throw new GradeStop({
      status: 'compile-error',
      diagnostics: alone.diagnostics,
      message:
        `Your shader does not compile: line ${first.line}, column ${first.column}: ${first.message}` +
        importNote(normalizeSource(source), exercise),
    });
  }
  // 2. The signature, read from the source.
  const found = functions.find((f) => f.name === exercise.subject.name);
  if (!found) {
    const names = functions.map((f) => f.name).join(', ');
    throw new GradeStop({
      status: 'wrong-signature',
      message:
        `The grader calls \`${expected}\`, but your code has no function named ` +
        `${exercise.subject.name}${names ? ` (it defines ${names})` : ''}.`,
    });
  }
  const want = exercise.subject.params;
  const typesMatch =
    found.params.length === want.length &&
    found.params.every((p, i) => p.type === paramTypeText((want[i] as (typeof want)[number]).type));
  if (!typesMatch || found.result !== exercise.subject.result) {
    const got = `fn ${found.name}(${found.params.map((p) => `${p.name}: ${p.type}`).join(', ')})${found.result ? ` -> ${found.result}` : ''}`;
    throw new GradeStop({
      status: 'wrong-signature',
      message: `The grader calls \`${expected}\`, but your function is \`${got}\`. Keep the signature of the starter code.`,
    });
  }
  // 3. The submission with the harness after it (its line numbers stay the same).
  const fullCode = `${head}${instrumented.source}\n${harness(exercise, library)}\n`;
  const full = await compile(device, fullCode, mapper(instrumented.insertions), timeoutMs);
  const fullErrors = full.diagnostics.filter((d) => d.severity === 'error');
  if (fullErrors.length > 0) {
    throw new GradeStop({
      status: 'compile-error',
      diagnostics: full.diagnostics,
      message: `Your shader does not compile with the grader's harness: ${fullErrors[0]?.message ?? ''}`,
    });
  }
  const { pipeline, error } = await createPipeline(device, fullCode, timeoutMs);
  if (error !== null) {
    // With bindings and entry points refused this is rare (e.g. workgroup memory past
    // the device's limits); it is the student's shader, so an outcome, never a throw.
    throw new GradeStop({
      status: 'compile-error',
      diagnostics: [{ line: 0, column: 0, message: error, severity: 'error' }],
      message: `Your shader compiled but the pipeline could not be created: ${error}`,
    });
  }
  return {
    program: { pipeline, role: 'student' },
    warnings: alone.diagnostics.filter((d) => d.severity === 'warning'),
  };
}

/**
 * The reference solution linked with WESL against the library. Not cached here: the
 * link (src/gpu/link.ts) and the module and pipeline (the GPU core) are cached by
 * their text.
 */
async function prepareReference(
  device: GPUDevice,
  library: ShaderLibrary,
  exercise: ExerciseDefinition,
  timeoutMs: number,
): Promise<Program> {
  const importLine = /^[ \t]*import[^;\n]*;[ \t]*$/gm;
  const imports = new Set([
    ...(exercise.helpers?.imports ?? []),
    ...(exercise.reference.match(importLine) ?? []).map((s) => s.trim()),
  ]);
  const root = [
    ...imports,
    exercise.reference.replace(importLine, ''),
    exercise.helpers?.wgsl ?? '',
    harness(exercise, library),
  ].join('\n');
  const code = await linkKernel(library, root);
  const { diagnostics } = await compile(device, code, () => null, timeoutMs);
  const error = diagnostics.find((d) => d.severity === 'error');
  if (error) throw new Error(`reference solution of ${exercise.id}: ${error.message}`);
  const created = await createPipeline(device, code);
  if (created.error !== null) throw new Error(`reference of ${exercise.id}: ${created.error}`);
  return { pipeline: created.pipeline, role: 'reference' };
}

/**
 * A dispatch the device refused, as an outcome (never a plain Error): a validation
 * error of the student's program (e.g. a pipeline layout the harness's bind group does
 * not match) is the submission's — 'rejected'; anything else (out of memory, or the
 * reference refused) is the grader's — 'internal-error'.
 */
function dispatchStop(
  program: Program,
  what: string,
  kind: GpuErrorKind,
  detail: string,
): GradeStop {
  if (program.role === 'student' && kind === 'validation') {
    return new GradeStop({
      status: 'rejected',
      message:
        `The grader could not run your shader while ${what}: ${detail} ` +
        'Your code may use only its parameters, the provided helpers and module-scope ' +
        '`const` or `var<private>` declarations.',
    });
  }
  return new GradeStop({
    status: 'internal-error',
    message: `The GPU refused the grader's dispatch (${kind}) while ${what}: ${detail}`,
  });
}

/** Runs `calls` through a program; one f32 result per call. */
async function run(
  device: GPUDevice,
  exercise: ExerciseDefinition,
  program: Program,
  calls: readonly (readonly number[])[],
  seed: number,
  timeoutMs: number,
  what: string,
): Promise<number[]> {
  return (await runDetailed(device, exercise, program, calls, seed, timeoutMs, what)).values;
}

/**
 * Runs `calls` (arguments, then the helpers' extra inputs) through a program linked
 * with `exercise.helpers`: one f32 result and the helpers' counters per call.
 */
async function runDetailed(
  device: GPUDevice,
  exercise: ExerciseDefinition,
  program: Program,
  calls: readonly (readonly number[])[],
  seed: number,
  timeoutMs: number,
  what: string,
): Promise<RunOutput> {
  const types = [
    ...exercise.subject.params.flatMap((p) => (p.type === 'ptr<function, u32>' ? [] : [p.type])),
    ...(exercise.helpers?.extraInputs ?? []).map(() => 'f32' as const),
  ];
  const stride = Math.max(inputStride(exercise), 1);
  const words = outputStride(exercise);
  const inputs = new Uint32Array(HEADER_WORDS + calls.length * stride);
  inputs[0] = calls.length;
  inputs[1] = seed >>> 0;
  calls.forEach((args, i) => {
    types.forEach((type, k) => {
      inputs[HEADER_WORDS + i * stride + k] = encodeScalar(type, args[k] ?? 0);
    });
  });
  try {
    // The core's dispatch: pooled buffers, every wait under the watchdog; an error the
    // device reports becomes the outcome dispatchStop chooses for its kind.
    const { output: data } = await runPipeline(
      device,
      program.pipeline,
      {
        inputs: [inputs],
        outputWords: Math.max(words, calls.length * words),
        workgroups: [Math.max(1, Math.ceil(calls.length / WORKGROUP_SIZE))],
      },
      { what, wait: guarded(device, timeoutMs, what), timed: false },
    ).catch((error: unknown) => {
      throw error instanceof GpuError
        ? dispatchStop(program, what, error.kind, error.detail)
        : error;
    });
    const results: number[] = [];
    const counters = (exercise.helpers?.counters ?? []).map(() => new Array<number>(calls.length));
    let budgetHit = -1;
    for (let i = 0; i < calls.length; i++) {
      results.push(bitsToF32(data[words * i] ?? 0));
      if (budgetHit < 0 && data[words * i + 1] !== 0) budgetHit = i;
      counters.forEach((counter, k) => {
        counter[i] = data[words * i + 2 + k] ?? 0;
      });
    }
    if (budgetHit >= 0 && program.role === 'student') {
      const budget = exercise.loopBudget ?? DEFAULT_LOOP_BUDGET;
      throw new LoopBudgetStop(budget, what, formatArgs(exercise, calls[budgetHit] ?? []));
    }
    return { values: results, counters };
  } catch (error) {
    // The student's dispatch ran past the watchdog: with every loop within its budget,
    // that is code doing far more work per call than the exercise needs (a loop body
    // of thousands of statements), not the grader's failure. It ends grading (the
    // device is still busy with that dispatch) as the student's outcome, so it is not
    // reported as "will be regraded" forever.
    if (
      program.role === 'student' &&
      error instanceof GradeStop &&
      error.outcome.status === 'timeout'
    )
      throw new GradeStop({
        status: 'loop-budget',
        message:
          `While ${what}, your function did not finish ${calls.length} calls within ` +
          `${(timeoutMs / 1000).toFixed(1)} s on the grader's GPU, so the grader stopped it. ` +
          'Each call may do only as much work as the exercise needs: look for a loop ' +
          'whose body does far more than one step.',
      });
    throw error;
  }
}

function formatNumber(value: number): string {
  if (Number.isNaN(value)) return 'NaN';
  if (!Number.isFinite(value)) return value > 0 ? 'inf' : '-inf';
  if (value === 0) return '0';
  const abs = Math.abs(value);
  return abs >= 1e-3 && abs < 1e6 ? String(Number(value.toPrecision(7))) : value.toExponential(6);
}

function formatArgs(exercise: ExerciseDefinition, args: readonly number[]): string {
  const names = exercise.subject.params
    .filter((p) => p.type !== 'ptr<function, u32>')
    .map((p) => p.name);
  return names.map((name, i) => `${name} = ${formatNumber(args[i] ?? 0)}`).join(', ');
}

/**
 * A sample's "Arguments" cell: the case's label, then the arguments unless the label
 * already states every one of them ("g = 0.7, μ = -1" for (0.7, −1) would otherwise
 * read "g = 0.7, μ = -1: g = 0.7, mu = -1").
 */
export function caseArguments(label: string, formatted: string, args: readonly number[]): string {
  const assignments = label.split('=').length - 1;
  const numbers = (label.match(/-?\d+(?:\.\d+)?(?:e-?\d+)?/gi) ?? []).map(Number);
  const statesAll =
    assignments === args.length &&
    args.every((arg) => numbers.some((n) => n === Number(arg.toPrecision(7))));
  return statesAll ? label : `${label}: ${formatted}`;
}

function withinTolerance(student: number, reference: number, rtol: number, atol: number): boolean {
  if (Number.isNaN(student)) return false;
  if (Number.isNaN(reference)) return false;
  if (!Number.isFinite(reference) || !Number.isFinite(student)) return student === reference;
  return Math.abs(student - reference) <= atol + rtol * Math.abs(reference);
}

interface CheckContext {
  device: GPUDevice;
  library: ShaderLibrary;
  exercise: ExerciseDefinition;
  student: Program;
  timeoutMs: number;
  seed: number;
  /** The same program linked with other helpers (e.g. a hidden medium), compiled once. */
  programFor: (helpers: Helpers) => Promise<Program>;
}

const sharedRuns = new WeakMap<Program, Map<string, Promise<RunOutput>>>();

/** The runtime a check runner in checks/ gets: runs with any helpers, shared by key. */
function checkRuntime(ctx: CheckContext): CheckRuntime {
  return {
    exercise: ctx.exercise,
    seed: ctx.seed,
    formatArgs: (args) => formatArgs(ctx.exercise, args),
    formatNumber,
    run: async (calls, streamSeed, what, helpers, shareKey) => {
      const linked = helpers ? { ...ctx.exercise, helpers } : ctx.exercise;
      const program = helpers ? await ctx.programFor(helpers) : ctx.student;
      const go = (): Promise<RunOutput> =>
        runDetailed(ctx.device, linked, program, calls, streamSeed, ctx.timeoutMs, what);
      if (shareKey === undefined) return go();
      let perProgram = sharedRuns.get(program);
      if (!perProgram) {
        perProgram = new Map();
        sharedRuns.set(program, perProgram);
      }
      const key = `${streamSeed}\n${shareKey}`;
      let shared = perProgram.get(key);
      if (!shared) {
        shared = go();
        perProgram.set(key, shared);
        // A failed run (loop budget, timeout) is not kept: the next check reports it too.
        shared.catch(() => perProgram?.delete(key));
      }
      return shared;
    },
  };
}

async function runCasesCheck(
  ctx: CheckContext,
  check: CasesCheck,
  visibility: 'public' | 'hidden',
): Promise<CheckResult> {
  const calls = check.cases.map((c) => c.args);
  const what = `running the check "${check.name}"`;
  const reference = await prepareReference(ctx.device, ctx.library, ctx.exercise, ctx.timeoutMs);
  const expected = await run(
    ctx.device,
    ctx.exercise,
    reference,
    calls,
    ctx.seed,
    ctx.timeoutMs,
    what,
  );
  const got = await run(
    ctx.device,
    ctx.exercise,
    ctx.student,
    calls,
    ctx.seed,
    ctx.timeoutMs,
    what,
  );
  const failing = check.cases.findIndex(
    (_, i) => !withinTolerance(got[i] ?? NaN, expected[i] ?? NaN, check.rtol, check.atol),
  );
  const samples = check.cases.map((c, i) => ({
    args: caseArguments(c.label, formatArgs(ctx.exercise, c.args), c.args),
    student: formatNumber(got[i] ?? NaN),
    reference: formatNumber(expected[i] ?? NaN),
  }));
  const figure = check.figure
    ? {
        kind: 'series' as const,
        x: check.cases.map((c) => c.args[check.figure?.argIndex ?? 0] ?? 0),
        xLabel: check.figure.xLabel,
        student: got,
        reference: expected,
      }
    : undefined;
  const pass = failing < 0;
  let message = `All ${check.cases.length} cases agree with the reference within ${check.rtol} relative + ${check.atol} absolute.`;
  if (!pass) {
    const bad = check.cases[failing] as (typeof check.cases)[number];
    const value = got[failing] ?? NaN;
    const nan = Number.isNaN(value) ? ' Your function returned NaN (not a number) here. ' : ' ';
    message =
      `${bad.message ?? check.message}${nan}First failing case: ${bad.label} ` +
      `(${formatArgs(ctx.exercise, bad.args)}): yours ${formatNumber(value)}, ` +
      `reference ${formatNumber(expected[failing] ?? NaN)}; tolerance ${check.rtol} relative + ${check.atol} absolute.`;
  }
  return {
    name: check.name,
    visibility,
    verdict: pass ? 'pass' : 'fail',
    points: pass ? check.points : 0,
    maxPoints: check.points,
    message,
    samples,
    ...(figure ? { figure } : {}),
  };
}

async function runChiSquareCheck(
  ctx: CheckContext,
  check: ChiSquareCheck,
  visibility: 'public' | 'hidden',
  index: number,
): Promise<CheckResult> {
  // Stratified uniforms: one ξ in each of n equal strata, jittered by the seed. For
  // a monotone inverse-CDF sampler each equiprobable bin then receives n/bins ± 1
  // samples whatever the seed, so the reference's statistic is ≤ bins²/n, far
  // below any critical value used here; the test stays a valid (conservative) χ² test
  // for any other sampler.
  const uniform = seededUniforms(mixSeed(ctx.seed, index));
  const calls: number[][] = [];
  for (let k = 0; k < check.n; k++) {
    const xi = Math.min(Math.fround((k + uniform()) / check.n), 1 - 2 ** -24);
    calls.push(check.args(xi));
  }
  const what = `running the check "${check.name}"`;
  const got = await run(
    ctx.device,
    ctx.exercise,
    ctx.student,
    calls,
    ctx.seed,
    ctx.timeoutMs,
    what,
  );
  const bad = got.findIndex((v) => !Number.isFinite(v));
  const test = chiSquareEquiprobable(
    got.filter((v) => Number.isFinite(v)),
    check.cdf,
    check.bins,
    check.alpha,
  );
  const edges = Array.from({ length: check.bins + 1 }, (_, j) => check.inverseCdf(j / check.bins));
  const pass = bad < 0 && test.statistic <= test.critical;
  const summary =
    `χ² = ${test.statistic.toFixed(2)} with ${test.degreesOfFreedom} degrees of freedom ` +
    `(critical value ${test.critical.toFixed(2)} at significance ${check.alpha}; p = ${test.pValue.toExponential(2)}), ` +
    `${check.n} samples in ${check.bins} equiprobable bins.`;
  const message = pass
    ? `Your samples follow the analytic distribution: ${summary}`
    : bad >= 0
      ? `${check.message} Your function returned ${formatNumber(got[bad] ?? NaN)} for ${formatArgs(ctx.exercise, calls[bad] ?? [])}.`
      : `${check.message} ${summary}`;
  return {
    name: check.name,
    visibility,
    verdict: pass ? 'pass' : 'fail',
    points: pass ? check.points : 0,
    maxPoints: check.points,
    message,
    figure: {
      kind: 'histogram',
      edges,
      observed: test.observed,
      expected: test.expected,
      xLabel: check.xLabel,
    },
  };
}

const monteCarloRuns = new WeakMap<Program, Map<string, Promise<number[]>>>();

async function runMonteCarloCheck(
  ctx: CheckContext,
  check: MonteCarloCheck,
  visibility: 'public' | 'hidden',
): Promise<CheckResult> {
  // The mean and the variance checks of the same arguments share one run.
  let perProgram = monteCarloRuns.get(ctx.student);
  if (!perProgram) {
    perProgram = new Map();
    monteCarloRuns.set(ctx.student, perProgram);
  }
  const key = `${ctx.seed}\n${check.n}\n${check.args.join(',')}`;
  let values = perProgram.get(key);
  if (!values) {
    const calls = Array.from({ length: check.n }, () => check.args);
    values = run(
      ctx.device,
      ctx.exercise,
      ctx.student,
      calls,
      // One stream family per argument list, so different cases are independent.
      check.args.reduce(
        (seed, arg) => mixSeed(seed, Math.round(arg * 1e6)),
        mixSeed(ctx.seed, check.n),
      ),
      ctx.timeoutMs,
      `running the check "${check.name}"`,
    );
    perProgram.set(key, values);
  }
  const got = await values;
  const bad = got.findIndex((v) => !Number.isFinite(v));
  const m = sampleMoments(got);
  const critical = normalCritical(check.alpha);
  const z =
    check.kind === 'mean'
      ? bernoulliMeanZ(m, check.expected)
      : bernoulliVarianceZ(m, check.expected);
  const pass = bad < 0 && Math.abs(z) <= critical;
  const quantity =
    check.kind === 'mean'
      ? `mean ${formatNumber(m.mean)} against exp(−τ) = ${formatNumber(check.expected)}`
      : `variance ${formatNumber(m.variance)} against T(1 − T) = ${formatNumber(check.expected * (1 - check.expected))}`;
  const nonBinary = got.filter((v) => v !== 0 && v !== 1).length;
  const summary =
    `${check.n} calls (${formatArgs(ctx.exercise, check.args)}): ${quantity}, ` +
    `z = ${z.toFixed(2)} (two-sided, pass when |z| ≤ ${critical.toFixed(2)}, significance ${check.alpha})` +
    (nonBinary > 0 ? `; ${nonBinary} of the results were neither 0 nor 1.` : '.');
  const message = pass
    ? `Consistent with the exact value: ${summary}`
    : bad >= 0
      ? `${check.message} Your function returned ${formatNumber(got[bad] ?? NaN)}.`
      : `${check.message} ${summary}`;
  return {
    name: check.name,
    visibility,
    verdict: pass ? 'pass' : 'fail',
    points: pass ? check.points : 0,
    maxPoints: check.points,
    message,
    samples: [
      {
        args: formatArgs(ctx.exercise, check.args),
        student: check.kind === 'mean' ? formatNumber(m.mean) : formatNumber(m.variance),
        reference:
          check.kind === 'mean'
            ? formatNumber(check.expected)
            : formatNumber(check.expected * (1 - check.expected)),
      },
    ],
  };
}

function runCheck(
  ctx: CheckContext,
  check: CheckSpec,
  visibility: 'public' | 'hidden',
  index: number,
): Promise<CheckResult> {
  switch (check.kind) {
    case 'cases':
      return runCasesCheck(ctx, check, visibility);
    case 'chi-square':
      return runChiSquareCheck(ctx, check, visibility, index);
    case 'mean':
    case 'variance':
      return runMonteCarloCheck(ctx, check, visibility);
    case 'generated-cases':
      return runCasesCheck(ctx, casesForSeed(check, ctx.seed), visibility);
    case 'distribution':
      return runDistributionCheck(checkRuntime(ctx), check, visibility);
    case 'tracking':
      return runTrackingCheck(checkRuntime(ctx), check, visibility);
  }
}

async function gradeProgram(
  device: GPUDevice,
  library: ShaderLibrary,
  exercise: ExerciseDefinition,
  prepare: (timeoutMs: number, helpers?: Helpers) => Promise<Program>,
  options: GradeOptions,
): Promise<GradeOutcome> {
  const seed = (options.seed ?? DEFAULT_SEED) >>> 0;
  const timeoutMs = options.timeoutMs ?? DEFAULT_TIMEOUT_MS;
  const checks: { check: CheckSpec; visibility: 'public' | 'hidden' }[] = exercise.checks.map(
    (check) => ({ check, visibility: 'public' }),
  );
  if (options.which === 'all') {
    if (!exercise.hiddenChecks) {
      throw new Error(
        `exercise ${exercise.id} was loaded without its hidden checks; load it with loadFullExercise()`,
      );
    }
    for (const check of exercise.hiddenChecks) checks.push({ check, visibility: 'hidden' });
  }
  try {
    const student = await prepare(timeoutMs);
    const linked = new Map<string, Promise<Program>>();
    const programFor = (helpers: Helpers): Promise<Program> => {
      const key = JSON.stringify(helpers);
      let program = linked.get(key);
      if (!program) {
        program = prepare(timeoutMs, helpers);
        linked.set(key, program);
      }
      return program;
    };
    const ctx: CheckContext = { device, library, exercise, student, timeoutMs, seed, programFor };
    const results: CheckResult[] = [];
    let overruns = 0;
    let budget = exercise.loopBudget ?? DEFAULT_LOOP_BUDGET;
    for (const [index, { check, visibility }] of checks.entries()) {
      options.signal?.throwIfAborted();
      try {
        results.push(await runCheck(ctx, check, visibility, index));
      } catch (error) {
        if (options.signal?.aborted) throw error;
        if (!(error instanceof LoopBudgetStop)) {
          // A timeout, device loss or grader error still ends grading (the device may be
          // busy or gone), but the top-level message must not name a hidden check
          // before publication.
          const stop =
            error instanceof GradeStop
              ? error
              : internalErrorStop(error, `running "${check.name}"`);
          if (visibility === 'public') throw stop;
          throw new GradeStop({
            ...stop.outcome,
            message: stop.outcome.message
              .split(`the check "${check.name}"`)
              .join('a hidden check')
              .split(`"${check.name}"`)
              .join('a hidden check'),
          });
        }
        // Only this check fails; the others are still scored. A hidden check's
        // arguments are left out of its message.
        overruns++;
        budget = error.budget;
        results.push({
          name: check.name,
          visibility,
          verdict: 'fail',
          points: 0,
          maxPoints: check.points,
          message: loopBudgetMessage(
            error.budget,
            error.what,
            visibility === 'public' ? error.argsText : undefined,
          ),
        });
      }
      options.onProgress?.(index + 1, checks.length);
    }
    if (overruns > 0 && overruns === checks.length) {
      // Every check overran: nothing was graded, which is the endless-loop outcome.
      return {
        status: 'loop-budget',
        message:
          `Your loop ran past its budget of ${budget} iterations in every check, so the ` +
          'grader stopped it. Check that every loop ends: its condition must become false, ' +
          'or a `break` must be reached.',
      };
    }
    return {
      status: 'graded',
      checks: results,
      score: results.reduce((sum, r) => sum + r.points, 0),
      maxScore: results.reduce((sum, r) => sum + r.maxPoints, 0),
      seed,
    };
  } catch (error) {
    if (error instanceof GradeStop) return error.outcome;
    // The page's cancel button aborts; its runner reports that itself.
    if (options.signal?.aborted) throw error;
    return internalErrorStop(error, 'preparing the checks').outcome;
  }
}

/**
 * An exception in the grader (not a GradeStop) as an 'internal-error' outcome: a
 * failure on the grader's side, which reports present as "grading failed, will be
 * regraded", never as the student's score.
 */
function internalErrorStop(error: unknown, where: string): GradeStop {
  const detail = error instanceof Error ? `${error.name}: ${error.message}` : String(error);
  return new GradeStop({
    status: 'internal-error',
    message: `The grader failed while ${where} (${detail}). This is not a problem with your code.`,
  });
}

/**
 * Grades `source` (the student's WGSL) for an exercise (its id, or the definition
 * loadExercise() returned). `options.which`: 'public' runs the public checks (the
 * page); 'all' also the hidden ones (needs a definition with hiddenChecks, as
 * loadFullExercise() in src/grading/node.ts returns). Never throws: compile errors,
 * refused submissions, wrong signatures and endless loops come back as the outcome's
 * status, and so do the grader's own failures (GPU timeouts, device loss, and any
 * exception — an unknown exercise, a broken reference — as 'internal-error'). Only a
 * run aborted through `options.signal` rejects.
 */
export async function gradeSubmission(
  device: GPUDevice,
  library: ShaderLibrary,
  exercise: string | ExerciseDefinition,
  source: string,
  options: GradeOptions,
): Promise<GradeOutcome> {
  try {
    const definition = typeof exercise === 'string' ? await loadExercise(exercise) : exercise;
    return await gradeProgram(
      device,
      library,
      definition,
      async (timeoutMs, helpers) => {
        const linked = helpers ? { ...definition, helpers } : definition;
        const prepared = await prepareStudent(device, library, linked, source, timeoutMs);
        return prepared.program;
      },
      options,
    );
  } catch (error) {
    if (options.signal?.aborted) throw error;
    return internalErrorStop(error, 'setting up the exercise').outcome;
  }
}

/**
 * Grades the reference solution itself with the same checks: deterministic checks
 * compare it with itself (they must pass trivially), statistical checks test it
 * against the analytic answer, so this is the grader's own sanity check.
 */
export function gradeReference(
  device: GPUDevice,
  library: ShaderLibrary,
  exercise: ExerciseDefinition,
  options: GradeOptions,
): Promise<GradeOutcome> {
  return gradeProgram(
    device,
    library,
    exercise,
    (timeoutMs, helpers) =>
      prepareReference(device, library, helpers ? { ...exercise, helpers } : exercise, timeoutMs),
    options,
  );
}
