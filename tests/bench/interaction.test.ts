// The pure judgement behind bench/interaction.ts: when a change counts as shown and as
// settled, total blocking time, and the slider values a change and a drag use. No
// timings are asserted: the inputs are made-up logs.
import { describe, expect, it } from 'vitest';
import {
  changeValues,
  dragValues,
  firstShown,
  framesBetween,
  judgeChange,
  longestTask,
  observation,
  snap,
  tasksWithin,
  totalBlockingTime,
  type Observation,
} from '../../bench/interactionJudge.ts';

function obs(t: number, frames: number, settled: boolean | null = null, stage = ''): Observation {
  return { t, frames, settled, stage: stage || null, frameMs: null, timer: null };
}

describe('observation', () => {
  it('prefers data-frames over data-rendered and parses the cost', () => {
    const raw = {
      t: 5,
      frames: '7',
      rendered: '3',
      settled: 'false',
      stage: 'preview',
      frameMs: '12.5',
      timer: 'wall',
    };
    expect(observation(raw)).toEqual({
      t: 5,
      frames: 7,
      settled: false,
      stage: 'preview',
      frameMs: 12.5,
      timer: 'wall',
    });
    const old = { ...raw, frames: null, settled: null, frameMs: null };
    expect(observation(old)).toMatchObject({ frames: 3, settled: null, frameMs: null });
  });
});

describe('judgeChange with data-settled', () => {
  it('waits for settled after the first new frame, ignoring the stale "true" before it', () => {
    const log = [
      obs(0, 4, true),
      obs(100, 4, false),
      obs(130, 5, false, 'preview'),
      obs(400, 6, true),
    ];
    const outcome = judgeChange(log, 90, 4, 500);
    expect(outcome.settledBy).toBe('data-settled');
    expect(outcome.firstPicture?.t).toBe(130);
    expect(outcome.firstPicture?.stage).toBe('preview');
    expect(outcome.settled?.t).toBe(400);
  });

  it('is not settled while the latest state says refining, even after an earlier "true"', () => {
    const log = [obs(100, 5, true), obs(200, 5, false), obs(300, 6, false)];
    expect(judgeChange(log, 50, 4, 10_000).settled).toBeNull();
  });

  it('takes the start of the final settled run when a job started after a settled frame', () => {
    const log = [obs(100, 5, true), obs(150, 5, false), obs(900, 6, true), obs(950, 6, true)];
    expect(judgeChange(log, 50, 4, 1000).settled?.t).toBe(900);
  });

  it('counts a first frame that is already full quality as settled at once', () => {
    const log = [obs(0, 1, true), obs(40, 2, true)];
    const outcome = judgeChange(log, 10, 1, 41);
    expect(outcome.firstPicture?.t).toBe(40);
    expect(outcome.settled?.t).toBe(40);
  });

  it('has no first picture before the counter moves', () => {
    const log = [obs(0, 1, true), obs(20, 1, false)];
    expect(judgeChange(log, 10, 1, 5000)).toMatchObject({ firstPicture: null, settled: null });
  });
});

describe('judgeChange without data-settled (older builds)', () => {
  const log = [obs(0, 2), obs(150, 3), obs(700, 4), obs(1300, 5)];

  it('is settled once the counter has been still for the quiet time, at its last move', () => {
    const outcome = judgeChange(log, 100, 2, 2400);
    expect(outcome.settledBy).toBe('quiet');
    expect(outcome.firstPicture?.t).toBe(150);
    expect(outcome.settled?.t).toBe(1300);
  });

  it('is not settled while frames keep coming within the quiet time', () => {
    expect(judgeChange(log, 100, 2, 2200).settled).toBeNull();
    expect(judgeChange(log, 100, 2, 2200, 500).settled?.t).toBe(1300);
  });

  it('ignores frames from before the input', () => {
    expect(judgeChange(log, 800, 4, 5000).firstPicture?.t).toBe(1300);
    expect(judgeChange(log, 1400, 5, 5000)).toMatchObject({ firstPicture: null, settled: null });
  });
});

describe('framesBetween', () => {
  it('counts the increase of the counter within the window', () => {
    const log = [obs(0, 2), obs(150, 3), obs(700, 4), obs(1300, 5)];
    expect(framesBetween(log, 100, 1000, 2)).toBe(2);
    expect(framesBetween(log, 1400, 2000, 5)).toBe(0);
  });
});

describe('long tasks', () => {
  const tasks = [
    { startTime: 0, duration: 120 },
    { startTime: 500, duration: 50 },
    { startTime: 900, duration: 310 },
    { startTime: 3000, duration: 80 },
  ];

  it('sums the part of each task beyond 50 ms (total blocking time)', () => {
    expect(totalBlockingTime(tasks)).toBe(70 + 0 + 260 + 30);
    expect(totalBlockingTime([])).toBe(0);
  });

  it('keeps tasks that overlap the window, including one running at its start', () => {
    expect(tasksWithin(tasks, 100, 2000).map((t) => t.startTime)).toEqual([0, 500, 900]);
    expect(tasksWithin(tasks, 120, 2000).map((t) => t.startTime)).toEqual([500, 900]);
  });

  it('reports the longest task, or none', () => {
    expect(longestTask(tasks)).toBe(310);
    expect(longestTask([])).toBeNull();
  });
});

describe('slider values', () => {
  it('snaps to the step grid inside the range, printed as the step', () => {
    expect(snap({ min: 0, max: 10, step: 0.01 }, 6.0000001)).toBe(6);
    expect(snap({ min: 0.05, max: 4, step: 0.05 }, 0.05 + 0.6 * 3.95)).toBe(2.4);
    expect(snap({ min: 1, max: 16, step: 1 }, 99)).toBe(16);
    expect(snap({ min: -0.99, max: 0.99, step: 0.01 }, -5)).toBe(-0.99);
  });

  it('alternates between 60 % of the range and the initial value, or its neighbour', () => {
    expect(changeValues({ min: 0, max: 10, step: 0.01 }, 0.2)).toEqual([6, 0.2]);
    expect(changeValues({ min: 0, max: 10, step: 1 }, 6)).toEqual([6, 5]);
    expect(changeValues({ min: 6, max: 10, step: 4 }, 10)).toEqual([10, 6]);
  });

  it('drags from min to max with every value differing from the one before', () => {
    const values = dragValues({ min: 0, max: 1, step: 0.01 }, 20);
    expect(values).toHaveLength(20);
    expect(values[0]).toBe(0);
    expect(values[19]).toBe(1);
    for (let i = 1; i < values.length; i++) expect(values[i]).not.toBe(values[i - 1]);
  });

  it('drags over every step and back when the slider has fewer steps than inputs', () => {
    const values = dragValues({ min: 1, max: 4, step: 1 }, 8);
    expect(values).toEqual([1, 2, 3, 4, 3, 2, 1, 2]);
    expect(dragValues({ min: 3, max: 3, step: 1 }, 20)).toEqual([]);
  });
});

describe('firstShown', () => {
  it('is the first animation frame after the counter passed frames0, at or after t0', () => {
    const shown = [
      { frames: 4, t: 50 },
      { frames: 5, t: 80 },
      { frames: 6, t: 420 },
      { frames: 7, t: 500 },
    ];
    // Frame 5 was shown before the input: it does not count.
    expect(firstShown(shown, 100, 5)).toEqual({ frames: 6, t: 420 });
    expect(firstShown(shown, 100, 7)).toBeNull();
    expect(firstShown([], 0, 0)).toBeNull();
  });
});
