// A cancellable convergence sweep shared by the image widgets: renders at
// n = 1, 2, 4, …, 256 (steps, samples per pixel, …), yielding to the page
// between renders so input, painting and Cancel stay live; plots RMSE against
// the time per render on a log–log plot and fits the slope of log RMSE against
// log n. The widget supplies the render and the readouts; this owns the run and
// Cancel buttons, the progress bar, the status line, the plot and its hint.
import { LinePlot } from './plot.ts';

/** The sweep's points: powers of two from 1 to 256. */
export const SWEEP_POINTS = [1, 2, 4, 8, 16, 32, 64, 128, 256] as const;

/**
 * Least-squares slope of log error against log n, so error ∝ n^slope.
 * Points with a zero (or non-finite) error are left out; null with fewer than
 * two usable points or when all n are equal.
 */
export function logLogSlope(n: readonly number[], errors: readonly number[]): number | null {
  const points = n
    .map((x, i) => [Math.log(x), Math.log(errors[i] ?? 0)] as const)
    .filter(([, y]) => Number.isFinite(y));
  if (points.length < 2) return null;
  const meanX = points.reduce((s, [x]) => s + x, 0) / points.length;
  const meanY = points.reduce((s, [, y]) => s + y, 0) / points.length;
  let sxy = 0;
  let sxx = 0;
  for (const [x, y] of points) {
    sxy += (x - meanX) * (y - meanY);
    sxx += (x - meanX) ** 2;
  }
  return sxx > 0 ? sxy / sxx : null;
}

/** One measured point of a sweep. */
export interface SweepPoint {
  n: number;
  rmse: number;
  milliseconds: number;
}

/** What one run of the sweep does; the widget builds it once the backend is known. */
export interface SweepJob {
  /** Renders with n and measures it. */
  measure(n: number): Promise<Omit<SweepPoint, 'n'>>;
  /** Legend label of the plotted curve. */
  label: string;
  /** Called after the last point; returns what the "Sweep done: …" status names. */
  finish(points: readonly SweepPoint[]): string;
  /** Called when a render failed (the status line already says why). */
  failed(): void;
}

export interface SweepOptions {
  /** The name of the swept quantity in the status line ("N", "spp"). */
  name: string;
  /** Text of the run button. */
  buttonText: string;
  /** The hint shown in place of the plot until the first point. */
  hint: string;
  /** Colour of the RMSE curve. */
  color: string;
  /** An extra class on the status line, kept for the widget's existing selectors. */
  statusClass?: string;
}

export class SweepControls {
  private readonly plot: LinePlot;
  private plotHint: HTMLElement | null;
  private readonly runButton: HTMLButtonElement;
  private readonly cancelButton: HTMLButtonElement;
  private readonly progress: HTMLProgressElement;
  private readonly status: HTMLElement;
  private token = 0;

  /**
   * Appends the hint, the plot and the controls to stage.
   * @param host gets `data-sweeping` while a sweep runs.
   * @param onRun called by the run button (the widget starts `run` from it).
   */
  constructor(
    stage: HTMLElement,
    private readonly host: HTMLElement,
    private readonly options: SweepOptions,
    onRun: () => void,
  ) {
    const plotArea = document.createElement('div');
    plotArea.className = 'sb-plot';
    plotArea.setAttribute('role', 'img');
    plotArea.setAttribute('aria-label', 'Log–log plot of RMSE against time per render');
    this.plotHint = document.createElement('p');
    this.plotHint.className = 'sb-sweep-hint';
    this.plotHint.textContent = options.hint;
    stage.append(this.plotHint, plotArea);
    this.plot = new LinePlot(plotArea, {
      xLabel: 'log₁₀ time per render (ms)',
      yLabel: 'RMSE',
      yLog: true,
      height: 240,
    });

    const bar = document.createElement('div');
    bar.className = 'sb-sweep';
    this.runButton = document.createElement('button');
    this.runButton.type = 'button';
    this.runButton.className = 'sb-button';
    this.runButton.textContent = options.buttonText;
    this.runButton.addEventListener('click', onRun);
    this.cancelButton = document.createElement('button');
    this.cancelButton.type = 'button';
    this.cancelButton.className = 'sb-button';
    this.cancelButton.textContent = 'Cancel';
    this.cancelButton.disabled = true;
    this.cancelButton.addEventListener('click', () => this.cancel('cancelled'));
    this.progress = document.createElement('progress');
    this.progress.max = SWEEP_POINTS.length;
    this.progress.value = 0;
    this.progress.setAttribute('aria-label', 'Sweep progress');
    this.status = document.createElement('span');
    this.status.className = 'sb-sweep-status';
    if (options.statusClass) this.status.classList.add(options.statusClass);
    this.status.setAttribute('aria-live', 'polite');
    this.status.textContent = 'No sweep yet.';
    bar.append(this.runButton, this.cancelButton, this.progress, this.status);
    stage.appendChild(bar);
  }

  /** Stops a running sweep (Cancel, device loss); the status says `Sweep ${message}.`. */
  cancel(message: string): void {
    if (!this.cancelButton.disabled) {
      this.token += 1;
      this.status.textContent = `Sweep ${message}.`;
      this.setSweeping(false);
    }
  }

  /**
   * Runs the sweep. `prepare` builds the job (it may wait for the backend); a
   * later run or a cancel supersedes this one, which then stops quietly.
   */
  async run(prepare: () => Promise<SweepJob>): Promise<void> {
    const token = ++this.token;
    const job = await prepare();
    this.setSweeping(true);
    const points: SweepPoint[] = [];
    try {
      for (const [k, n] of SWEEP_POINTS.entries()) {
        if (token !== this.token) return;
        this.status.textContent = `${this.options.name} = ${n} (${k + 1} of ${SWEEP_POINTS.length})…`;
        const measured = await job.measure(n);
        if (token !== this.token) return;
        points.push({ n, ...measured });
        this.progress.value = k + 1;
        this.plotPoints(points, job.label);
        // Let the page breathe between renders: input, painting and Cancel stay live.
        await new Promise((resolve) => setTimeout(resolve, 0));
      }
    } catch (error) {
      if (token === this.token) {
        job.failed();
        this.status.textContent = `Sweep failed: ${error instanceof Error ? error.message : String(error)}`;
        this.setSweeping(false);
      }
      return;
    }
    this.status.textContent = `Sweep done: ${job.finish(points)}.`;
    this.setSweeping(false);
  }

  private setSweeping(on: boolean): void {
    this.runButton.disabled = on;
    this.cancelButton.disabled = !on;
    this.host.toggleAttribute('data-sweeping', on);
  }

  private plotPoints(points: readonly SweepPoint[], label: string): void {
    // uPlot wants ascending x: sort the points by time. At small n the fixed cost
    // of a dispatch dominates, so time is not monotone in n.
    const sorted = [...points].sort((a, b) => a.milliseconds - b.milliseconds);
    const x = sorted.map((p) => Math.log10(Math.max(p.milliseconds, 1e-4)));
    this.plotHint?.remove();
    this.plotHint = null;
    this.plot.update(x, [
      { label: `RMSE, ${label}`, color: this.options.color, values: sorted.map((p) => p.rmse) },
    ]);
  }
}
