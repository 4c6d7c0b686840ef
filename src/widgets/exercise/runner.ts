// Runs an exercise's public checks on a GPU device of the exercise's own, so that a
// student shader that hangs or faults can never take the book's shared device (and
// with it every other figure on the page) down. Three guards keep the page alive:
// the grading core's own watchdog (GradeOptions.timeoutMs), an outer watchdog here
// in case a submission never returns at all, and device-loss handling: a lost or
// abandoned device is dropped and the next run requests a fresh one. Loops in the
// student's code are bounded by the core's instrumentation ('loop-budget').
import type { GradeOptions, GradeOutcome } from '../../grading/types.ts';

export type RunOutcome =
  | GradeOutcome
  | { status: 'cancelled'; message: string }
  /** The grading core itself threw: a fault of the grader, not of the student's code. */
  | { status: 'error'; message: string };

/** Grades `source` on `device`: the grading core, bound to one exercise. */
export type GradeFunction = (
  device: GPUDevice,
  source: string,
  options: GradeOptions,
) => Promise<GradeOutcome>;

/** Extra time the outer watchdog allows beyond the core's own, for compiling and read-back. */
const OUTER_GRACE_MS = 5_000;

export class WebGpuUnavailable extends Error {}

/** A fresh device of the page's WebGPU adapter (not the shared one of the figures). */
async function requestOwnDevice(): Promise<GPUDevice> {
  if (typeof navigator === 'undefined' || !('gpu' in navigator) || !navigator.gpu)
    throw new WebGpuUnavailable('this browser has no WebGPU (navigator.gpu is missing)');
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) throw new WebGpuUnavailable('WebGPU found no suitable GPU adapter');
  return adapter.requestDevice();
}

export class ExerciseRunner {
  private device: GPUDevice | null = null;

  /**
   * @param requestDevice where devices come from (tests pass a fake).
   * @param graceMs the outer watchdog's allowance beyond GradeOptions.timeoutMs.
   */
  constructor(
    private readonly requestDevice: () => Promise<GPUDevice> = requestOwnDevice,
    private readonly graceMs = OUTER_GRACE_MS,
  ) {}

  /** This runner's device, created on first use and again after a loss. */
  private async acquire(): Promise<GPUDevice> {
    if (this.device) return this.device;
    const device = await this.requestDevice();
    void device.lost.then(() => {
      if (this.device === device) this.device = null;
    });
    this.device = device;
    return device;
  }

  /** Drops the device (abandoning any work still queued on it); the next run gets a fresh one. */
  private abandon(device: GPUDevice): void {
    if (this.device === device) this.device = null;
    device.destroy();
  }

  /**
   * Runs the public checks. Resolves (never rejects for a student's mistake) with the
   * core's outcome, or 'timeout' / 'device-lost' / 'cancelled' from the guards here.
   */
  async run(
    grade: GradeFunction,
    source: string,
    options: {
      timeoutMs: number;
      signal: AbortSignal;
      onProgress: (done: number, total: number) => void;
    },
  ): Promise<RunOutcome> {
    const device = await this.acquire();
    const inner = new AbortController();
    const timers: ReturnType<typeof setTimeout>[] = [];
    let cleanup = (): void => undefined;
    const guards = new Promise<RunOutcome>((resolve) => {
      void device.lost.then((info) => {
        if (info.reason === 'destroyed') return;
        resolve({
          status: 'device-lost',
          message: `The GPU device was lost while running your code (${info.message || 'the browser gave no reason'}).`,
        });
      });
      timers.push(
        setTimeout(() => {
          resolve({
            status: 'timeout',
            message:
              `The GPU gave no answer within ${Math.round((options.timeoutMs + this.graceMs) / 1000)} s, ` +
              'so the run was abandoned. Look for a loop that does far more work than the exercise needs.',
          });
        }, options.timeoutMs + this.graceMs),
      );
      const onAbort = (): void =>
        resolve({ status: 'cancelled', message: 'You cancelled the run.' });
      if (options.signal.aborted) onAbort();
      options.signal.addEventListener('abort', onAbort);
      cleanup = () => options.signal.removeEventListener('abort', onAbort);
    });
    const graded = grade(device, source, {
      which: 'public',
      timeoutMs: options.timeoutMs,
      signal: inner.signal,
      onProgress: options.onProgress,
    }).catch((error: unknown): RunOutcome => ({
      status: 'error',
      message: error instanceof Error ? error.message : String(error),
    }));
    const outcome = await Promise.race([graded, guards]);
    for (const timer of timers) clearTimeout(timer);
    cleanup();
    if (['timeout', 'cancelled', 'device-lost', 'error'].includes(outcome.status)) {
      // Work may still be queued (a long student loop): tell the core to stop and drop
      // the device so the GPU is freed; the next run starts on a fresh device.
      inner.abort();
      this.abandon(device);
    }
    return outcome;
  }
}
