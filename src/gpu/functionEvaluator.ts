// Evaluates one WGSL library function on the GPU over a list of calls, in the
// manner of the WebGPU CTS: the arguments of every call are packed into one
// buffer, one generated compute kernel calls the function once per call, and the
// results are unpacked to numbers. The shader tests (tests/support/shaderHarness.ts)
// and the command line (src/cli/main.ts) both use it; the caller passes the device
// (Dawn in Node, navigator.gpu in a browser) and the shader library.
//
// Supported signatures: arguments f32, u32, i32 and array<f32, N> (written `f32[N]`),
// results f32, u32, i32, vec2f, vec3f, vec4f. Anything else (pointers, structs,
// textures) needs a `wrapper`: a WGSL `fn caseUnderTest(...)` with a supported
// signature that calls the function. signatureOf() reads a function's signature from
// the library with the WESL parser and builds that wrapper for vecNf arguments.
// The exercise grader (src/grading/grade.ts) builds its harness from the same pieces:
// the word encoding (encodeScalar, bitsToF32) and the argument loads (argumentLoads).
import { parseSrcModule, type ExpressionElem, type FnElem, type TypeRefElem } from 'wesl';
import { runCompute } from './compute.ts';
import { linkKernel, type ShaderLibrary } from './link.ts';

export type ScalarType = 'f32' | 'u32' | 'i32';
/** `f32[N]` stands for the WGSL `array<f32, N>`. */
export type ArgumentType = ScalarType | `f32[${number}]`;
export type ResultType = ScalarType | 'vec2f' | 'vec3f' | 'vec4f';

export type Argument = number | readonly number[];

/** What the generated kernel calls: a library function, or a wrapper around it. */
export interface FunctionSpec {
  /** Module path under shaders/ without extension, e.g. `transmittance`. */
  module: string;
  /** Function name, the same in WGSL and in the twin. */
  fn: string;
  args: readonly ArgumentType[];
  result: ResultType;
  /**
   * For functions that cannot be called with plain values (pointer arguments):
   * WGSL source of `fn caseUnderTest(...) -> RESULT` that wraps the call, and the
   * library symbols it imports. The twin must compute the same thing.
   */
  wrapper?: { wgsl: string; imports: readonly string[] };
}

/** A function with its float64 twin and named calls (a test table without tolerances). */
export interface FunctionCases extends FunctionSpec {
  /** The float64 twin, called with the f32-rounded arguments. */
  twin: (...args: never[]) => number | readonly number[];
  cases: readonly { name: string; args: readonly Argument[] }[];
}

export interface CaseOutcome {
  gpu: number[];
  twin: number[];
}

const WORKGROUP_SIZE = 64;

export function argumentWords(type: ArgumentType): number {
  const match = /^f32\[(\d+)\]$/.exec(type);
  return match ? Number(match[1]) : 1;
}

export function resultWords(type: ResultType): number {
  return type === 'vec2f' ? 2 : type === 'vec3f' ? 3 : type === 'vec4f' ? 4 : 1;
}

const scratch = new DataView(new ArrayBuffer(4));

export function f32ToBits(value: number): number {
  scratch.setFloat32(0, value);
  return scratch.getUint32(0);
}

export function bitsToF32(bits: number): number {
  scratch.setUint32(0, bits >>> 0);
  return scratch.getFloat32(0);
}

/** The u32 word the GPU reads for a scalar argument (f32 bits, i32 two's complement). */
export function encodeScalar(type: ScalarType, value: number): number {
  if (type === 'f32') return f32ToBits(value);
  if (type === 'i32') return (value | 0) >>> 0;
  return value >>> 0;
}

/** Rounds an argument as the GPU will see it. */
export function asGpuSees(type: ArgumentType, value: Argument): Argument {
  if (Array.isArray(value)) return value.map((v) => Math.fround(v));
  if (type === 'f32') return Math.fround(value as number);
  return value;
}

/**
 * WGSL statements that declare each argument `name` from consecutive words of the u32
 * array `inputs`, starting at the u32 expression `base` (arguments packed as
 * packArguments packs them).
 */
export function argumentLoads(
  args: readonly { type: ArgumentType; name: string }[],
  inputs: string,
  base: string,
): string[] {
  const lines: string[] = [];
  let offset = 0;
  for (const { type, name } of args) {
    const word = `${inputs}[${base} + ${offset}u]`;
    if (type === 'f32') lines.push(`  let ${name} = bitcast<f32>(${word});`);
    else if (type === 'u32') lines.push(`  let ${name} = ${word};`);
    else if (type === 'i32') lines.push(`  let ${name} = bitcast<i32>(${word});`);
    else {
      const n = argumentWords(type);
      lines.push(`  var ${name}: array<f32, ${n}>;`);
      lines.push(
        `  for (var k = 0u; k < ${n}u; k++) { ${name}[k] = bitcast<f32>(${inputs}[${base} + ${offset}u + k]); }`,
      );
    }
    offset += argumentWords(type);
  }
  return lines;
}

