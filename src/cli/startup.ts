// Start-up phases of the command line (issue 19: `npm run render` from process start to
// its first render pass submitted, under 0.5 s). Times are milliseconds since the process
// started: Node sets performance.timeOrigin when the process starts, and
// performance.now() counts from it, so the first mark also holds Node's own bootstrap and
// the loading of the program (tsx compiling TypeScript, or the prebuilt bundle,
// scripts/cli.mjs). `scatterbook render --stats` writes them as `startup`.
import { performance } from 'node:perf_hooks';

/** A phase's start and end, milliseconds since the process started. */
export interface PhaseSpan {
  start: number;
  end: number;
}

export interface StartupReport {
  /** What the clock counts from. */
  origin: string;
  /** Node's own bootstrap (performance.nodeTiming.bootstrapComplete). */
  nodeBootstrapMs: number;
  /** Each phase's span; phases may overlap where they run concurrently. */
  phases: Record<string, PhaseSpan>;
  /** Process start to the first render pass submitted to the queue. */
  firstPassSubmittedMs: number | null;
  /**
   * CPU time (user + system, every thread: Dawn's and SwiftShader's compiler included)
   * the process had used by then: the work of start-up, which a loaded machine stretches
   * less than the wall time.
   */
  firstPassCpuMs: number | null;
}

export class StartupTimer {
  private readonly spans = new Map<string, PhaseSpan>();
  private firstSubmit: number | null = null;
  private firstSubmitCpu: number | null = null;

  /** Milliseconds since the process started. */
  now(): number {
    return performance.now();
  }

  /** Records a phase that ran from `start` until now (a name's first span is kept). */
  record(name: string, start: number): void {
    if (!this.spans.has(name)) this.spans.set(name, { start, end: this.now() });
  }

  /** Runs `work` and records its span as `name` (also when it throws). */
  async time<T>(name: string, work: () => Promise<T> | T): Promise<T> {
    const start = this.now();
    try {
      return await work();
    } finally {
      this.record(name, start);
    }
  }

  /**
   * Notes the first queue submission of `device` from now on: the scene renderer's first
   * pass is the first submit after its pipelines are compiled and its scene uploaded
   * (uploads go through queue.writeBuffer/writeTexture, which do not submit). The
   * wrapper removes itself after that one call.
   */
  watchFirstSubmit(device: GPUDevice): void {
    const queue = device.queue;
    const submit = queue.submit.bind(queue);
    queue.submit = (buffers: Iterable<GPUCommandBuffer>): undefined => {
      if (this.firstSubmit === null) {
        this.firstSubmit = this.now();
        const { user, system } = process.cpuUsage();
        this.firstSubmitCpu = (user + system) / 1000;
      }
      queue.submit = submit;
      return submit(buffers);
    };
  }

  report(): StartupReport {
    const phases: Record<string, PhaseSpan> = {};
    for (const [name, span] of this.spans)
      phases[name] = { start: round(span.start), end: round(span.end) };
    return {
      origin: 'process start (performance.timeOrigin)',
      nodeBootstrapMs: round(performance.nodeTiming.bootstrapComplete),
      phases,
      firstPassSubmittedMs: this.firstSubmit === null ? null : round(this.firstSubmit),
      firstPassCpuMs: this.firstSubmitCpu === null ? null : round(this.firstSubmitCpu),
    };
  }
}

function round(ms: number): number {
  return Math.round(ms * 100) / 100;
}
