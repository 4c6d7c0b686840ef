// Refinement past full quality for the progressive scene widgets (volume-path-tracer,
// single-scatter): once a frame of the reader's samples per pixel is up, the image
// keeps accumulating (and the reference with it) without going through the base
// element's render(). A render() is stage 0 of a new picture for the base, which marks
// the widget unsettled until its frame reports, so accumulating through render() made
// data-settled flicker to "false" on every frame for minutes. Here each further frame
// is reported with context.report: the readouts and the picture update, and the widget
// stays settled. A new input (the context's inputSignal), a destroyed widget, a widget
// scrolled out of view, or the view's own render() stops the loop; a render() waits for
// the frame in flight first (halt), so two frames never add passes to one image at once.
import type { FrameBackend } from '../widgets/base/definition.ts';
import type { ViewContext } from '../widgets/base/view.ts';

const nextAnimationFrame = (): Promise<void> =>
  new Promise((resolve) => requestAnimationFrame(() => resolve()));

/** Whether the widget's shell is on screen (the base draws only then, or when presenting). */
function onScreen(host: HTMLElement): boolean {
  if (document.visibilityState !== 'visible') return false;
  const shell = host.querySelector('.sb-widget') ?? host;
  const box = shell.getBoundingClientRect();
  return box.bottom > 0 && box.top < innerHeight && box.width > 0;
}

export class BackgroundRefinement<Frame> {
  private token = 0;
  private inFlight: Promise<unknown> = Promise.resolve();

  constructor(private readonly context: ViewContext<unknown>) {}

  /** Stops the loop now (its frame in flight is dropped; before freeing what it draws). */
  stop(): void {
    this.token++;
  }

  /** Stops the loop and waits for its frame in flight (call before a render adds passes). */
  async halt(): Promise<void> {
    this.token++;
    await this.inFlight;
  }

  /**
   * Reports `step()`'s frames, one per animation frame, while `more()` says there is
   * work. `step` gets the input signal of the moment the loop started.
   */
  start(step: (signal: AbortSignal) => Promise<Frame | null>, more: () => boolean): void {
    const token = ++this.token;
    const { context } = this;
    const signal = context.inputSignal;
    const destroyed = context.signal;
    const stale = (): boolean => token !== this.token || signal.aborted || destroyed.aborted;
    void (async () => {
      const backend = await context.backend();
      const where: FrameBackend =
        backend.kind === 'gpu'
          ? { kind: 'gpu', adapterDescription: backend.gpu.adapterDescription }
          : { kind: 'cpu', reason: backend.reason };
      for (;;) {
        await nextAnimationFrame();
        if (stale() || !more()) return;
        if (!onScreen(context.host)) {
          // The base draws again when the widget comes back into view (then this loop restarts).
          context.scheduleRender();
          return;
        }
        const running = step(signal);
        this.inFlight = running.catch(() => undefined);
        let frame: Frame | null;
        try {
          frame = await running;
        } catch (error) {
          if (stale()) return;
          // A failed GPU frame: the CPU twin from now on, as a failed render() would.
          context.useCpu(error instanceof Error ? error.message : String(error));
          return;
        }
        if (stale() || frame === null) return;
        context.report(frame, where);
      }
    })();
  }
}
