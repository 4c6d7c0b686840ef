// src/gpu/bands.ts, the cutting of long GPU work into bands of rows (issue 23), with a fake
// GPU: every row once and in order, bands sized from the measured time per row, no more in
// flight than asked, an aborted signal stopping before the next band only after the bands
// in flight are back, and a failed band failing the call.
import { describe, expect, it } from 'vitest';
import { bandRows, runInBands, type Band, type BandOptions } from '../../src/gpu/bands.ts';

const OPTIONS: BandOptions = { budgetMs: 10, firstRows: 4, inFlight: 2 };

/** A GPU that takes `msPerRow` per row; it records what is in flight. */
function fakeGpu(msPerRow: number) {
  const state = { submitted: [] as Band[], inFlight: 0, largest: 0, done: 0 };
  const run = async (band: Band) => {
    state.submitted.push(band);
    state.inFlight += 1;
    state.largest = Math.max(state.largest, state.inFlight);
    await new Promise((resolve) => setTimeout(resolve, 1));
    state.inFlight -= 1;
    state.done += 1;
    return { milliseconds: msPerRow * band.rows };
  };
  return { state, run };
}

describe('bands of rows', () => {
  it('cover every row once, in order, sized to the budget once timed; a last sliver joins its band', async () => {
    const { state, run } = fakeGpu(2);
    const { bands, msPerRow } = await runInBands(3, 40, OPTIONS, run);
    expect(bands.map((b) => b.start)).toEqual(state.submitted.map((b) => b.start));
    let next = 3;
    for (const band of bands) {
      expect(band.start).toBe(next);
      next += band.rows;
    }
    expect(next).toBe(40);
    // Two untimed bands of 4 rows, then 10 ms / 2 ms = 5 rows each.
    expect(bands.slice(0, 2).map((b) => b.rows)).toEqual([4, 4]);
    expect(bands.slice(2, -1).every((b) => b.rows === 5)).toBe(true);
    expect(msPerRow).toBe(2);
    expect(state.largest).toBe(2);
    expect(bandRows(8, 2, OPTIONS)).toBe(5);
    expect(bandRows(7, 2, OPTIONS)).toBe(7); // 2 rows left would be less than half a band
    expect(bandRows(3, 2, OPTIONS)).toBe(3);
    expect(bandRows(5, null, { ...OPTIONS, fixedRows: 2 })).toBe(2);
    expect(bandRows(3, null, OPTIONS)).toBe(3);
  });

  it('one band at a time when asked, and a known time per row sizes the first band', async () => {
    const { state, run } = fakeGpu(1);
    await runInBands(0, 30, { ...OPTIONS, inFlight: 1, msPerRow: 1 }, run);
    expect(state.largest).toBe(1);
    expect(state.submitted[0]!.rows).toBe(10);
  });

  it('with the rows’ own predicted times, expensive rows get bands of their own, and each call measures them', async () => {
    // 40 rows: cheap (0.5 ms) except rows 10–19 (4 ms each), as a sphere across an image.
    const cost = Float64Array.from({ length: 40 }, (_, row) => (row >= 10 && row < 20 ? 4 : 0.5));
    const submitted: Band[] = [];
    const run = async (band: Band) => {
      submitted.push(band);
      let ms = 0;
      for (let row = band.start; row < band.start + band.rows; row++) ms += cost[row]!;
      return { milliseconds: ms };
    };
    const first = await runInBands(0, 40, { ...OPTIONS, inFlight: 1, msPerRow: 1 }, run);
    // The measured time of each row is its band's time shared evenly: their sum is the total.
    const total = cost.reduce((a, b) => a + b, 0);
    expect(first.rowMs.reduce((a, b) => a + b, 0)).toBeCloseTo(total, 9);
    submitted.length = 0;
    await runInBands(0, 40, { ...OPTIONS, inFlight: 1, rowMs: cost }, run);
    // No band predicted (and, here, measured) over the budget but a single row's, or one
    // that took in a rest of under half a budget (at most 1.5 budgets).
    for (const band of submitted) {
      let ms = 0;
      for (let row = band.start; row < band.start + band.rows; row++) ms += cost[row]!;
      expect(ms <= 1.5 * OPTIONS.budgetMs || band.rows === 1, `${band.start}+${band.rows}`).toBe(
        true,
      );
    }
    // The expensive rows are cut where they start: none of rows 10–19 shares a band with
    // more than one cheap row before it.
    for (const band of submitted) {
      const expensive = [...Array(band.rows).keys()].filter((k) => cost[band.start + k]! > 1);
      if (expensive.length > 0) expect(expensive.length).toBeLessThanOrEqual(2);
    }
    expect(bandRows(30, null, { ...OPTIONS, rowMs: cost }, 10)).toBe(2); // 4 + 4 ms ≤ 10
    expect(bandRows(20, null, { ...OPTIONS, rowMs: cost }, 20)).toBe(20); // 20 × 0.5 = 10 ms
    expect(bandRows(4, null, { ...OPTIONS, rowMs: cost }, 36)).toBe(4); // a 2-ms rest joins
  });

  it('an aborted signal submits nothing more and rejects once the bands in flight are back', async () => {
    const { state, run } = fakeGpu(1);
    const controller = new AbortController();
    const call = runInBands(0, 100, { ...OPTIONS, signal: controller.signal }, async (band) => {
      const result = await run(band);
      controller.abort();
      return result;
    });
    await expect(call).rejects.toMatchObject({ name: 'AbortError' });
    expect(state.submitted.length).toBeLessThanOrEqual(OPTIONS.inFlight);
    expect(state.inFlight).toBe(0);
    expect(state.done).toBe(state.submitted.length);
  });

  it('a failed band fails the call', async () => {
    const failing = async (band: Band) => {
      await new Promise((resolve) => setTimeout(resolve, 1));
      if (band.start > 0) throw new Error('device lost');
      return { milliseconds: 1 };
    };
    await expect(runInBands(0, 20, OPTIONS, failing)).rejects.toThrow('device lost');
  });
});
