// The table-driven harness that holds every WGSL library function against its
// float64 TypeScript twin (DESIGN.md contract 1), in the manner of the WebGPU CTS:
// a list of cases is packed into one buffer, one generated compute kernel calls
// the function once per case, and each case is compared with the twin under a
// stated tolerance.
//
// Adding a module means adding a table, not a harness:
//
//   describeShaderFunction({
//     module: 'transmittance', fn: 'transmittanceHomogeneous',
//     args: ['f32', 'f32'], result: 'f32',
//     twin: transmittanceHomogeneous,
//     tolerance: { relative: 1e-5, absolute: 1e-37, reason: 'exp has 3 + 2|x| ULP in WGSL' },
//     cases: [{ name: 'σt = 0 gives T = 1', args: [0, 1], expected: 1 }],
//   });
//
// Inputs are rounded to f32 before both sides see them (physics.md §10: the
// oracle works on the same f32 inputs). Every f32 output must be finite.
import { beforeAll, describe, expect, it } from 'vitest';
import { linkKernel } from '../../src/gpu/link.ts';
import { runCompute } from '../../src/gpu/compute.ts';
import { nodeDevice } from './nodeGpu.ts';
import { SHADER_LIBRARY } from './shaderLibrary.ts';
import { bitsToF32, f32ToBits, ulpDistance } from './f32.ts';

export type ScalarType = 'f32' | 'u32' | 'i32';
/** `f32[N]` stands for the WGSL `array<f32, N>`. */
export type ArgumentType = ScalarType | `f32[${number}]`;
export type ResultType = ScalarType | 'vec2f' | 'vec3f' | 'vec4f';

export type Argument = number | readonly number[];

export interface Tolerance {
  /** Pass when |gpu − twin| ≤ relative·|twin| … */
  relative?: number;
  /** … or |gpu − twin| ≤ absolute … */
  absolute?: number;
  /** … or the two are within this many f32 ULPs. */
  ulps?: number;
  /** Why this tolerance: which operations, which WGSL accuracy bound (physics.md §10). */
  reason: string;
}

export interface ShaderCase {
  name: string;
  args: readonly Argument[];
  /** A published value (physics.md) that both implementations must also meet. */
  expected?: number | readonly number[];
  /** Overrides the table's tolerance for this case. */
  tolerance?: Tolerance;
}

export interface ShaderFunctionTable {
  /** Module path under shaders/ without extension, e.g. `transmittance`. */
  module: string;
  /** Function name, the same in WGSL and in the twin. */
  fn: string;
  args: readonly ArgumentType[];
  result: ResultType;
  /** The float64 twin, called with the f32-rounded arguments. */
  twin: (...args: never[]) => number | readonly number[];
  tolerance: Tolerance;
  cases: readonly ShaderCase[];
  /**
   * For functions that cannot be called with plain values (pointer arguments):
   * WGSL source of `fn caseUnderTest(...) -> RESULT` that wraps the call, and the
   * library symbols it imports. The twin must compute the same thing.
   */
  wrapper?: { wgsl: string; imports: readonly string[] };
}

const WORKGROUP_SIZE = 64;

function argumentWords(type: ArgumentType): number {
  const match = /^f32\[(\d+)\]$/.exec(type);
  return match ? Number(match[1]) : 1;
}

function resultWords(type: ResultType): number {
  return type === 'vec2f' ? 2 : type === 'vec3f' ? 3 : type === 'vec4f' ? 4 : 1;
}

function encodeScalar(type: ScalarType | 'f32', value: number): number {
  if (type === 'f32') return f32ToBits(value);
  if (type === 'i32') return (value | 0) >>> 0;
  return value >>> 0;
}

/** Rounds an argument as the GPU will see it. */
function asGpuSees(type: ArgumentType, value: Argument): Argument {
  if (Array.isArray(value)) return value.map((v) => Math.fround(v));
  if (type === 'f32') return Math.fround(value as number);
  return value;
}

export function generateKernel(table: ShaderFunctionTable, caseCount: number): string {
  const strides = table.args.map(argumentWords);
  const stride = strides.reduce((a, b) => a + b, 0);
  const lines: string[] = [];
  let offset = 0;
  table.args.forEach((type, index) => {
    if (type === 'f32') lines.push(`  let a${index} = bitcast<f32>(inputs[base + ${offset}u]);`);
    else if (type === 'u32') lines.push(`  let a${index} = inputs[base + ${offset}u];`);
    else if (type === 'i32')
      lines.push(`  let a${index} = bitcast<i32>(inputs[base + ${offset}u]);`);
    else {
      const n = argumentWords(type);
      lines.push(`  var a${index}: array<f32, ${n}>;`);
      lines.push(
        `  for (var k = 0u; k < ${n}u; k++) { a${index}[k] = bitcast<f32>(inputs[base + ${offset}u + k]); }`,
      );
    }
    offset += argumentWords(type);
  });
  const callee = table.wrapper ? 'caseUnderTest' : table.fn;
  const call = `${callee}(${table.args.map((_, i) => `a${i}`).join(', ')})`;
  const words = resultWords(table.result);
  const store =
    table.result === 'u32'
      ? ['  outputs[i] = r;']
      : table.result === 'i32' || table.result === 'f32'
        ? ['  outputs[i] = bitcast<u32>(r);']
        : Array.from(
            { length: words },
            (_, k) => `  outputs[i * ${words}u + ${k}u] = bitcast<u32>(r[${k}]);`,
          );
  const imports = table.wrapper ? table.wrapper.imports : [table.fn];
  return [
    ...imports.map((name) => `import package::${table.module.replace(/\//g, '::')}::${name};`),
    '@group(0) @binding(0) var<storage, read> inputs: array<u32>;',
    '@group(0) @binding(1) var<storage, read_write> outputs: array<u32>;',
    table.wrapper?.wgsl ?? '',
    `@compute @workgroup_size(${WORKGROUP_SIZE})`,
    'fn main(@builtin(global_invocation_id) id: vec3u) {',
    '  let i = id.x;',
    `  if (i >= ${caseCount}u) { return; }`,
    `  let base = i * ${stride}u;`,
    ...lines,
    `  let r = ${call};`,
    ...store,
    '}',
  ].join('\n');
}

