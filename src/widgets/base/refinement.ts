// Progressive refinement: after any input a widget shows a first picture within a
// frame budget (a coarse rung: fewer pixels, samples or steps), then refines it in
// later frames up to full quality, each stage one frame of its own so that the page
// paints and takes input in between. The base element (definedElement.ts) counts the
// stages, restarts at stage 0 on every input and aborts a stale later stage's signal; a
// view chooses what each stage draws, usually with a Ladder, and says through
// WidgetView.refinement which stage a frame is and whether more will come. A picture
// that is complete for what the reader asked may still improve by itself (a Monte
// Carlo image accumulating samples): its frames are 'background' refinement, settled
// for the reader and the tests, drawn at low priority, and dropped on the next input.

/** After an input, the first picture should be on screen within this on WebGPU… */
export const GPU_FIRST_PICTURE_MS = 100;
/** …and within this with the CPU twin (issue 23: 100 ms and 200 ms on a CPU WebGPU). */
export const CPU_FIRST_PICTURE_MS = 200;
/**
 * Share of the first-picture budget a preview's own work may take: the budget runs from the
 * input to the picture on screen, and the rest goes to handling the input, waiting for the
 * GPU work in flight and drawing (together 20–40 ms on SwiftShader, firstPictureProbe).
 * A ladder picks its first rung by this share (Ladder.pick); volume-path-tracer sizes its
 * preview by it.
 */
export const PREVIEW_WORK_SHARE = 0.6;
/** Work on the main thread runs in slices of at most this (the long-task threshold). */
export const SLICE_MS = 50;
/** What a refinement stage after the first may cost (per frame): the page stays responsive. */
export const REFINE_STAGE_MS = 250;

/** What the base element asks of one frame. */
export interface FrameRequest {
  /** 0: the first frame after an input (within the first-picture budget); then 1, 2, …. */
  readonly stage: number;
  /**
   * Aborted when the inputs change again and this frame will not be shown, so it may stop
   * early: a later stage or a background frame. A first picture's (showsWhenStale) aborts
   * only on an input that comes when it is overdue (three first-picture budgets after it
   * started, definedElement.ts), or when the widget is destroyed.
   */
  readonly signal: AbortSignal;
  /**
   * Aborted once the inputs change after this request, whatever the stage: a view starts
   * no side work (a reference, an analysis, a saved measurement) from a frame whose
   * inputs are already stale, though the frame itself may still be shown.
   */
  readonly inputsChanged: AbortSignal;
  /**
   * True when the last frame was complete and asked for background refinement: this
   * frame improves a settled picture (the view may keep it small; an input cancels it).
   */
  readonly background?: boolean;
}

/**
 * Whether a frame drawn for inputs that changed meanwhile is still finished and shown: a
 * first picture (stage 0, not background) is. During a drag every input comes before the
 * last one's picture is done (inputs 16–50 ms apart, first pictures 20–90 ms on
 * SwiftShader), and dropping each of them froze the picture for the whole drag
 * (beer-law: 1 frame shown in a 1 s drag of 20 inputs, 16 drawn and dropped). It shows
 * its own inputs' picture and readouts, never settles the widget or asks for more
 * (RefinementState.report), and the latest inputs' first picture starts right after it.
 * A later stage or a background frame is dropped: that first picture comes next; so is a
 * first picture still drawing three first-picture budgets after it started when an input
 * comes (a rung that cost more than predicted would hold the drag's pictures back).
 */
export function showsWhenStale(request: { stage: number; background?: boolean }): boolean {
  return request.stage === 0 && request.background !== true;
}

/**
 * What comes after a reported frame: 'frame', the base asks for the next stage on the
 * next animation frame (a preview: not settled); 'job', the view's own job (a
 * reference, a training run) reports again by itself (not settled); 'background', the
 * picture is complete for these inputs (settled) and the base asks for further frames
 * at low priority while they improve it; null, this is full quality, nothing follows.
 */
export type Pending = 'frame' | 'job' | 'background' | null;

/** What a reported frame is. */
export interface Refinement {
  /** Shown to the reader: e.g. "Preview: 64×64 pixels, 1 sample per pixel". */
  label: string;
  pending: Pending;
}

/** Whether a frame with this `pending` shows a complete picture (data-settled). */
export function isComplete(pending: Pending): boolean {
  return pending === null || pending === 'background';
}

/** What the base draws next after a report: nothing, the next stage now, or a background frame. */
export type NextFrame = 'frame' | 'background' | null;

/**
 * The base element's refinement state, apart from the DOM (definedElement.ts drives
 * it; tests/widgets/refinement.test.ts checks it). Every input bumps the version; a
 * render asks `request()` which stage to draw; a frame's report says whether the
 * picture is settled and what to draw next. The rules:
 * - an input (or a redraw that is not a continuation) starts again at stage 0, unsettled;
 * - a frame rendered for inputs that changed since never settles the widget and never
 *   asks for more (its successor for the new inputs does);
 * - a frame saying 'background' or null settles it; 'frame' or 'job' unsettles it,
 *   except once background refinement of these inputs began: background frames (and
 *   a job's reports meanwhile) never flip it back to unsettled, only an input or a
 *   restart does.
 */
