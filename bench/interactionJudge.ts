// The pure part of bench/interaction.ts: what the page recorded (attribute changes of
// the widget element with their times, long tasks) turned into the numbers a reader
// feels. Kept apart from the browser driving so that it can be unit-tested
// (tests/bench/interaction.test.ts).

/** One snapshot of the widget element's attributes, taken when one of them changed. */
export interface RawObservation {
  /** performance.now() in the page. */
  t: number;
  frames: string | null;
  rendered: string | null;
  settled: string | null;
  stage: string | null;
  frameMs: string | null;
  timer: string | null;
}

export interface Observation {
  t: number;
  /** Frames shown so far: data-frames, or data-rendered where the build has no data-frames. */
  frames: number;
  /** data-settled as a boolean; null where the build does not set it. */
  settled: boolean | null;
  stage: string | null;
  frameMs: number | null;
  timer: string | null;
}

export function observation(raw: RawObservation): Observation {
  const count = raw.frames ?? raw.rendered;
  const frameMs = raw.frameMs === null ? NaN : Number(raw.frameMs);
  return {
    t: raw.t,
    frames: count === null ? 0 : Number(count) || 0,
    settled: raw.settled === null ? null : raw.settled === 'true',
    stage: raw.stage,
    frameMs: Number.isFinite(frameMs) ? frameMs : null,
    timer: raw.timer,
  };
}

/** How a change was judged finished: the element's data-settled, or frames quiet for a while. */
export type SettledBy = 'data-settled' | 'quiet';

export interface ChangeOutcome {
  /** The first observation with a new frame after the input. */
  firstPicture: Observation | null;
  /** When the widget showed full quality for the new input; null while it has not. */
  settled: Observation | null;
  settledBy: SettledBy;
}

/**
 * Judges one input from the log of observations (in time order).
 *
 * - first picture: the first observation at or after `t0` whose frame count exceeds
 *   `frames0` (the count when the input was given);
 * - settled, where the element sets data-settled (the build has the attribute in its
 *   latest observation): the start of the final run of observations that are all
 *   settled and all past the input's first frame — a widget that said "settled" and then
 *   started another automatic job is not settled until it says so again;
 * - settled, for builds without data-settled: the frame counter moved past `frames0`
 *   and has not moved for `quietMs` up to `now`; full quality is then the last frame.
 */
export function judgeChange(
  log: readonly Observation[],
  t0: number,
  frames0: number,
  now: number,
  quietMs = 1000,
): ChangeOutcome {
  const latest = log[log.length - 1];
  const settledBy: SettledBy = latest && latest.settled !== null ? 'data-settled' : 'quiet';
  const after = log.filter((o) => o.t >= t0);
  const firstPicture = after.find((o) => o.frames > frames0) ?? null;
  if (!firstPicture || !latest) return { firstPicture, settled: null, settledBy };
  if (settledBy === 'data-settled') {
    let start: Observation | null = null;
    for (let i = after.length - 1; i >= 0; i--) {
      const o = after[i];
      if (!o || o.settled !== true || o.frames <= frames0 || o.t < firstPicture.t) break;
      start = o;
    }
    return { firstPicture, settled: start, settledBy };
  }
  if (latest.frames <= frames0 || now - latestFrameChange(after, latest).t < quietMs)
    return { firstPicture, settled: null, settledBy };
  return { firstPicture, settled: latestFrameChange(after, latest), settledBy };
}

/** The observation where the frame count reached its latest value. */
function latestFrameChange(after: readonly Observation[], latest: Observation): Observation {
  return after.find((o) => o.frames === latest.frames) ?? latest;
}

/** Frames shown between two times (the counter's increase). */
export function framesBetween(
  log: readonly Observation[],
  from: number,
  to: number,
  framesAtFrom: number,
): number {
  let last = framesAtFrom;
  for (const o of log) if (o.t >= from && o.t <= to) last = o.frames;
  return Math.max(0, last - framesAtFrom);
}

