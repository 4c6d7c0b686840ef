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
//
// Each table runs on two engines with the same tolerances: Dawn (Tint, as in Chrome)
// in this process, and wgpu (naga, as in Firefox) through Deno, all of a test file's
// tables in one batch (tests/support/denoGpu.ts).
import { beforeAll, describe, expect, it } from 'vitest';
import {
  evaluateCases,
  evaluateTwin,
  evaluationJob,
  generateKernel,
  unpackResult,
  type Argument,
  type ArgumentType,
  type CaseOutcome,
  type ResultType,
  type ScalarType,
} from '../../src/gpu/functionEvaluator.ts';
import { runOnWgpu } from './denoGpu.ts';
import { nodeDevice } from './nodeGpu.ts';
import { SHADER_LIBRARY } from './shaderLibrary.ts';
import { ulpDistance } from './f32.ts';

// Packing, kernel generation, dispatch and unpacking live in src/gpu/functionEvaluator.ts
// (shared with the command line); this file adds the Dawn device, tolerances and Vitest.
export { generateKernel };
export type { Argument, ArgumentType, CaseOutcome, ResultType, ScalarType };

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

/** Links and runs the table on the GPU and evaluates the twin; one outcome per case. */
export async function evaluateTable(table: ShaderFunctionTable): Promise<CaseOutcome[]> {
  const device = await nodeDevice();
  return evaluateCases(device, SHADER_LIBRARY, table);
}

// The same tables on the second engine, wgpu (naga, as in Firefox) through Deno.
// Every table a test file declares is collected at collection time; the first
// wgpu beforeAll sends them all in one batch (one Deno process per test file), and
// each table's outcomes are compared with the twin here in Node under the same
// tolerances as on Dawn.
const wgpuTables: ShaderFunctionTable[] = [];
let wgpuBatch: Promise<Map<ShaderFunctionTable, CaseOutcome[] | Error>> | null = null;

async function evaluateTablesOnWgpu(
  tables: readonly ShaderFunctionTable[],
): Promise<Map<ShaderFunctionTable, CaseOutcome[] | Error>> {
  const outcomes = new Map<ShaderFunctionTable, CaseOutcome[] | Error>();
  const jobs = [];
  const sent: ShaderFunctionTable[] = [];
  for (const table of tables) {
    try {
      const job = await evaluationJob(
        SHADER_LIBRARY,
        table,
        table.cases.map((testCase) => testCase.args),
        (index) => `case "${table.cases[index]?.name}"`,
      );
      jobs.push({ name: `${table.module}.${table.fn}`, ...job });
      sent.push(table);
    } catch (error) {
      outcomes.set(table, error as Error);
    }
  }
  const answer = await runOnWgpu({ evaluate: jobs });
  sent.forEach((table, k) => {
    const result = answer.evaluate[k];
    if (!result?.output) {
      outcomes.set(table, new Error(`wgpu: ${result?.error ?? 'no answer'}`));
      return;
    }
    const output = result.output;
    outcomes.set(
      table,
      table.cases.map((testCase, index) => ({
        gpu: unpackResult(table, output, index),
        twin: evaluateTwin(table, table.twin, testCase.args),
      })),
    );
  });
  return outcomes;
}

/** The table's outcomes on wgpu (Deno), from this test file's single batch. */
export async function evaluateTableOnWgpu(table: ShaderFunctionTable): Promise<CaseOutcome[]> {
  if (!wgpuTables.includes(table)) wgpuTables.push(table);
  wgpuBatch ??= evaluateTablesOnWgpu([...wgpuTables]);
  let outcome = (await wgpuBatch).get(table);
  if (outcome === undefined) {
    // Declared after the batch left (not at collection time): a batch of its own.
    outcome = (await evaluateTablesOnWgpu([table])).get(table);
  }
  if (outcome === undefined || outcome instanceof Error)
    throw outcome ?? new Error('no wgpu outcome');
  return outcome;
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

/**
 * Registers one Vitest test per case: WGSL result vs twin (and vs the published value),
 * once on Dawn (Tint, as in Chrome) and once on wgpu (naga, as in Firefox).
 */
export function describeShaderFunction(table: ShaderFunctionTable): void {
  wgpuTables.push(table);
  describeOn('', table, () => evaluateTable(table));
  describeOn(' on wgpu (naga, Deno)', table, () => evaluateTableOnWgpu(table));
}

function describeOn(
  engine: string,
  table: ShaderFunctionTable,
  evaluate: () => Promise<CaseOutcome[]>,
): void {
  describe(`${table.module}.${table.fn}: WGSL${engine} vs float64 twin`, () => {
    let outcomes: CaseOutcome[] = [];
    beforeAll(async () => {
      outcomes = await evaluate();
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
