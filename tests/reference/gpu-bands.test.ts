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
