// Long GPU work in bands of image rows (issue 23). The GPU runs a dispatch to its end, so an
// input's preview queues behind whatever is in flight: a whole frame in one dispatch
// (transfer-function's 160² ray cast, translucent-render's octree gather, photon-map's
// gather) held the next picture back by 130–380 ms on SwiftShader. Cut into bands of about
// `budgetMs` of GPU time each, sized from the time per row measured on the bands before,
// the wait is one band; an input is checked before each band is submitted.

export interface BandOptions {
  /** GPU time one band may take (ms). */
  budgetMs: number;
  /** Rows of a band before any band has been timed (and no `msPerRow` is given). */
  firstRows: number;
  /**
   * Bands submitted before the first of them is read back: the next band runs while the
   * last one's result comes back (a read-back is a round trip of 10–20 ms in Chrome on
   * SwiftShader). 1 when the caller's bands share resources that must not overlap.
   */
  inFlight: number;
  /** GPU ms per row known from earlier work, to size the first band by; null if none. */
  msPerRow?: number | null;
  /** Rows per band instead of the budget (a test's fixed cut). */
  fixedRows?: number;
  /**
   * Predicted GPU ms of each row (indexed by row, e.g. the `rowMs` of the same kernel's
   * last call): bands are then cut where the predicted time reaches the budget, so rows that
   * cost several times the mean (a sphere across the middle of the image) get bands of their
   * own instead of joining a band sized by the cheap rows above them.
   */
  rowMs?: ArrayLike<number> | null;
  /** An input: no band is submitted once it is aborted, and the call rejects. */
  signal?: AbortSignal;
}

export interface Band {
  start: number;
  rows: number;
}

/** The rejection of work an input made stale (what a FrameRequest's consumers expect). */
export function abortError(what: string): DOMException {
  return new DOMException(`${what} is no longer needed`, 'AbortError');
}

/**
 * Rows of the next band at `msPerRow` (null: not timed yet), or by the predicted time of
 * each row from `start` on where `options.rowMs` gives it; a last sliver joins it.
 */
export function bandRows(
  remaining: number,
  msPerRow: number | null,
  options: BandOptions,
  start = 0,
): number {
  const predicted = options.rowMs;
  let rows: number;
  if (options.fixedRows !== undefined) rows = Math.max(1, Math.floor(options.fixedRows));
  else if (predicted && predicted.length >= start + remaining) {
    let sum = 0;
    rows = 0;
    while (rows < remaining && (rows === 0 || sum + predicted[start + rows]! <= options.budgetMs)) {
      sum += predicted[start + rows]!;
      rows += 1;
    }
    // What is left predicted at under half a band joins this one.
    let rest = 0;
    for (let row = start + rows; row < start + remaining; row++) rest += predicted[row]!;
    return rest < options.budgetMs / 2 && sum + rest <= 1.5 * options.budgetMs ? remaining : rows;
  } else
    rows =
      msPerRow === null
        ? options.firstRows
        : Math.max(1, Math.floor(options.budgetMs / Math.max(msPerRow, 1e-6)));
  // Less than half a band would be left: take it now rather than pay a read-back for it.
  return remaining - rows < rows / 2 ? remaining : rows;
}

/**
 * Runs rows [rowStart, rowEnd) band by band through `run`, which submits one band and
 * resolves with its GPU time once it is back. Resolves with every band's result in row
 * order and the time per row measured last. An aborted `signal` rejects with an
 * AbortError before the next band is submitted, after the bands in flight are back (their
 * resources may not be handed on while the GPU still writes them).
 */
export async function runInBands<T extends { milliseconds: number }>(
  rowStart: number,
  rowEnd: number,
  options: BandOptions,
  run: (band: Band) => Promise<T>,
): Promise<{ bands: (T & Band)[]; msPerRow: number | null; rowMs: Float64Array }> {
  let msPerRow = options.msPerRow ?? null;
  const inFlight: Promise<T & Band>[] = [];
  const bands: (T & Band)[] = [];
  const settle = async (): Promise<void> => {
    const band = await inFlight.shift()!;
    if (band.rows > 0 && band.milliseconds > 0) msPerRow = band.milliseconds / band.rows;
    bands.push(band);
  };
  let next = rowStart;
  try {
    while (next < rowEnd || inFlight.length > 0) {
      if (next < rowEnd && inFlight.length < Math.max(1, options.inFlight)) {
        if (options.signal?.aborted) {
          await Promise.allSettled(inFlight);
          throw abortError('the rest of this picture');
        }
        const band: Band = {
          start: next,
          rows: bandRows(rowEnd - next, msPerRow, options, next),
        };
        inFlight.push(run(band).then((result) => ({ ...result, ...band })));
        next += band.rows;
      } else {
        await settle();
      }
    }
  } catch (error) {
    // A failed band ends the call; the others' failures are not the caller's any more.
    for (const band of inFlight) band.catch(() => undefined);
    throw error;
  }
  // The measured time of each row (its band's time shared evenly), for the next call.
  const rowMs = new Float64Array(rowEnd);
  for (const band of bands)
    for (let row = band.start; row < band.start + band.rows; row++)
      rowMs[row] = band.milliseconds / band.rows;
  return { bands, msPerRow, rowMs };
}