export function generateKernel(spec: FunctionSpec, caseCount: number): string {
  const strides = spec.args.map(argumentWords);
  const stride = strides.reduce((a, b) => a + b, 0);
  const lines = argumentLoads(
    spec.args.map((type, index) => ({ type, name: `a${index}` })),
    'inputs',
    'base',
  );
  const callee = spec.wrapper ? 'caseUnderTest' : spec.fn;
  const call = `${callee}(${spec.args.map((_, i) => `a${i}`).join(', ')})`;
  const words = resultWords(spec.result);
  const store =
    spec.result === 'u32'
      ? ['  outputs[i] = r;']
      : spec.result === 'i32' || spec.result === 'f32'
        ? ['  outputs[i] = bitcast<u32>(r);']
        : Array.from(
            { length: words },
            (_, k) => `  outputs[i * ${words}u + ${k}u] = bitcast<u32>(r[${k}]);`,
          );
  const imports = spec.wrapper ? spec.wrapper.imports : [spec.fn];
  return [
    ...imports.map((name) => `import package::${spec.module.replace(/\//g, '::')}::${name};`),
    '@group(0) @binding(0) var<storage, read> inputs: array<u32>;',
    '@group(0) @binding(1) var<storage, read_write> outputs: array<u32>;',
    spec.wrapper?.wgsl ?? '',
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

/**
 * Packs the arguments of every call into one u32 buffer. `describeCall(i)` names a
 * call in the error for a wrong argument count (default: `call i+1`).
 */
export function packArguments(
  spec: FunctionSpec,
  calls: readonly (readonly Argument[])[],
  describeCall: (index: number) => string = (index) => `call ${index + 1}`,
): Uint32Array {
  const stride = spec.args.map(argumentWords).reduce((a, b) => a + b, 0);
  const inputs = new Uint32Array(calls.length * stride);
  calls.forEach((args, callIndex) => {
    if (args.length !== spec.args.length) {
      throw new Error(
        `${spec.fn} ${describeCall(callIndex)} has ${args.length} arguments, expected ${spec.args.length}`,
      );
    }
    let offset = callIndex * stride;
    spec.args.forEach((type, index) => {
      const value = args[index] as Argument;
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
  return inputs;
}

/** The GPU's result of call `index`: f32 values as numbers, u32/i32 as integers. */
export function unpackResult(spec: FunctionSpec, output: Uint32Array, index: number): number[] {
  const words = resultWords(spec.result);
  const raw = Array.from(output.slice(index * words, index * words + words));
  return spec.result === 'u32'
    ? raw
    : spec.result === 'i32'
      ? raw.map((w) => w | 0)
      : raw.map(bitsToF32);
}

/** The linked kernel, packed inputs and dispatch size of one evaluation (any WebGPU engine). */
export interface EvaluationJob {
  code: string;
  entryPoint: 'main';
  inputs: [Uint32Array];
  outputWords: number;
  workgroups: [number];
}

/** Links and packs all calls for one dispatch; evaluateOnGpu runs it, tests also on wgpu. */
export async function evaluationJob(
  library: ShaderLibrary,
  spec: FunctionSpec,
  calls: readonly (readonly Argument[])[],
  describeCall?: (index: number) => string,
): Promise<EvaluationJob> {
  const code = await linkKernel(library, generateKernel(spec, calls.length));
  return {
    code,
    entryPoint: 'main',
    inputs: [packArguments(spec, calls, describeCall)],
    outputWords: calls.length * resultWords(spec.result),
    workgroups: [Math.ceil(calls.length / WORKGROUP_SIZE)],
  };
}

/** Links, packs and runs all calls in one dispatch; one result (array of components) per call. */
export async function evaluateOnGpu(
  device: GPUDevice,
  library: ShaderLibrary,
  spec: FunctionSpec,
  calls: readonly (readonly Argument[])[],
  describeCall?: (index: number) => string,
): Promise<number[][]> {
  const job = await evaluationJob(library, spec, calls, describeCall);
  const { output } = await runCompute(device, job);
  return calls.map((_, index) => unpackResult(spec, output, index));
}

/** The twin on the arguments as the GPU sees them, as an array of components. */
export function evaluateTwin(
  spec: FunctionSpec,
  twin: FunctionCases['twin'],
  args: readonly Argument[],
): number[] {
  const rounded = args.map((value, index) => asGpuSees(spec.args[index] as ArgumentType, value));
  const value = (twin as (...a: Argument[]) => number | readonly number[])(...rounded);
  return typeof value === 'number' ? [value] : [...value];
}

/** Runs every case on the GPU and through the twin; one outcome per case. */
export async function evaluateCases(
  device: GPUDevice,
  library: ShaderLibrary,
  table: FunctionCases,
): Promise<CaseOutcome[]> {
  const gpu = await evaluateOnGpu(
    device,
    library,
    table,
    table.cases.map((testCase) => testCase.args),
    (index) => `case "${table.cases[index]?.name}"`,
  );
  return table.cases.map((testCase, caseIndex) => ({
    gpu: gpu[caseIndex] ?? [],
    twin: evaluateTwin(table, table.twin, testCase.args),
  }));
}

// ---------------------------------------------------------------------------
// Signatures read from the library, for callers that know only a function's name.

/** A parameter or result type as written in WGSL, and what the evaluator makes of it. */
export interface WgslType {
  /** The type as written, e.g. `array<f32, GRID1D_MAX_CELLS>`. */
  text: string;
  /** How many numbers a caller passes for it: 1 for a scalar, N for vecNf or array<f32, N>. */
  components: number;
  /** Why the GPU evaluator cannot take it, or null when it can. */
  unsupported: string | null;
}

export interface FunctionSignature {
  module: string;
  fn: string;
  params: readonly { name: string; type: WgslType }[];
  result: WgslType | null;
  /** The signature as one line, e.g. `transmittanceHomogeneous(sigmaT: f32, distance: f32) -> f32`. */
  text: string;
  /**
   * Whether the declaration is absent from a kernel linked with no conditions, as an
   * evaluation kernel is: an @if that does not hold then (integrator.wesl's scene-grid
   * lookups under gridMedia), or any @elif or @else.
   */
  conditional: boolean;
}

/**
 * Whether a WESL translate-time condition (`a`, `!a`, `a && (b || !c)`, `true`, `false`)
 * holds when no condition is set, as in an evaluation kernel, which links with none: every
 * name is false. An expression of another kind counts as not holding.
 */
export function holdsWithNoConditions(expression: ExpressionElem): boolean {
  switch (expression.kind) {
    case 'literal':
      return expression.value === 'true';
    case 'ref':
      return false;
    case 'parenthesized-expression':
      return holdsWithNoConditions(expression.expression);
    case 'unary-expression':
      return expression.operator.value === '!' && !holdsWithNoConditions(expression.expression);
    case 'binary-expression': {
      const left = holdsWithNoConditions(expression.left);
      const right = holdsWithNoConditions(expression.right);
      if (expression.operator.value === '&&') return left && right;
      if (expression.operator.value === '||') return left || right;
      return false;
    }
    default:
      return false;
  }
}

/** The library module `shaders/NAME.wesl`'s function declarations, in source order. */
export function functionsOf(library: ShaderLibrary, module: string): FunctionSignature[] {
  const source = library[`${module}.wesl`];
  if (source === undefined) throw new Error(`no shader module "${module}" in the library`);
  const ast = parseSrcModule({
    modulePath: `package::${module.replace(/\//g, '::')}`,
    debugFilePath: `shaders/${module}.wesl`,
    src: source,
  });
  const text = (elem: TypeRefElem): string => source.slice(elem.start, elem.end).trim();
  return ast.moduleElem.decls
    .filter((decl): decl is FnElem => decl.kind === 'fn')
    .map((decl) => {
      const params = decl.params.map((param) => {
        const typeRef = param.name.typeRef;
        return {
          name: param.name.decl.ident.originalName,
          type: classifyType(library, typeRef ? text(typeRef) : ''),
        };
      });
      const result = decl.returnType ? classifyType(library, text(decl.returnType)) : null;
      const fn = decl.name.ident.originalName;
      const list = params.map((p) => `${p.name}: ${p.type.text}`).join(', ');
      const conditional = (decl.attributes ?? []).some((a) => {
        const attribute = a.attribute;
        if (attribute.kind === '@if') return !holdsWithNoConditions(attribute.param.expression);
        // @elif and @else depend on the declarations before them: taken as absent.
        return attribute.kind === '@elif' || attribute.kind === '@else';
      });
      return {
        module,
        fn,
        params,
        result,
        text: `${fn}(${list})${result ? ` -> ${result.text}` : ''}`,
        conditional,
      };
    });
}

const VECTOR = /^vec([234])(?:f|<\s*f32\s*>)$/;
const ARRAY = /^array<\s*f32\s*,\s*([A-Za-z_][A-Za-z0-9_]*|\d+)u?\s*>$/;

/** The value of an integer `const NAME` declared anywhere in the library (imports included). */
function libraryConstant(library: ShaderLibrary, name: string): number | null {
  const pattern = new RegExp(
    `^\\s*const\\s+${name}\\s*(?::\\s*[ui]32\\s*)?=\\s*(\\d+)[ui]?\\s*;`,
    'm',
  );
  for (const source of Object.values(library)) {
    const match = pattern.exec(source);
    if (match) return Number(match[1]);
  }
  return null;
}

function classifyType(library: ShaderLibrary, text: string): WgslType {
  const compact = text.replace(/\s+/g, ' ');
  if (compact === 'f32' || compact === 'u32' || compact === 'i32')
    return { text: compact, components: 1, unsupported: null };
  const vector = VECTOR.exec(compact);
  if (vector) return { text: compact, components: Number(vector[1]), unsupported: null };
  const array = ARRAY.exec(compact);
  if (array) {
    const size = /^\d+$/.test(array[1] ?? '')
      ? Number(array[1])
      : libraryConstant(library, array[1] ?? '');
    if (size !== null && size > 0) return { text: compact, components: size, unsupported: null };
    return {
      text: compact,
      components: 0,
      unsupported: 'its array length is not a known constant',
    };
  }
  const kind = compact.startsWith('ptr<')
    ? 'a pointer'
    : /^texture|^sampler/.test(compact)
      ? 'a texture or sampler'
      : /^[A-Z]/.test(compact)
        ? 'a struct'
        : 'not one of f32, u32, i32, vecNf, array<f32, N>';
  return { text: compact, components: 0, unsupported: kind };
}

/**
 * The evaluator's spec for a library function, or an error naming the first type it
 * cannot take. vecNf arguments become N f32 arguments through a wrapper, so callers
 * pass them as arrays of N numbers.
 */
export function specFor(signature: FunctionSignature): FunctionSpec {
  const where = `${signature.module}.${signature.fn}`;
  if (signature.conditional)
    throw new UnsupportedSignatureError(
      `${where} exists only under a link condition (@if), which evaluation kernels do not set`,
    );
  for (const param of signature.params) {
    if (param.type.unsupported !== null)
      throw new UnsupportedSignatureError(
        `${where}: parameter ${param.name} has type ${param.type.text} (${param.type.unsupported})`,
      );
  }
  const result = signature.result;
  if (!result) throw new UnsupportedSignatureError(`${where} returns nothing`);
  const resultVector = VECTOR.exec(result.text);
  if (result.unsupported !== null || ARRAY.test(result.text))
    throw new UnsupportedSignatureError(
      `${where}: its result has type ${result.text} (${result.unsupported ?? 'an array'})`,
    );
  const resultType = (resultVector ? `vec${resultVector[1]}f` : result.text) as ResultType;
  const vectors = signature.params.some((p) => VECTOR.test(p.type.text));
  const args: ArgumentType[] = [];
  const wrapperParams: string[] = [];
  const callArgs: string[] = [];
  signature.params.forEach((param, index) => {
    const text = param.type.text;
    if (VECTOR.test(text)) {
      const parts = Array.from({ length: param.type.components }, (_, k) => `p${index}_${k}`);
      parts.forEach((part) => {
        args.push('f32');
        wrapperParams.push(`${part}: f32`);
      });
      callArgs.push(`vec${param.type.components}f(${parts.join(', ')})`);
    } else if (ARRAY.test(text)) {
      args.push(`f32[${param.type.components}]`);
      wrapperParams.push(`p${index}: array<f32, ${param.type.components}>`);
      callArgs.push(`p${index}`);
    } else {
      args.push(text as ScalarType);
      wrapperParams.push(`p${index}: ${text}`);
      callArgs.push(`p${index}`);
    }
  });
  const spec: FunctionSpec = {
    module: signature.module,
    fn: signature.fn,
    args,
    result: resultType,
  };
  if (!vectors) return spec;
  return {
    ...spec,
    wrapper: {
      wgsl: `fn caseUnderTest(${wrapperParams.join(', ')}) -> ${result.text} {\n  return ${signature.fn}(${callArgs.join(', ')});\n}`,
      imports: [signature.fn],
    },
  };
}

/** A signature the GPU evaluator cannot take (a struct, pointer or texture type). */
export class UnsupportedSignatureError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'UnsupportedSignatureError';
  }
}

/** Flattens one call's arguments for specFor's argument list (vecNf → N numbers). */
export function flattenCall(signature: FunctionSignature, call: readonly Argument[]): Argument[] {
  return signature.params.flatMap((param, index) => {
    const value = call[index] as Argument;
    return VECTOR.test(param.type.text) && Array.isArray(value) ? [...value] : [value];
  });
}
