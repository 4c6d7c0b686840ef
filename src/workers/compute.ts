// Heavy CPU work off the main thread: `workerJobs('<widget>')` runs the functions of
// that widget's jobs.ts in one shared compute worker, one job at a time, and caches
// results by job and arguments, so a float64 reference is computed once per parameter
// set however often the widget redraws. A job whose callers all gave up (their
// signals aborted, e.g. the reader moved the slider on) before it started is dropped
// from the queue; one already running finishes and is kept in the cache. Where there is
// no Worker (Node, Vitest) or it fails to start, jobs run in the page instead.
import type { JobTable } from './jobs.ts';
import type { JobRequest, JobResponse } from './protocol.ts';

/** How many results each widget's cache keeps (least recently used go first). */
const DEFAULT_CACHE_SIZE = 24;

interface QueuedJob {
  request: JobRequest;
  /** Settles with the job's result. */
  done: Promise<unknown>;
  /** Callers still waiting; at 0 before the job starts, it is dropped. */
  interested: number;
  started: boolean;
  resolve(value: unknown): void;
  reject(error: Error): void;
}

/** The page's one compute worker, its queue, and the in-page fallback. */
class ComputeQueue {
  private worker: Worker | null = null;
  private broken = typeof Worker === 'undefined';
  private readonly queue: QueuedJob[] = [];
  private running: QueuedJob | null = null;
  private nextId = 1;

  enqueue(widget: string, name: string, args: readonly unknown[]): QueuedJob {
    let resolve!: (value: unknown) => void;
    let reject!: (error: Error) => void;
    const done = new Promise<unknown>((res, rej) => {
      resolve = res;
      reject = rej;
    });
    const job: QueuedJob = {
      request: { id: this.nextId++, widget, name, args },
      interested: 0,
      started: false,
      resolve,
      reject,
      done,
    };
    this.queue.push(job);
    queueMicrotask(() => this.pump());
    return job;
  }

  /** Starts the next job nobody gave up on, if none is running. */
  private pump(): void {
    if (this.running) return;
    let job: QueuedJob | undefined;
    while ((job = this.queue.shift())) {
      if (job.interested > 0) break;
      job.reject(abortError());
    }
    if (!job) return;
    this.running = job;
    job.started = true;
    if (this.broken) void this.runInPage(job);
    else this.send(job);
  }

  private finish(job: QueuedJob): void {
    if (this.running === job) this.running = null;
    this.pump();
  }

  private async runInPage(job: QueuedJob): Promise<void> {
    try {
      const { runJob } = await import('./jobs.ts');
      const { widget, name, args } = job.request;
      job.resolve(await runJob(widget, name, args));
    } catch (error) {
      job.reject(error instanceof Error ? error : new Error(String(error)));
    } finally {
      this.finish(job);
    }
  }

  private send(job: QueuedJob): void {
    const worker = this.ensureWorker();
    if (!worker) {
      void this.runInPage(job);
      return;
    }
    worker.postMessage(job.request);
  }

  private ensureWorker(): Worker | null {
    if (this.worker || this.broken) return this.worker;
    try {
      this.worker = new Worker(new URL('./compute.worker.ts', import.meta.url), {
        type: 'module',
        name: 'scatterbook-compute',
      });
    } catch {
      this.broken = true;
      return null;
    }
    this.worker.onmessage = (event: MessageEvent<JobResponse>) => {
      const job = this.running;
      if (!job || job.request.id !== event.data.id) return;
      if (event.data.ok) job.resolve(event.data.result);
      else job.reject(new Error(event.data.error));
      this.finish(job);
    };
    // A worker that cannot load (a blocked module, an old browser) or crashes: the
    // job it held and every later job run in the page, slower but correct.
    this.worker.onerror = (event) => {
      event.preventDefault();
      this.broken = true;
      this.worker?.terminate();
      this.worker = null;
      const job = this.running;
      if (job) void this.runInPage(job);
    };
    return this.worker;
  }
}

let sharedQueue: ComputeQueue | null = null;

function abortError(): Error {
  return new DOMException('the job is no longer needed', 'AbortError');
}