export class RefinementState {
  private version = 0;
  private renderedVersion = -1;
  private stage = 0;
  private next: NextFrame = null;
  /** The input version whose picture is complete (null: none yet). */
  private settledVersion: number | null = null;
  /** The input version whose frames are background refinement of a complete picture. */
  private backgroundVersion: number | null = null;

  /** The current input version (a render captures it to report with). */
  get inputVersion(): number {
    return this.version;
  }

  /** Whether the picture shown is complete for the current inputs. */
  get settled(): boolean {
    return this.settledVersion === this.version;
  }

  /** Whether a background frame is wanted for `version` (checked when its low-priority turn comes). */
  wantsBackground(version: number): boolean {
    return this.next === 'background' && version === this.version;
  }

  /** New inputs: the next request is stage 0 and the picture is not settled. */
  input(): void {
    this.version += 1;
    this.next = null;
  }

  /** Drops a requested continuation (a fall back to the CPU draws a new stage 0). */
  cancelNext(): void {
    this.next = null;
  }

  /**
   * What this render draws: the next stage when the last frame asked for one (a stage or a
   * background frame) for the same inputs; otherwise stage 0 of a new picture (an input, a
   * redraw, a move), which is not settled until it reports.
   */
  request(): { stage: number; version: number; background: boolean } {
    const continuing = this.next !== null && this.renderedVersion === this.version;
    const background = continuing && this.next === 'background';
    this.stage = continuing ? this.stage + 1 : 0;
    this.renderedVersion = this.version;
    this.next = null;
    if (!continuing) {
      this.settledVersion = null;
      this.backgroundVersion = null;
    }
    return { stage: this.stage, version: this.version, background };
  }

  /**
   * A frame was shown. `version` is the input version it was rendered for (absent: a
   * view's job reported by itself, taken as current). Returns what to draw next.
   */
  report(pending: Pending, version?: number): NextFrame {
    const drawnFor = version ?? this.version;
    if (drawnFor !== this.version) return null; // stale: neither settles nor continues
    if (isComplete(pending)) this.settledVersion = drawnFor;
    // A job's step or a stage after background refinement began keeps the picture
    // settled; before that (a preview, a job a full frame started) it is not complete.
    else if (this.backgroundVersion !== drawnFor) this.settledVersion = null;
    if (pending === 'background') this.backgroundVersion = drawnFor;
    // A job's report may ask for the next stage too (as before background refinement).
    if (pending === 'frame' || pending === 'background') this.next = pending;
    return pending === 'frame' || pending === 'background' ? pending : null;
  }

  /** A render that returned no frame (it drew by itself): complete if the view has no refinement. */
  settleWithoutFrame(version: number): void {
    if (version === this.version) this.settledVersion = version;
  }
}

/**
 * Runs `callback` when the page has nothing more urgent to do: a background-priority
 * task (scheduler.postTask) where there is one, else an idle callback (at most 100 ms
 * late), else a plain task. Background refinement waits for this, so an input, another
 * widget's first picture or the page's own rendering go first.
 */
export function whenIdle(callback: () => void): void {
  const scheduler = (
    globalThis as {
      scheduler?: {
        postTask?: (task: () => void, options: { priority: string }) => Promise<unknown>;
      };
    }
  ).scheduler;
  if (scheduler?.postTask) {
    void scheduler.postTask(callback, { priority: 'background' }).catch(() => undefined);
    return;
  }
  if (typeof requestIdleCallback === 'function') {
    requestIdleCallback(() => callback(), { timeout: 100 });
    return;
  }
  setTimeout(callback, 0);
}

/** The first-picture budget of a backend. */
export function firstPictureBudget(backend: 'gpu' | 'cpu'): number {
  return backend === 'gpu' ? GPU_FIRST_PICTURE_MS : CPU_FIRST_PICTURE_MS;
}

/** One rung of a ladder: a setting (a resolution, a sample count), its relative work and a label. */
export interface Rung<T> {
  value: T;
  /** Work relative to the other rungs (pixels × samples, steps…): cost is taken as proportional. */
  work: number;
  label: string;
}

/** The rung a frame draws, and whether it is the last (full quality). */
export interface RungChoice<T> {
  rung: Rung<T>;
  index: number;
  final: boolean;
}

