// The refinement ladder (which rung each stage draws, learnt from measured costs) and
// the time slicer that keeps main-thread work under the long-task threshold, and the
// base element's state machine of stages, background refinement and settledness.
import { describe, expect, it } from 'vitest';
import {
  Ladder,
  PREVIEW_WORK_SHARE,
  RefinementState,
  showsWhenStale,
  TimeSlicer,
  whenIdle,
  yieldToPage,
  type Rung,
} from '../../src/widgets/base/refinement.ts';

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

  it('starts at the finest rung the measured cost fits into the preview’s share of the first-picture budget', () => {
    const ladder = new Ladder(RUNGS, 100, 0);
    // 3 ms per unit of work: 16 units = 48 ms fits PREVIEW_WORK_SHARE × 100 ms, 64 = 192 does not.
    ladder.record(0, 3);
    expect(ladder.pick({ stage: 0 }).index).toBe(2);
    // 5 ms per unit: 16 units = 80 ms would fit the whole budget, but not the preview's share
    // (the rest is the input, the work in flight and the drawing).
    const tighter = new Ladder(RUNGS, 100, 0);
    tighter.record(0, 5);
    expect(PREVIEW_WORK_SHARE * 100).toBeLessThan(80);
    expect(tighter.pick({ stage: 0 }).index).toBe(1);
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

  it('predicts a measured rung by its own time, not by the work ratio of another', () => {
    // A fixed part of every frame: the full picture (64 units) takes 64 ms, but the rung of
    // 16 units 150 ms (photon-map's coarse previews cost far more than their work says).
    const ladder = new Ladder(RUNGS, 100, 0);
    ladder.record(3, 64);
    expect(ladder.fitting(100)).toBe(3);
    ladder.record(2, 150);
    expect(ladder.predicted(2)).toBe(150);
    // Rung 1 is not measured: scaled from the nearest measured rung (2), 150 × 4/16.
    expect(ladder.predicted(1)).toBeCloseTo(37.5, 9);
    // The full picture still fits 100 ms: the finest fitting rung is chosen.
    expect(ladder.fitting(100)).toBe(3);
    ladder.record(3, 300); // now smoothed to 182
    expect(ladder.fitting(100)).toBe(1);
    expect(ladder.pick({ stage: 0 }).index).toBe(1);
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

describe('RefinementState', () => {
  /** A render as the base element does it: request, then report the frame's pending. */
  const render = (
    state: RefinementState,
    pending: 'frame' | 'job' | 'background' | null,
  ): { stage: number; background: boolean; next: string | null; settled: boolean } => {
    const request = state.request();
    const next = state.report(pending, request.version);
    return { stage: request.stage, background: request.background, next, settled: state.settled };
  };

  it('climbs previews unsettled, settles on a complete frame and stops on full quality', () => {
    const state = new RefinementState();
    state.input();
    expect(render(state, 'frame')).toEqual({
      stage: 0,
      background: false,
      next: 'frame',
      settled: false,
    });
    expect(render(state, 'frame')).toMatchObject({ stage: 1, next: 'frame', settled: false });
    expect(render(state, null)).toMatchObject({ stage: 2, next: null, settled: true });
    // Nothing asked for more: a later render (a move, a redraw) is a new picture.
    expect(state.request()).toMatchObject({ stage: 0, background: false });
    expect(state.settled).toBe(false);
  });

  it('background frames follow a complete picture and never unsettle it', () => {
    const state = new RefinementState();
    state.input();
    render(state, 'frame');
    expect(render(state, 'background')).toMatchObject({
      stage: 1,
      background: false,
      next: 'background',
      settled: true,
    });
    const version = state.inputVersion;
    expect(state.wantsBackground(version)).toBe(true);
    // The background frame is asked as such, and it stays settled whatever it reports
    // ('frame' from a confused view, a job's step meanwhile), until the work is done.
    const request = state.request();
    expect(request).toMatchObject({ stage: 2, background: true });
    expect(state.settled).toBe(true);
    expect(state.report('frame', request.version)).toBe('frame');
    expect(state.settled).toBe(true);
    expect(state.report('job')).toBe(null);
    expect(state.settled).toBe(true);
    // A job's report (no version) may ask for the next frame, taken as the current inputs'.
    expect(state.report('frame')).toBe('frame');
    expect(state.settled).toBe(true);
    expect(render(state, 'background')).toMatchObject({ background: false, settled: true });
    expect(render(state, null)).toMatchObject({ background: true, next: null, settled: true });
    expect(state.wantsBackground(version)).toBe(false);
  });

  it('an input during background refinement starts again at stage 0, unsettled', () => {
    const state = new RefinementState();
    state.input();
    render(state, 'background');
    const before = state.inputVersion;
    state.request(); // a background frame is in flight…
    state.input(); // …when the reader moves a slider
    expect(state.settled).toBe(false);
    expect(state.wantsBackground(before)).toBe(false); // the idle callback does nothing
    // The frame in flight lands for the old inputs: it neither settles nor continues.
    expect(state.report('background', before)).toBe(null);
    expect(state.settled).toBe(false);
    expect(state.report(null, before)).toBe(null);
    expect(state.settled).toBe(false);
    expect(render(state, 'frame')).toMatchObject({ stage: 0, background: false, settled: false });
  });

  it('stale frames never settle, whatever they report', () => {
    for (const pending of ['frame', 'job', 'background', null] as const) {
      const state = new RefinementState();
      state.input();
      const old = state.request();
      state.input();
      expect(state.report(pending, old.version)).toBe(null);
      expect(state.settled).toBe(false);
      // The next render is stage 0 for the new inputs, not a continuation of the stale one.
      expect(state.request()).toMatchObject({ stage: 0, background: false });
    }
  });

  it('a stale first picture is shown during a drag, a stale later stage or background frame is not', () => {
    const state = new RefinementState();
    state.input();
    const first = state.request();
    expect(showsWhenStale(first)).toBe(true);
    expect(state.report('frame', first.version)).toBe('frame');
    const second = state.request();
    expect(second.stage).toBe(1);
    expect(showsWhenStale(second)).toBe(false);
    expect(state.report('background', second.version)).toBe('background');
    const background = state.request();
    expect(background).toMatchObject({ stage: 2, background: true });
    expect(showsWhenStale(background)).toBe(false);
    // An input while the next first picture is drawn: shown, but it neither settles the
    // widget nor continues; the new inputs' stage 0 follows.
    state.input();
    const dragged = state.request();
    state.input();
    expect(showsWhenStale(dragged)).toBe(true);
    expect(state.report('frame', dragged.version)).toBe(null);
    expect(state.settled).toBe(false);
    expect(state.request()).toMatchObject({ stage: 0, background: false });
  });

  it('a job report before the picture was complete keeps it unsettled; a restart unsettles', () => {
    const state = new RefinementState();
    state.input();
    expect(render(state, 'job')).toMatchObject({ next: null, settled: false });
    expect(state.report('job')).toBe(null);
    expect(state.settled).toBe(false);
    expect(state.report(null)).toBe(null);
    expect(state.settled).toBe(true);
    // A job step after full quality (not background) says the picture is incomplete again.
    expect(state.report('job')).toBe(null);
    expect(state.settled).toBe(false);
    // A redraw of a settled background picture is a restart: unsettled until it reports.
    render(state, 'background');
    expect(state.settled).toBe(true);
    state.cancelNext();
    expect(state.request()).toMatchObject({ stage: 0, background: false });
    expect(state.settled).toBe(false);
  });

  it('a render without a frame settles only for the current inputs', () => {
    const state = new RefinementState();
    state.input();
    const { version } = state.request();
    state.input();
    state.settleWithoutFrame(version);
    expect(state.settled).toBe(false);
    state.settleWithoutFrame(state.request().version);
    expect(state.settled).toBe(true);
  });
});

describe('whenIdle', () => {
  it('runs the callback later, not synchronously', async () => {
    let ran = false;
    const done = new Promise<void>((resolve) =>
      whenIdle(() => {
        ran = true;
        resolve();
      }),
    );
    expect(ran).toBe(false);
    await done;
    expect(ran).toBe(true);
  });
});
