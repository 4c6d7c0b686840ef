// Writing the widgets' state into the URL (urlState.ts) costs a history.replaceState
// per change, which Chromium measured at 11–19 ms of main-thread time per input on
// this project's SwiftShader machine (issue 23: the largest script cost of a drag on
// delta-tracking and dipole-profile, ahead of their drawing). A drag sends ~20 inputs a
// second; the link only needs the last. The writer writes at once when it has been
// quiet for `intervalMs` (a single change shows in the URL straight away, as before),
// and otherwise once at the end of the interval with the newest state.

/** At most one URL write per this many milliseconds during a drag. */
export const STATE_WRITE_INTERVAL_MS = 200;

export interface WriterClock {
  now(): number;
  setTimeout(callback: () => void, ms: number): unknown;
  clearTimeout(handle: unknown): void;
}

const PAGE_CLOCK: WriterClock = {
  now: () => performance.now(),
  setTimeout: (callback, ms) => setTimeout(callback, ms),
  clearTimeout: (handle) => clearTimeout(handle as ReturnType<typeof setTimeout>),
};

export class ThrottledWriter {
  private lastWrite = -Infinity;
  private timer: unknown = null;
  private pending: (() => void) | null = null;

  constructor(
    private readonly intervalMs = STATE_WRITE_INTERVAL_MS,
    private readonly clock: WriterClock = PAGE_CLOCK,
  ) {}

  /** Runs `write` now if the writer has been quiet long enough, else at the interval's end (the newest write wins). */
  write(write: () => void): void {
    const now = this.clock.now();
    if (this.timer === null && now - this.lastWrite >= this.intervalMs) {
      this.lastWrite = now;
      write();
      return;
    }
    this.pending = write;
    this.timer ??= this.clock.setTimeout(
      () => this.flush(),
      Math.max(0, this.lastWrite + this.intervalMs - now),
    );
  }

  /** Runs a write still waiting, now (before the element goes, or when the link is read). */
  flush(): void {
    if (this.timer !== null) this.clock.clearTimeout(this.timer);
    this.timer = null;
    const write = this.pending;
    this.pending = null;
    if (!write) return;
    this.lastWrite = this.clock.now();
    write();
  }
}
