// Dawn's Node binding (the `webgpu` package, dawn.node's AsyncRunner) settles a pending
// promise — mapAsync, onSubmittedWorkDone, createComputePipelineAsync, popErrorScope… — by
// calling the instance's ProcessEvents() from setImmediate, again and again, until it
// settles: while the GPU works, Node's main thread spins at a full core. Without a GPU the
// "GPU" is SwiftShader, whose worker threads need those very cores: on this project's
// 2-core machines the spin took as much CPU as both of SwiftShader's threads together
// (perf, `npm run bench -- --only=peers` scene "multiple scattering"), and the scene
// kernel moved 1.65× more paths per second once it stopped (issue 19).
//
// installQuietPolling() wraps those methods so that, after a short spin (a quick result,
// such as an error scope, comes back as fast as before), the main thread sleeps between
// polls (Atomics.wait, 0.25 ms growing to 2 ms) and lets one setImmediate turn run between
// sleeps, so that dawn.node's own poll still runs. The sleeps block this thread's event
// loop for at most 2 ms at a time, which suits Node scripts (tests, the command line,
// benchmarks); browser code never imports this (browsers do not spin).

/** Wall time spent spinning as before, for a result that is almost ready. */
const SPIN_MS = 0.5;
const FIRST_SLEEP_MS = 0.25;
const LONGEST_SLEEP_MS = 2;

const sleeper = new Int32Array(new SharedArrayBuffer(4));

let enabled = true;

/** Turns the quiet polling off (dawn.node's own spin) or on again: for before/after benches. */
export function setQuietPolling(on: boolean): void {
  enabled = on;
}

function nextTurn(): Promise<void> {
  return new Promise((resolve) => setImmediate(resolve));
}

/** `promise`, awaited with sleeps between event-loop turns instead of a busy spin. */
export async function settleQuietly<T>(promise: Promise<T>): Promise<T> {
  if (!enabled) return promise;
  let settled = false;
  promise.then(
    () => (settled = true),
    () => (settled = true),
  );
  const spinUntil = performance.now() + SPIN_MS;
  while (!settled && performance.now() < spinUntil) await nextTurn();
  let sleep = FIRST_SLEEP_MS;
  while (!settled) {
    Atomics.wait(sleeper, 0, 0, sleep);
    sleep = Math.min(LONGEST_SLEEP_MS, 2 * sleep);
    await nextTurn();
  }
  return promise;
}

/** The promise-returning WebGPU methods that dawn.node settles by polling. */
const POLLED_METHODS = {
  GPU: ['requestAdapter'],
  GPUAdapter: ['requestDevice'],
  GPUDevice: ['createComputePipelineAsync', 'createRenderPipelineAsync', 'popErrorScope'],
  GPUBuffer: ['mapAsync'],
  GPUQueue: ['onSubmittedWorkDone'],
  GPUShaderModule: ['getCompilationInfo'],
} as const;

const QUIET = Symbol('scatterbook.quietPolling');

type Method = (this: unknown, ...args: unknown[]) => unknown;

/** Wraps the polled methods of the WebGPU classes in `globals` (once per class). */
export function installQuietPolling(globals: object): void {
  for (const [className, methods] of Object.entries(POLLED_METHODS)) {
    const constructor = (globals as Record<string, unknown>)[className] as
      { prototype?: Record<PropertyKey, unknown> } | undefined;
    const prototype = constructor?.prototype;
    if (!prototype || prototype[QUIET]) continue;
    for (const name of methods) {
      const original = prototype[name];
      if (typeof original !== 'function') continue;
      const call = original as Method;
      prototype[name] = function (this: unknown, ...args: unknown[]): unknown {
        const result = call.apply(this, args);
        return result instanceof Promise ? settleQuietly(result) : result;
      };
    }
    prototype[QUIET] = true;
  }
}
