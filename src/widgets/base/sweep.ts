// A cancellable convergence sweep shared by the image widgets: renders at
// n = 1, 2, 4, …, 256 or the widget's own list (steps, samples per pixel, …),
// yielding to the page between renders so input, painting and Cancel stay live;
// plots RMSE (or the widget's error) against the time per render on a log–log
// plot and fits the slope of log RMSE against log n. The widget supplies the
// render and the readouts; this owns the run and Cancel buttons, the progress
// bar, the status line, the plot and its hint.
import { LinePlot, createPlotArea } from './plot.ts';

/** The sweep's points: powers of two from 1 to 256. */
export const SWEEP_POINTS = [1, 2, 4, 8, 16, 32, 64, 128, 256] as const;

/**
 * Least-squares slope of log error against log n (error ∝ n^slope), from
 * src/statistics/regression.ts; re-exported for the sweeps' callers.
 */
export { logLogSlope } from '../../statistics/regression.ts';

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

/** One curve of a sweep over several series (estimators, methods). */
export interface SweepSeries {
  label: string;
  color: string;
  /** Dash pattern, so that curves differ in more than colour. */
  dash?: number[];
}

/**
 * A sweep of several series in one plot: every n is measured for each series in
 * turn (n outermost), so a cancelled sweep still shows every series so far.
 */
export interface SeriesSweepJob {
  series: readonly SweepSeries[];
  /** Renders series s with n and measures it. */
  measure(series: number, n: number): Promise<Omit<SweepPoint, 'n'>>;
  /** Legend label of series s given its points so far (e.g. with a fitted slope). */
  label?(series: number, points: readonly SweepPoint[]): string;
  /** Called after the last point; returns what the "Sweep done: …" status names. */
  finish(points: readonly (readonly SweepPoint[])[]): string;
  /** Called when a render failed (the status line already says why). */
  failed(): void;
}

/**
 * Several series with their own times on one x axis, for uPlot: x is the sorted
 * union of log₁₀ ms, and each series has NaN where it has no point (a gap that
 * the plot bridges, LinePlot's `spanGaps`).
 */
export function mergeSeries(series: readonly (readonly SweepPoint[])[]): {
  x: number[];
  values: number[][];
} {
  const logTime = (p: SweepPoint): number => Math.log10(Math.max(p.milliseconds, 1e-4));
  const x = [...new Set(series.flatMap((points) => points.map(logTime)))].sort((a, b) => a - b);
  const column = new Map(x.map((value, i) => [value, i]));
  const values = series.map((points) => {
    const row = new Array<number>(x.length).fill(Number.NaN);
    for (const p of points) row[column.get(logTime(p))!] = p.rmse;
    return row;
  });
  return { x, values };
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
  /** The values of n to render, in order (default SWEEP_POINTS). */
  points?: readonly number[];
  /** What the error is called on the y axis and in the legend (default "RMSE"). */
  errorName?: string;
}

export class SweepControls {
  private readonly plot: LinePlot;
  private plotHint: HTMLElement | null;
  private readonly runButton: HTMLButtonElement;
  private readonly cancelButton: HTMLButtonElement;
  private readonly progress: HTMLProgressElement;
  private readonly status: HTMLElement;
  private token = 0;
  private readonly points: readonly number[];
  private readonly errorName: string;

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
    this.points = options.points ?? SWEEP_POINTS;
    this.errorName = options.errorName ?? 'RMSE';
    const plotArea = createPlotArea(`Log–log plot of ${this.errorName} against time per render`);
    this.plotHint = document.createElement('p');
    this.plotHint.className = 'sb-sweep-hint';
    this.plotHint.textContent = options.hint;
    stage.append(this.plotHint, plotArea);
    this.plot = new LinePlot(plotArea, {
      xLabel: 'log₁₀ time per render (ms)',
      yLabel: this.errorName,
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
    this.progress.max = this.points.length;
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
      for (const [k, n] of this.points.entries()) {
        if (token !== this.token) return;
        this.status.textContent = `${this.options.name} = ${n} (${k + 1} of ${this.points.length})…`;
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

  /**
   * Runs a sweep of several series (runSeries and run share the token, so either
   * supersedes the other); the progress bar counts points × series.
   */
  async runSeries(prepare: () => Promise<SeriesSweepJob>): Promise<void> {
    const token = ++this.token;
    const job = await prepare();
    if (token !== this.token) return;
    this.setSweeping(true);
    const points: SweepPoint[][] = job.series.map(() => []);
    const total = this.points.length * job.series.length;
    this.progress.max = total;
    this.progress.value = 0;
    let done = 0;
    try {
      for (const n of this.points) {
        for (const [s, series] of job.series.entries()) {
          if (token !== this.token) return;
          this.status.textContent = `${series.label}: ${this.options.name} = ${n} (${done + 1} of ${total})…`;
          const measured = await job.measure(s, n);
          if (token !== this.token) return;
          points[s]!.push({ n, ...measured });
          this.progress.value = ++done;
          this.plotSeries(job, points);
          // Let the page breathe between renders: input, painting and Cancel stay live.
          await new Promise((resolve) => setTimeout(resolve, 0));
        }
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

  private plotSeries(job: SeriesSweepJob, points: readonly (readonly SweepPoint[])[]): void {
    const { x, values } = mergeSeries(points);
    this.plotHint?.remove();
    this.plotHint = null;
    this.plot.update(
      x,
      job.series.map((series, s) => ({
        label: job.label?.(s, points[s]!) ?? series.label,
        color: series.color,
        ...(series.dash ? { dash: series.dash } : {}),
        spanGaps: true,
        values: values[s]!,
      })),
    );
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
      {
        label: `${this.errorName}, ${label}`,
        color: this.options.color,
        values: sorted.map((p) => p.rmse),
      },
    ]);
  }
}