/**
 * A ladder of settings from coarse to full, climbed one rung per stage. Stage 0 starts on
 * the finest rung whose predicted cost fits the preview's share of the first-picture
 * budget (PREVIEW_WORK_SHARE), so a fast GPU starts high and a CPU WebGPU starts low.
 * Before any measurement it starts on the lowest rung.
 *
 * The cost of a rung is learnt from the frames drawn on it (record): a rung measured before
 * is predicted by its own time; one not measured yet by the nearest measured rung's time
 * scaled by the ratio of their work. A frame's time is rarely proportional to its work: a
 * fixed part (dispatches, read-backs, a march over the pixels) made photon-map's coarsest
 * previews cost a quarter of its full picture, not the 1/25 their work says, and one cost
 * per unit of work learnt mostly from the full pictures picked previews of 80–130 ms for a
 * budget of 100 (issue 23).
 */
export class Ladder<T> {
  private current = 0;
  /** Each rung's time (ms), smoothed over its recent frames (null: never drawn). */
  private readonly measured: (number | null)[];

  constructor(
    readonly rungs: readonly Rung<T>[],
    private readonly firstBudgetMs: number,
    private readonly stageBudgetMs = REFINE_STAGE_MS,
  ) {
    if (rungs.length === 0) throw new Error('a ladder needs at least one rung');
    this.measured = rungs.map(() => null);
  }

  /**
   * The rung of this stage: at stage 0 the finest rung predicted to fit the preview's share
   * of the first-picture budget (PREVIEW_WORK_SHARE); after that at least one rung up, or
   * straight to the finest rung predicted to fit a refinement stage's budget (a fast GPU
   * skips the rungs it does not need).
   */
  pick(request: Pick<FrameRequest, 'stage'>): RungChoice<T> {
    const last = this.rungs.length - 1;
    this.current =
      request.stage === 0
        ? this.fitting(PREVIEW_WORK_SHARE * this.firstBudgetMs)
        : Math.min(Math.max(this.current + 1, this.fitting(this.stageBudgetMs)), last);
    return { rung: this.rungs[this.current]!, index: this.current, final: this.current === last };
  }

  /** The predicted time (ms) of rung `index`, or null before any rung was measured. */
  predicted(index: number): number | null {
    const own = this.measured[index];
    if (own !== null && own !== undefined) return own;
    let nearest = -1;
    this.measured.forEach((ms, j) => {
      if (ms !== null && (nearest < 0 || Math.abs(j - index) < Math.abs(nearest - index)))
        nearest = j;
    });
    if (nearest < 0) return null;
    return (this.measured[nearest]! * this.rungs[index]!.work) / this.rungs[nearest]!.work;
  }

  /** The index of the finest rung predicted to cost at most `budgetMs` (0 before any measurement). */
  fitting(budgetMs: number): number {
    let best = 0;
    this.rungs.forEach((_, index) => {
      const ms = this.predicted(index);
      if (ms !== null && ms <= budgetMs) best = index;
    });
    return best;
  }

  /** Learns the cost of a frame drawn on rung `index` (exponentially smoothed, α = ½). */
  record(index: number, milliseconds: number): void {
    const rung = this.rungs[index];
    if (!rung || !(milliseconds >= 0) || !(rung.work > 0)) return;
    const before = this.measured[index];
    this.measured[index] =
      before === null || before === undefined ? milliseconds : 0.5 * (before + milliseconds);
  }

  /** The refinement of a frame drawn on `choice`. */
  refinement(choice: RungChoice<T>): Refinement {
    return {
      label: choice.final ? choice.rung.label : `Preview: ${choice.rung.label}`,
      pending: choice.final ? null : 'frame',
    };
  }
}

/**
 * Gives the page a turn: the browser paints and handles input before the work goes on.
 * scheduler.yield where there is one (it keeps the task's priority), else a message
 * (a macrotask without setTimeout's 4 ms clamp).
 */
export function yieldToPage(): Promise<void> {
  const scheduler = (globalThis as { scheduler?: { yield?: () => Promise<void> } }).scheduler;
  if (scheduler?.yield) return scheduler.yield();
  if (typeof MessageChannel === 'undefined')
    return new Promise((resolve) => setTimeout(resolve, 0));
  return new Promise((resolve) => {
    const channel = new MessageChannel();
    channel.port1.onmessage = () => {
      channel.port1.close();
      resolve();
    };
    channel.port2.postMessage(null);
  });
}

/**
 * A loop's time slicer: `await slicer.pause()` inside long CPU work yields to the page
 * once the current slice has run for `sliceMs`, so no task is longer than about that.
 * It throws the signal's reason when the work went stale while it waited.
 */
export class TimeSlicer {
  private sliceStart = performance.now();

  constructor(
    private readonly signal?: AbortSignal,
    private readonly sliceMs = SLICE_MS * 0.6,
  ) {}

  /** True when the slice is used up (check it every few iterations: performance.now is cheap). */
  due(): boolean {
    return performance.now() - this.sliceStart >= this.sliceMs;
  }

  /** Yields if the slice is used up; throws if aborted (before or after yielding). */
  async pause(): Promise<void> {
    this.signal?.throwIfAborted();
    if (!this.due()) return;
    await yieldToPage();
    this.signal?.throwIfAborted();
    this.sliceStart = performance.now();
  }
}