/** A PerformanceLongTaskTiming, reduced to what is compared. */
export interface LongTask {
  startTime: number;
  duration: number;
}

/** Long tasks that end after `from` and start before `to` (a task running at `from` counts). */
export function tasksWithin(tasks: readonly LongTask[], from: number, to: number): LongTask[] {
  return tasks.filter((task) => task.startTime + task.duration > from && task.startTime < to);
}

/** The browser's threshold of a long task (Long Tasks API, and total blocking time in Lighthouse). */
export const LONG_TASK_MS = 50;

/** Total blocking time: the sum over long tasks of the part beyond 50 ms. */
export function totalBlockingTime(tasks: readonly LongTask[]): number {
  return tasks.reduce((sum, task) => sum + Math.max(0, task.duration - LONG_TASK_MS), 0);
}

/** The page's next animation frame after the frame counter reached `frames` (the recorder's log of them). */
export interface ShownFrame {
  frames: number;
  t: number;
}

/**
 * When the input's first picture reached the screen: the first animation frame that
 * came after the counter passed `frames0`, at or after `t0` (null when none was logged).
 * A widget's frame counter moves when it has drawn; the page shows the drawing with its
 * next frame, which on a software adapter under load can come hundreds of ms later.
 */
export function firstShown(
  shown: readonly ShownFrame[],
  t0: number,
  frames0: number,
): ShownFrame | null {
  return shown.find((s) => s.t >= t0 && s.frames > frames0) ?? null;
}

/** The longest task's duration, or null when there was none (every task under 50 ms). */
export function longestTask(tasks: readonly LongTask[]): number | null {
  return tasks.length === 0 ? null : Math.max(...tasks.map((task) => task.duration));
}

/** Decimals of a slider step (0.01 → 2), so that values print as the slider would. */
function decimals(step: number): number {
  const text = String(step);
  const exponent = /e-(\d+)$/.exec(text);
  if (exponent) return Number(exponent[1]);
  const dot = text.indexOf('.');
  return dot < 0 ? 0 : text.length - dot - 1;
}

export interface Slider {
  min: number;
  max: number;
  step: number;
}

/** The slider value nearest `x` on its step grid, inside [min, max]. */
export function snap(slider: Slider, x: number): number {
  const { min, max, step } = slider;
  const steps = Math.floor((max - min) / step + 1e-9);
  const index = Math.min(Math.max(Math.round((x - min) / step), 0), steps);
  return Number((min + index * step).toFixed(decimals(step)));
}

/**
 * The two values a single change alternates between: 60 % of the range, and the
 * widget's own value (or the neighbouring step where the two coincide).
 */
export function changeValues(slider: Slider, initial: number): [number, number] {
  const target = snap(slider, slider.min + 0.6 * (slider.max - slider.min));
  const home = snap(slider, initial);
  if (home !== target) return [target, home];
  const below = snap(slider, target - slider.step);
  return [target, below !== target ? below : snap(slider, target + slider.step)];
}

/**
 * A scripted drag of `count` inputs across the slider from min to max, each value
 * differing from the one before (a reader's drag gives no input without a move). A
 * slider with fewer steps than inputs is dragged over every step and back.
 */
export function dragValues(slider: Slider, count: number): number[] {
  const steps = Math.floor((slider.max - slider.min) / slider.step + 1e-9);
  if (steps <= 0) return [];
  const indices: number[] = [];
  if (steps + 1 >= count) {
    // Spacing of at least one step: rounding keeps consecutive values distinct.
    for (let i = 0; i < count; i++) indices.push(Math.round((i * steps) / (count - 1)));
  } else {
    let index = 0;
    let direction = 1;
    for (let i = 0; i < count; i++) {
      indices.push(index);
      if (index + direction > steps || index + direction < 0) direction = -direction;
      index += direction;
    }
  }
  return indices.map((index) => snap(slider, slider.min + index * slider.step));
}