export interface CaseOutcome {
  gpu: number[];
  twin: number[];
}

/** Links and runs the table on the GPU and evaluates the twin; one outcome per case. */
export async function evaluateTable(table: ShaderFunctionTable): Promise<CaseOutcome[]> {
  const device = await nodeDevice();
  const code = await linkKernel(SHADER_LIBRARY, generateKernel(table, table.cases.length));
  const stride = table.args.map(argumentWords).reduce((a, b) => a + b, 0);
  const words = resultWords(table.result);
  const inputs = new Uint32Array(table.cases.length * stride);
  table.cases.forEach((testCase, caseIndex) => {
    if (testCase.args.length !== table.args.length) {
      throw new Error(
        `${table.fn} case "${testCase.name}" has ${testCase.args.length} arguments, expected ${table.args.length}`,
      );
    }
    let offset = caseIndex * stride;
    table.args.forEach((type, index) => {
      const value = testCase.args[index] as Argument;
      if (Array.isArray(value)) {
        const n = argumentWords(type);
        for (let k = 0; k < n; k++) inputs[offset + k] = f32ToBits(value[k] ?? 0);
        offset += n;
      } else {
        inputs[offset] = encodeScalar(type as ScalarType, value as number);
        offset += 1;
      }
    });
  });
  const { output } = await runCompute(device, {
    code,
    inputs: [inputs],
    outputWords: table.cases.length * words,
    workgroups: [Math.ceil(table.cases.length / WORKGROUP_SIZE)],
  });
  return table.cases.map((testCase, caseIndex) => {
    const raw = Array.from(output.slice(caseIndex * words, caseIndex * words + words));
    const gpu =
      table.result === 'u32'
        ? raw
        : table.result === 'i32'
          ? raw.map((w) => w | 0)
          : raw.map(bitsToF32);
    const args = testCase.args.map((value, index) =>
      asGpuSees(table.args[index] as ArgumentType, value),
    );
    const twinValue = (table.twin as (...a: Argument[]) => number | readonly number[])(...args);
    const twin = typeof twinValue === 'number' ? [twinValue] : [...twinValue];
    return { gpu, twin };
  });
}

export function withinTolerance(actual: number, reference: number, tolerance: Tolerance): boolean {
  if (actual === reference) return true;
  const difference = Math.abs(actual - reference);
  if (tolerance.absolute !== undefined && difference <= tolerance.absolute) return true;
  if (tolerance.relative !== undefined && difference <= tolerance.relative * Math.abs(reference))
    return true;
  if (tolerance.ulps !== undefined && ulpDistance(actual, reference) <= tolerance.ulps) return true;
  return false;
}

function describeTolerance(tolerance: Tolerance): string {
  const parts = [
    tolerance.relative !== undefined ? `rel ${tolerance.relative}` : '',
    tolerance.absolute !== undefined ? `abs ${tolerance.absolute}` : '',
    tolerance.ulps !== undefined ? `${tolerance.ulps} ULP` : '',
  ].filter(Boolean);
  return `${parts.join(' or ')} (${tolerance.reason})`;
}

/** Registers one Vitest test per case: WGSL result vs twin (and vs the published value). */
export function describeShaderFunction(table: ShaderFunctionTable): void {
  describe(`${table.module}.${table.fn}: WGSL vs float64 twin`, () => {
    let outcomes: CaseOutcome[] = [];
    beforeAll(async () => {
      outcomes = await evaluateTable(table);
    }, 60_000);
    table.cases.forEach((testCase, caseIndex) => {
      const tolerance = testCase.tolerance ?? table.tolerance;
      it(`${testCase.name} [${describeTolerance(tolerance)}]`, () => {
        const outcome = outcomes[caseIndex];
        expect(outcome, 'the GPU evaluation ran').toBeDefined();
        if (!outcome) return;
        const exact = table.result === 'u32' || table.result === 'i32';
        outcome.gpu.forEach((gpu, k) => {
          const twin = outcome.twin[k] ?? NaN;
          if (exact) {
            expect(gpu, `component ${k}`).toBe(twin);
            return;
          }
          expect(Number.isFinite(gpu), `GPU result ${gpu} is finite`).toBe(true);
          expect(
            withinTolerance(gpu, twin, tolerance),
            `component ${k}: GPU ${gpu} vs twin ${twin} (diff ${Math.abs(gpu - twin)})`,
          ).toBe(true);
        });
        if (testCase.expected !== undefined) {
          const expected =
            typeof testCase.expected === 'number' ? [testCase.expected] : testCase.expected;
          expected.forEach((value, k) => {
            expect(
              withinTolerance(outcome.gpu[k] ?? NaN, value, tolerance),
              `GPU vs published ${value}`,
            ).toBe(true);
            expect(
              withinTolerance(outcome.twin[k] ?? NaN, value, tolerance),
              `twin vs published ${value}`,
            ).toBe(true);
          });
        }
      });
    });
  });
}