/** Arguments as a cache key: JSON, with typed arrays written as plain arrays. */
export function cacheKey(name: string, args: readonly unknown[]): string {
  return `${name}(${JSON.stringify(args, (_key, value: unknown) =>
    ArrayBuffer.isView(value) && !(value instanceof DataView)
      ? Array.from(value as unknown as ArrayLike<number>)
      : value,
  )})`;
}

export interface JobOptions {
  /** Aborting it rejects this call's promise with an AbortError (the result may still be cached). */
  signal?: AbortSignal;
  /**
   * The cache key, where the caller has a cheaper one than the JSON of the arguments
   * (a hash of a large scene): it must identify the name and the arguments exactly.
   */
  key?: string;
}

type Result<F> = F extends (...args: never[]) => infer R ? Awaited<R> : never;
type Args<F> = F extends (...args: infer A) => unknown ? A : never;

/** A widget's jobs, run off the main thread and cached by arguments. */
export interface WorkerJobs<J extends JobTable> {
  run<K extends keyof J & string>(
    name: K,
    args: Args<J[K]>,
    options?: JobOptions,
  ): Promise<Result<J[K]>>;
  /** The cached result of a finished job, if any (to draw at once without waiting a frame). */
  cached<K extends keyof J & string>(name: K, args: Args<J[K]>): Result<J[K]> | undefined;
}

/**
 * The jobs of `widget` (its src/widgets/<widget>/jobs.ts). Type it with the table:
 * `workerJobs<typeof jobs>('dipole-profile')` after `import type { jobs } from './jobs.ts'`.
 */
export function workerJobs<J extends JobTable>(
  widget: string,
  cacheSize = DEFAULT_CACHE_SIZE,
): WorkerJobs<J> {
  interface Entry {
    job: QueuedJob;
    value?: unknown;
    settled: boolean;
  }
  /** Results and jobs in flight, least recently used first (Map keeps insertion order). */
  const cache = new Map<string, Entry>();
  const touch = (key: string, entry: Entry): void => {
    cache.delete(key);
    cache.set(key, entry);
    for (const [oldKey, old] of cache) {
      if (cache.size <= cacheSize) break;
      if (old.settled) cache.delete(oldKey);
    }
  };
  const enqueue = (key: string, name: string, args: readonly unknown[]): Entry => {
    sharedQueue ??= new ComputeQueue();
    const entry: Entry = { job: sharedQueue.enqueue(widget, name, args), settled: false };
    entry.job.done.then(
      (value) => {
        entry.value = value;
        entry.settled = true;
      },
      () => {
        // Failed or dropped: forget it, so that the next call runs it again.
        if (cache.get(key) === entry) cache.delete(key);
      },
    );
    return entry;
  };
  return {
    cached(name, args) {
      const entry = cache.get(cacheKey(name, args));
      return entry?.settled ? (entry.value as never) : undefined;
    },
    run(name, args, options = {}) {
      const { signal } = options;
      if (signal?.aborted) return Promise.reject(abortError());
      const key = options.key ?? cacheKey(name, args);
      let entry = cache.get(key);
      // A queued job everyone gave up on is about to be dropped: queue it afresh.
      const abandoned = entry && !entry.settled && !entry.job.started && entry.job.interested === 0;
      if (!entry || abandoned) entry = enqueue(key, name, args);
      touch(key, entry);
      if (entry.settled) return Promise.resolve(entry.value as never);
      const job = entry.job;
      job.interested += 1;
      return new Promise((resolve, reject) => {
        let waiting = true;
        const settle = (): boolean => {
          signal?.removeEventListener('abort', onAbort);
          const was = waiting;
          waiting = false;
          return was;
        };
        const onAbort = (): void => {
          if (!settle()) return;
          job.interested -= 1;
          reject(abortError());
        };
        signal?.addEventListener('abort', onAbort, { once: true });
        job.done.then(
          (value) => {
            if (settle()) resolve(value as never);
          },
          (error: unknown) => {
            if (settle()) reject(error instanceof Error ? error : new Error(String(error)));
          },
        );
      });
    },
  };
}
