// GPU failures are surfaced, never swallowed: an error in a dispatch becomes an
// exception with the driver's message (and, for a shader that does not compile, the
// compiler's messages with line and column), and device loss is reported to whoever
// listens (the widgets then fall back to the CPU reference). Every error scope of
// the project is pushed and popped here.

/** WebGPU's error filters; a scope of each is pushed around every guarded body. */
export type GpuErrorKind = 'validation' | 'out-of-memory' | 'internal';

/** One compiler message of a shader module created inside the scope. */
export interface CompilationNote {
  type: GPUCompilationMessageType;
  line: number;
  column: number;
  message: string;
}

/** The first error the device reported for a guarded body, with its kind. */
export class GpuError extends Error {
  constructor(
    readonly what: string,
    readonly kind: GpuErrorKind,
    /** The device's own message, without `what`. */
    readonly detail: string,
    /** Errors and warnings of shader modules created in the body (empty when none). */
    readonly compilation: readonly CompilationNote[] = [],
  ) {
    const notes = compilation
      .filter((note) => note.type === 'error')
      .map((note) => `\n  line ${note.line}, column ${note.column}: ${note.message}`);
    super(`${what}: ${detail}${notes.join('')}`);
    this.name = kind === 'validation' ? 'GpuValidationError' : 'GpuError';
  }
}

/** The former name: every guarded error is a GpuError now (see `kind`). */
export const GpuValidationError = GpuError;

/** What a guarded body created, so a failure can name compiler messages and drop cache entries. */
interface ScopeFrame {
  modules: GPUShaderModule[];
  onFailure: (() => void)[];
}

const frames = new WeakMap<GPUDevice, ScopeFrame[]>();

/**
 * Called by the GPU core for every shader module (and cache entry) it creates: when
 * the innermost scope of `device` fails, its compiler messages are attached and
 * `onFailure` runs (the core forgets the entry, so a broken pipeline is not reused).
 */
export function noteCreated(
  device: GPUDevice,
  created: { module?: GPUShaderModule; onFailure?: () => void },
): void {
  const frame = frames.get(device)?.at(-1);
  if (!frame) return;
  if (created.module) frame.modules.push(created.module);
  if (created.onFailure) frame.onFailure.push(created.onFailure);
}

export interface ScopeOptions {
  /**
   * Wraps every wait on the device (popping the scopes, compilation info), e.g. the
   * grader's watchdog and device-loss guard. Default: await as is.
   */
  wait?: <T>(promise: Promise<T>) => Promise<T>;
}

const FILTERS: readonly GpuErrorKind[] = ['internal', 'out-of-memory', 'validation'];

async function compilationNotes(
  modules: readonly GPUShaderModule[],
  wait: <T>(promise: Promise<T>) => Promise<T>,
): Promise<CompilationNote[]> {
  const notes: CompilationNote[] = [];
  for (const module of modules) {
    const info = await wait(module.getCompilationInfo());
    for (const m of info.messages)
      if (m.type !== 'info')
        notes.push({ type: m.type, line: m.lineNum, column: m.linePos, message: m.message });
  }
  return notes;
}

/**
 * Runs `body` inside validation, out-of-memory and internal error scopes and throws
 * the first error as a GpuError (validation before out-of-memory before internal).
 * `body` runs synchronously; a promise it returns is awaited after the scopes close.
 */
export async function withErrorScopes<T>(
  device: GPUDevice,
  what: string,
  body: () => T,
  options: ScopeOptions = {},
): Promise<Awaited<T>> {
  const wait = options.wait ?? (<U>(promise: Promise<U>) => promise);
  for (const filter of FILTERS) device.pushErrorScope(filter);
  const frame: ScopeFrame = { modules: [], onFailure: [] };
  const stack = frames.get(device) ?? [];
  frames.set(device, stack);
  stack.push(frame);
  let result: T | undefined;
  let thrown: unknown = null;
  try {
    result = body();
  } catch (error) {
    thrown = error;
  } finally {
    stack.pop();
  }
  // Pop every scope whatever happened, so that the device's scope stack stays balanced;
  // they come off in reverse order of the pushes, all three before anything is awaited.
  // Pushes, body and pops are then one synchronous stretch: another guarded call (a
  // second renderer made side by side, Promise.all) can never push between our pops and
  // have its scope popped as ours, and the three answers come back in one round trip to
  // the GPU process instead of three (firstPictureProbe: 4–10 ms each on SwiftShader).
  const pops = [...FILTERS].reverse().map((filter) => ({ filter, error: device.popErrorScope() }));
  const answers = await Promise.allSettled(pops.map(({ error }) => wait(error)));
  const popped: Partial<Record<GpuErrorKind, GPUError | null>> = {};
  for (const [i, { filter }] of pops.entries()) {
    const answer = answers[i]!;
    if (answer.status === 'rejected') throw answer.reason;
    popped[filter] = answer.value;
  }
  const kind = FILTERS.slice()
    .reverse()
    .find((filter) => popped[filter]);
  if (kind) {
    // A promise the body returned is dropped with the error; keep its rejection handled.
    if (result instanceof Promise) result.catch(() => undefined);
    for (const forget of frame.onFailure) forget();
    const notes = kind === 'validation' ? await compilationNotes(frame.modules, wait) : [];
    throw new GpuError(what, kind, popped[kind]?.message ?? '', notes);
  }
  if (thrown !== null) throw thrown;
  return await (result as T);
}
