// Jobs that run off the main thread: each widget that has heavy CPU work (float64
// references, sweeps, CPU-fallback pictures) exports `jobs` from its folder's jobs.ts,
// a table of plain functions from structured-cloneable arguments to a
// structured-cloneable result. The compute worker (compute.worker.ts) and the
// in-page fallback (compute.ts, where there is no Worker) load a widget's table
// lazily by folder name, so a page pulls in only the jobs of the widgets it shows.

/** A widget's job table: name → function (sync or async). */
export type JobTable = Readonly<Record<string, (...args: never[]) => unknown>>;

/** The module every `src/widgets/<name>/jobs.ts` is. */
export interface JobModule {
  jobs: JobTable;
}

/** Lazy loaders of the widgets' job modules, keyed by widget folder. */
const MODULES = import.meta.glob<JobModule>('../widgets/*/jobs.ts');

/** Loads widget `widget`'s job table (throws for a widget without jobs.ts). */
export async function loadJobs(widget: string): Promise<JobTable> {
  const load = MODULES[`../widgets/${widget}/jobs.ts`];
  if (!load) throw new Error(`the widget "${widget}" has no jobs.ts`);
  return (await load()).jobs;
}

/** Runs one job by name (in the worker, or in the page without one). */
export async function runJob(
  widget: string,
  name: string,
  args: readonly unknown[],
): Promise<unknown> {
  const table = await loadJobs(widget);
  const job = table[name] as ((...a: readonly unknown[]) => unknown) | undefined;
  if (!job) throw new Error(`the widget "${widget}" has no job "${name}"`);
  return job(...args);
}

/**
 * The buffers of typed arrays in a result, moved to the page instead of copied
 * (a float64 reference image can be megabytes).
 */
export function transferables(value: unknown, found: Set<ArrayBuffer> = new Set()): ArrayBuffer[] {
  if (ArrayBuffer.isView(value)) {
    if (value.buffer instanceof ArrayBuffer) found.add(value.buffer);
  } else if (value instanceof ArrayBuffer) found.add(value);
  else if (Array.isArray(value)) for (const item of value) transferables(item, found);
  else if (value !== null && typeof value === 'object')
    for (const item of Object.values(value)) transferables(item, found);
  return [...found];
}
