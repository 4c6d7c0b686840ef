// The refinement ladder (which rung each stage draws, learnt from measured costs) and
// the time slicer that keeps main-thread work under the long-task threshold.
import { describe, expect, it } from 'vitest';
import { Ladder, TimeSlicer, yieldToPage, type Rung } from '../../src/widgets/base/refinement.ts';

const RUNGS: Rung<number>[] = [
  { value: 32, work: 1, label: '32 px' },
  { value: 64, work: 4, label: '64 px' },
  { value: 128, work: 16, label: '128 px' },
  { value: 256, work: 64, label: '256 px' },
];

describe('Ladder', () => {
  it('starts on the lowest rung before anything is measured and climbs one rung per stage', () => {
    const ladder = new Ladder(RUNGS, 100, 0);
    expect(ladder.pick({ stage: 0 }).index).toBe(0);
    expect(ladder.pick({ stage: 1 }).index).toBe(1);
    expect(ladder.pick({ stage: 2 }).index).toBe(2);
    const last = ladder.pick({ stage: 3 });
    expect(last.index).toBe(3);
    expect(last.final).toBe(true);
    // Past the top it stays there (a redraw of the last stage).
    expect(ladder.pick({ stage: 4 }).index).toBe(3);
  });

  it('starts at the finest rung the measured cost fits into the first-picture budget', () => {
    const ladder = new Ladder(RUNGS, 100, 0);
    ladder.record(0, 5); // 5 ms per unit of work: 16 units = 80 ms fits, 64 = 320 ms does not
    expect(ladder.pick({ stage: 0 }).index).toBe(2);
    const slow = new Ladder(RUNGS, 100, 0);
    slow.record(0, 150); // even the lowest rung is over budget: still draw it
    expect(slow.pick({ stage: 0 }).index).toBe(0);
  });

  it('skips to the finest rung a refinement stage can afford', () => {
    const ladder = new Ladder(RUNGS, 100, 1000);
    ladder.record(1, 4); // 1 ms per unit: everything fits in 1 s
    ladder.pick({ stage: 0 });
    expect(ladder.pick({ stage: 1 }).index).toBe(3);
  });

  it('smooths the cost estimate and ignores nonsense measurements', () => {
    const ladder = new Ladder(RUNGS, 100, 0);
    ladder.record(0, Number.NaN);
    ladder.record(7, 1);
    expect(ladder.fitting(100)).toBe(0); // nothing valid measured yet
    ladder.record(3, 64 * 10); // 10 ms per unit
    ladder.record(3, 64 * 2); // then 2: smoothed to 6
    expect(ladder.fitting(100)).toBe(2); // 16 × 6 = 96 ≤ 100 < 64 × 6
  });

  it('labels previews and full quality, and asks for the next stage only before the top', () => {
    const ladder = new Ladder(RUNGS, 100, 0);
    const first = ladder.pick({ stage: 0 });
    expect(ladder.refinement(first)).toEqual({ label: 'Preview: 32 px', pending: 'frame' });
    ladder.pick({ stage: 1 });
    ladder.pick({ stage: 2 });
    expect(ladder.refinement(ladder.pick({ stage: 3 }))).toEqual({
      label: '256 px',
      pending: null,
    });
  });

  it('refuses an empty ladder', () => {
    expect(() => new Ladder([], 100)).toThrow(/at least one rung/);
  });
});

describe('TimeSlicer', () => {
  it('yields once a slice is used up and throws when the work went stale', async () => {
    const aborter = new AbortController();
    const slicer = new TimeSlicer(aborter.signal, 20);
    while (!slicer.due());
    await slicer.pause();
    // The pause started a new slice (a slice of 20 ms cannot be used up by one expect).
    expect(slicer.due()).toBe(false);
    aborter.abort();
    await expect(slicer.pause()).rejects.toThrow();
  });

  it('yieldToPage resolves', async () => {
    await expect(yieldToPage()).resolves.toBeUndefined();
  });
});
