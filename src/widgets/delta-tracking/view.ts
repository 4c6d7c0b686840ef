// The drawing of <sb-delta-tracking>: the single view (estimated T and its variance,
// painted on 2D canvases from either backend, and the sweep over spp) and the
// comparison view (all five estimators at equal samples and equal time, a long job
// with its own readouts, table and sweep of all five). The single view's readouts,
// the backend choice and the fallback are widget.ts's and the base element's.
import type { GpuContext } from '../../gpu/device.ts';
import type { Backend } from '../base/backend.ts';
import type { FrameCost } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel } from '../base/timing.ts';
import {
  gradientCss,
  imageCanvas,
  imageFigure,
  imagePanel,
  niceScale,
} from '../base/imagePanel.ts';
import { ReadoutList } from '../base/readoutList.ts';
import { SweepControls, type SweepPoint } from '../base/sweep.ts';
import { logLogSlope } from '../../statistics/regression.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import { LadderFamily } from '../base/ladderFamily.ts';
import {
  CPU_FIRST_PICTURE_MS,
  GPU_FIRST_PICTURE_MS,
  type FrameRequest,
  type Refinement,
} from '../base/refinement.ts';
import {
  CALIBRATION_RUNS,
  CALIBRATION_SPP,
  CALIBRATION_TARGET_MS,
  CALIBRATION_WARMUP,
  ESTIMATOR_ORDER,
  FIT_MIN_SPP,
  SERIES_STYLE,
  TIMING_RUNS,
  calibrationSpp,
  costPerSample,
  isEstimatorKey,
  median,
  planEqualTime,
  sppSlope,
  timeSlope,
  type EstimatorKey,
} from './compare.ts';
import { CompareGrid, CompareTable, type CompareCell, type CompareRow } from './compareView.ts';
import { CPU_HEIGHT, CPU_WIDTH, paintImages, renderCpu } from './cpuBackend.ts';
import { DeltaTrackingGpu } from './gpuBackend.ts';
import {
  ESTIMATOR_NAMES,
  IMAGE_HEIGHT,
  IMAGE_WIDTH,
  SPP_MAX,
  exactImage,
  imageStatistics,
  inputsFrom,
  sampleVariance,
  transmittanceColour,
  varianceColour,
  withEstimator,
  type TrackingImage,
  type TrackingInputs,
} from './model.ts';
import { sampleRungs } from './stages.ts';
import { MAJORANT_NAMES, type TrackingFrame } from './widget.ts';

const COMPARE_ROWS = [
  ['budget', 'Equal-time budget'],
  ['best-samples', 'Lowest RMSE, equal samples'],
  ['best-time', 'Lowest RMSE, equal time'],
  ['timing', 'Times measured with'],
] as const;

/** One image on the backend in use, the exact T, and what it cost. */
interface Measured {
  image: TrackingImage;
  exact: Float64Array;
  milliseconds: number;
  timing: FrameCost['timing'];
}

/** Cost per sample of each estimator on one backend and majorant, measured once. */
interface Calibration {
  costs: Record<EstimatorKey, number>;
  /** The spp of each estimator's timed calibration renders. */
  spp: Record<EstimatorKey, number>;
  how: string;
}

type View = 'single' | 'compare';

/** The estimator's name for text. */
function nameOf(estimator: string): string {
  return ESTIMATOR_NAMES[estimator] ?? estimator;
}

/** What the comparison's images depend on (the grid setting only repaints). */
function compareKey(inputs: TrackingInputs, backend: string): string {
  return [backend, inputs.estimator, inputs.spp, inputs.majorant, inputs.seed].join('|');
}

class DeltaTrackingView implements WidgetView<TrackingFrame, DeltaTrackingGpu> {
  private imageCanvas: HTMLCanvasElement | null = null;
  private varianceCanvas: HTMLCanvasElement | null = null;
  private scaleTop: HTMLElement | null = null;
  private sweep: SweepControls | null = null;

  constructor(private readonly context: ViewContext<DeltaTrackingGpu>) {}

  // The two views: each has its stage content and readouts, and only the shown
  // view's are in the document (so each view's selectors find one of each).
  private view: View | null = null;
  private stageHost: HTMLElement | null = null;
  private readoutHost: HTMLElement | null = null;
  private readonly singleStage = document.createElement('div');
  private readonly compareStage = document.createElement('div');
  private readonly singleReadout = document.createElement('div');
  private readonly compareReadout = document.createElement('div');
  private grid: CompareGrid | null = null;
  private table: CompareTable | null = null;
  private compareReadouts: ReadoutList | null = null;
  private sweepAll: SweepControls | null = null;
  /** Costs per sample, per backend and majorant: measured once, then reused. */
  private readonly calibrations = new Map<string, Calibration>();
  /** compareKey of the images the grid holds ('' before the first). */
  private gridKey = '';

  build(stage: HTMLElement): void {
    this.stageHost = stage;
    this.singleStage.className = 'sb-dt-view';
    this.compareStage.className = 'sb-dt-view';
    this.buildSingleStage(this.singleStage);
    this.buildCompareStage(this.compareStage);
  }

  private buildSingleStage(stage: HTMLElement): void {
    this.imageCanvas = imageCanvas('Estimated transmittance image', IMAGE_WIDTH, IMAGE_HEIGHT);
    this.varianceCanvas = imageCanvas('Per-pixel variance image', IMAGE_WIDTH, IMAGE_HEIGHT);
    const variance = imagePanel(this.varianceCanvas, 'Variance of one estimate, per pixel', {
      gradient: gradientCss((x) => varianceColour(x, 1)),
      low: '0',
      top: { readout: 'variance-scale' },
    });
    this.scaleTop = variance.top;
    stage.appendChild(
      imageFigure(
        imagePanel(this.imageCanvas, 'Estimated T (mean of spp samples)', {
          gradient: gradientCss(transmittanceColour),
          low: '0',
          top: { text: '1' },
        }).panel,
        variance.panel,
      ),
    );
    this.sweep = new SweepControls(
      stage,
      this.context.host,
      {
        name: 'spp',
        buttonText: 'Run sweep spp = 1 … 256',
        hint: 'Run the sweep to plot RMSE against the time per render for spp = 1, 2, 4, …, 256. An unbiased estimator falls as spp^(−½); a biased one levels off at its bias.',
        color: '#3b7dd8',
        statusClass: 'sb-dt-sweep-status',
      },
      () => void this.runSweep(),
    );
  }

  private buildCompareStage(stage: HTMLElement): void {
    this.grid = new CompareGrid(this.context.widgetId);
    stage.appendChild(this.grid.element);
    this.sweepAll = new SweepControls(
      stage,
      this.context.host,
      {
        name: 'spp',
        buttonText: 'Sweep all five, spp = 1 … 256',
        hint: 'Run the sweep to plot the RMSE of all five estimators against the time per render, for spp = 1, 2, 4, …, 256 each. Unbiased estimators keep falling with slope −½; the biased exp(−τ̂) levels off at its bias.',
        color: SERIES_STYLE.delta.color,
        statusClass: 'sb-dt-sweepall-status',
      },
      () => void this.runSweepAll(),
    );
  }

  /**
   * The base element's readout list (the single view's rows and cost line) moves into
   * the single view's container; the comparison has a list and a table of its own.
   */
  buildReadoutExtras(readout: HTMLElement): void {
    this.readoutHost = readout;
    this.singleReadout.append(...readout.childNodes);
    this.compareReadouts = new ReadoutList(this.compareReadout, COMPARE_ROWS);
    this.table = new CompareTable();
    this.compareReadout.insertBefore(this.table.element, this.compareReadouts.cost);
    this.showView(inputsFrom(this.context.values).view);
  }

  /**
   * Shows one view's stage and readouts; a sweep of the other view is cancelled.
   * The "Comparison shows" control only matters in the comparison, and there the
   * estimator control picks the estimator whose time sets the budget.
   */
  private showView(view: View): void {
    if (view === this.view) return;
    if (this.view !== null)
      (view === 'compare' ? this.sweep : this.sweepAll)?.cancel('stopped: the view changed');
    this.view = view;
    this.context.host.dataset['view'] = view;
    this.stageHost?.replaceChildren(view === 'compare' ? this.compareStage : this.singleStage);
    this.readoutHost?.replaceChildren(
      view === 'compare' ? this.compareReadout : this.singleReadout,
    );
    const gridControl = this.context.host.querySelector(
      `#${CSS.escape(`${this.context.widgetId}-grid`)}`,
    );
    const wrapper = gridControl?.closest<HTMLElement>('.sb-control');
    if (wrapper) wrapper.hidden = view !== 'compare';
    const label = this.context.host.querySelector(
      `label[for="${CSS.escape(`${this.context.widgetId}-estimator`)}"]`,
    );
    if (label)
      label.textContent =
        view === 'compare' ? 'Estimator that sets the equal-time budget' : 'Estimator';
  }

  private set(key: string, text: string, state?: 'ok' | 'bad'): void {
    this.context.setReadout(key, text, state);
  }

  /** One image with spp samples on the backend in use, and the exact T to compare it with. */
  private async frame(
    backend: Backend<DeltaTrackingGpu>,
    inputs: TrackingInputs,
    spp: number,
  ): Promise<Measured> {
    if (backend.kind === 'gpu') {
      const image = await backend.renderer.render(inputs, spp);
      return {
        image,
        exact: exactImage(IMAGE_WIDTH, IMAGE_HEIGHT),
        milliseconds: image.milliseconds,
        timing: image.timing,
      };
    }
    const { image, milliseconds } = await renderCpu(inputs, spp);
    return {
      image,
      exact: exactImage(CPU_WIDTH, CPU_HEIGHT),
      milliseconds,
      timing: 'cpu',
    };
  }

  get cpuNotice(): string {
    const compare = inputsFrom(this.context.values).view === 'compare';
    return `Showing the float64 CPU twin: the same rays and estimators, at ${CPU_WIDTH}×${CPU_HEIGHT} pixels${compare ? ', with CPU wall time in place of GPU time' : ''}.`;
  }

  createRenderer(gpu: GpuContext): DeltaTrackingGpu {
    return new DeltaTrackingGpu(gpu);
  }

  renderGpu(
    renderer: DeltaTrackingGpu,
    gpu: GpuContext,
    request: FrameRequest,
  ): Promise<TrackingFrame | null> {
    return this.renderOn({ kind: 'gpu', gpu, renderer }, request);
  }

  renderCpu(request: FrameRequest): Promise<TrackingFrame | null> {
    return this.renderOn({ kind: 'cpu', reason: '' }, request);
  }

  /**
   * The single view's frames are staged (stages.ts): the base follows their refinement.
   * A getter, because the comparison draws by itself and returns no frame, and the base
   * settles a frameless render only for a view without refinement (definedElement.ts).
   */
  get refinement(): ((frame: TrackingFrame) => Refinement | undefined) | undefined {
    if (inputsFrom(this.context.values).view === 'compare') return undefined;
    return (frame) => frame.refinement;
  }

  /** Per backend, the ladders of samples per pixel, one per spp (ladderFamily.ts). */
  private readonly ladders = {
    gpu: new LadderFamily<number>(GPU_FIRST_PICTURE_MS),
    cpu: new LadderFamily<number>(CPU_FIRST_PICTURE_MS),
  };

  /**
   * The single view's frame at this stage's samples per pixel (the first of them after
   * an input: the same streams, so a stage refines the last); the comparison is a long
   * job that reports itself (null).
   */
  private async renderOn(
    backend: Backend<DeltaTrackingGpu>,
    request: FrameRequest,
  ): Promise<TrackingFrame | null> {
    const inputs = inputsFrom(this.context.values);
    this.showView(inputs.view);
    if (inputs.view === 'compare') {
      await this.renderCompare(inputs, backend);
      return null;
    }
    const family = this.ladders[backend.kind];
    const ladder = family.get(String(inputs.spp), () => sampleRungs(inputs.spp));
    const choice = ladder.pick(request);
    const started = performance.now();
    const { image, exact, milliseconds, timing } = await this.frame(
      backend,
      inputs,
      choice.rung.value,
    );
    // The ladder learns the stage's whole time (read-back and statistics too).
    const variance = sampleVariance(image);
    const stats = imageStatistics(image, exact, variance);
    family.record(ladder, choice, performance.now() - started);
    return {
      inputs,
      image,
      variance,
      stats,
      estimatorName: nameOf(inputs.estimator),
      milliseconds,
      timing,
      refinement: ladder.refinement(choice),
    };
  }

  onCpuFallback(): void {
    this.sweep?.cancel('stopped: the GPU was lost');
    this.sweepAll?.cancel('stopped: the GPU was lost');
  }

  show({ image, variance, stats, estimatorName }: TrackingFrame): void {
    const scale = niceScale(stats.largestVariance);
    if (this.imageCanvas && this.varianceCanvas)
      paintImages(this.imageCanvas, this.varianceCanvas, image, variance, scale);
    if (this.scaleTop)
      this.scaleTop.textContent = image.spp < 2 ? 'needs spp ≥ 2' : formatNumber(scale, 2);
    if (image.capped > 0) {
      this.context.showNotice(
        'capped',
        'warning',
        `${image.capped} estimates reached their cap and were cut short; the image is biased there.`,
      );
    } else {
      this.context.clearNotice('capped');
    }
    this.imageCanvas?.setAttribute(
      'aria-label',
      `Estimated transmittance, ${estimatorName}, spp = ${image.spp}, RMSE ${formatNumber(stats.rmse, 3)}`,
    );
  }

  /** The statistics a grid image shows, from one frame. */
  private cellOf(frame: Measured): CompareCell {
    const variance = sampleVariance(frame.image);
    const stats = imageStatistics(frame.image, frame.exact, variance);
    let sum = 0;
    for (const v of variance) sum += v;
    return {
      image: frame.image,
      variance,
      stats,
      milliseconds: frame.milliseconds,
      meanVariance: sum / variance.length,
      // Significant at 5 SE (the book's threshold for "biased", physics.md §4.5).
      biased: frame.image.spp >= 2 && Math.abs(stats.bias) > 5 * stats.biasError,
    };
  }

  /**
   * The cost per sample of every estimator with this majorant on this backend:
   * the median time of CALIBRATION_RUNS renders at CALIBRATION_SPP, over the spp.
   * Measured once and cached; null when the settings changed meanwhile.
   */
  private async calibrate(
    backend: Backend<DeltaTrackingGpu>,
    inputs: TrackingInputs,
  ): Promise<Calibration | null> {
    const key = `${backend.kind}|${inputs.majorant}`;
    const cached = this.calibrations.get(key);
    if (cached) return cached;
    const changed = (): boolean => {
      const now = inputsFrom(this.context.values);
      return now.view !== 'compare' || now.majorant !== inputs.majorant;
    };
    const status = (text: string): void => {
      this.grid!.status.textContent = text;
    };
    // Warm-up passes over all five first, so that no estimator is timed while code
    // it shares with the others is still being compiled (the CPU fallback) or the
    // GPU is still raising its clocks; the last pass also sizes the timed renders.
    const warmup = {} as Record<EstimatorKey, number>;
    const passes = CALIBRATION_WARMUP[backend.kind];
    for (let pass = 1; pass <= passes; pass++)
      for (const estimator of ESTIMATOR_ORDER) {
        if (changed()) return null;
        status(
          `Warming up (pass ${pass} of ${passes}): ${nameOf(estimator)} at spp ${CALIBRATION_SPP}…`,
        );
        const frame = await this.frame(backend, withEstimator(inputs, estimator), CALIBRATION_SPP);
        warmup[estimator] = frame.milliseconds;
      }
    const costs = {} as Record<EstimatorKey, number>;
    const spp = {} as Record<EstimatorKey, number>;
    let how = '';
    for (const [index, estimator] of ESTIMATOR_ORDER.entries()) {
      // Timed renders of CALIBRATION_TARGET_MS or more, so the clock's resolution
      // and the dispatch's fixed cost do not set the cost per sample.
      const calibrate = calibrationSpp(warmup[estimator]);
      const times: number[] = [];
      for (let run = 1; run <= CALIBRATION_RUNS; run++) {
        if (changed()) return null;
        status(
          `Measuring the cost per sample of ${nameOf(estimator)} (${index + 1} of ${ESTIMATOR_ORDER.length}): render ${run} of ${CALIBRATION_RUNS} at spp ${calibrate}…`,
        );
        const frame = await this.frame(backend, withEstimator(inputs, estimator), calibrate);
        times.push(frame.milliseconds);
        how = timingLabel(frame.timing);
      }
      costs[estimator] = costPerSample(times, calibrate);
      spp[estimator] = calibrate;
    }
    const calibration = { costs, spp, how };
    this.calibrations.set(key, calibration);
    return calibration;
  }

  /**
   * The comparison: the five estimators at the chosen spp, then at the spp that
   * spends the reference estimator's time at that spp (planEqualTime), each with
   * its measured time; the images are kept, so "Comparison shows" only repaints.
   */
  private async renderCompare(
    inputs: TrackingInputs,
    backend: Backend<DeltaTrackingGpu>,
  ): Promise<void> {
    const grid = this.grid!;
    const key = compareKey(inputs, backend.kind);
    const stale = (): boolean => {
      const now = inputsFrom(this.context.values);
      return now.view !== 'compare' || compareKey(now, backend.kind) !== key;
    };
    const reference: EstimatorKey = isEstimatorKey(inputs.estimator) ? inputs.estimator : 'delta';
    if (key !== this.gridKey) {
      grid.element.setAttribute('aria-busy', 'true');
      const calibration = await this.calibrate(backend, inputs);
      if (!calibration || stale()) return;
      const plan = planEqualTime(calibration.costs, reference, inputs.spp);
      grid.setRowTitle('samples', `Equal samples: every estimator at spp = ${inputs.spp}`);
      grid.setRowTitle(
        'time',
        `Equal time: each gets ${formatMilliseconds(plan.budgetMs)}, the time of ${nameOf(reference)} at spp = ${inputs.spp}`,
      );
      const total = 2 * ESTIMATOR_ORDER.length;
      let done = 0;
      const render = async (row: CompareRow, estimator: EstimatorKey, spp: number) => {
        if (stale()) return false;
        done += 1;
        grid.status.textContent = `Rendering ${done} of ${total}: ${row === 'samples' ? 'equal samples' : 'equal time'}, ${nameOf(estimator)} at spp ${spp}…`;
        const reuse =
          row === 'time' && spp === inputs.spp ? grid.cell('samples', estimator) : undefined;
        if (reuse) {
          grid.setCell(row, estimator, reuse);
        } else {
          const input = withEstimator(inputs, estimator);
          const first = await this.frame(backend, input, spp);
          const times = [first.milliseconds];
          while (times.length < TIMING_RUNS) {
            if (stale()) return false;
            times.push((await this.frame(backend, input, spp)).milliseconds);
          }
          grid.setCell(row, estimator, this.cellOf({ ...first, milliseconds: median(times) }));
        }
        grid.paint(inputs.grid);
        return true;
      };
      for (const estimator of ESTIMATOR_ORDER)
        if (!(await render('samples', estimator, inputs.spp))) return;
      for (const estimator of ESTIMATOR_ORDER)
        if (!(await render('time', estimator, plan.spp[estimator]))) return;
      this.gridKey = key;
      grid.element.removeAttribute('aria-busy');
      this.showCompareReadouts(inputs, backend, calibration, plan.budgetMs, reference);
    }
    grid.paint(inputs.grid);
  }

  private showCompareReadouts(
    inputs: TrackingInputs,
    backend: Backend<DeltaTrackingGpu>,
    calibration: Calibration,
    budgetMs: number,
    reference: EstimatorKey,
  ): void {
    const grid = this.grid!;
    const readouts = this.compareReadouts!;
    const best = (row: CompareRow): string => {
      let winner: EstimatorKey = reference;
      for (const estimator of ESTIMATOR_ORDER)
        if (grid.cell(row, estimator)!.stats.rmse < grid.cell(row, winner)!.stats.rmse)
          winner = estimator;
      const cell = grid.cell(row, winner)!;
      return `${nameOf(winner)} (${formatNumber(cell.stats.rmse, 3)})`;
    };
    readouts.set(
      'budget',
      `${formatMilliseconds(budgetMs)} = ${nameOf(reference)} × spp ${inputs.spp}`,
    );
    readouts.set('best-samples', best('samples'));
    readouts.set('best-time', best('time'));
    readouts.set('timing', calibration.how);
    for (const estimator of ESTIMATOR_ORDER) {
      this.table?.set('cost', estimator, formatMilliseconds(calibration.costs[estimator]));
      this.table?.set(
        'lookups',
        estimator,
        formatNumber(grid.cell('samples', estimator)!.stats.lookupsPerEstimate, 3),
      );
    }
    const times = ESTIMATOR_ORDER.map((e) => grid.cell('time', e)!);
    const fastest = Math.min(...times.map((c) => c.milliseconds));
    const slowest = Math.max(...times.map((c) => c.milliseconds));
    const atLimit = ESTIMATOR_ORDER.filter((e) => {
      const spp = grid.cell('time', e)!.image.spp;
      return spp === SPP_MAX || (spp === 1 && calibration.costs[e] > budgetMs);
    });
    grid.status.textContent = `Equal time: budget ${formatMilliseconds(budgetMs)}, measured ${formatMilliseconds(fastest)} … ${formatMilliseconds(slowest)} (${calibration.how}).${atLimit.length ? ` At the limit of spp = 1 … ${SPP_MAX}, so off budget: ${atLimit.map(nameOf).join(', ')}.` : ''}`;
    const lowest = Math.min(...Object.values(calibration.spp));
    const highest = Math.max(...Object.values(calibration.spp));
    const sppRange = lowest === highest ? String(lowest) : `${lowest} … ${highest}`;
    const where =
      backend.kind === 'gpu'
        ? `WebGPU (${backend.gpu.adapterDescription}): ${IMAGE_WIDTH}×${IMAGE_HEIGHT} rays per image`
        : `CPU fallback (float64 twin): ${CPU_WIDTH}×${CPU_HEIGHT} rays per image`;
    readouts.cost.textContent = `${where}, ten images, ${MAJORANT_NAMES[inputs.majorant] ?? inputs.majorant}. Cost per sample: median of ${CALIBRATION_RUNS} renders per estimator after ${CALIBRATION_WARMUP[backend.kind]} untimed warm-up ${CALIBRATION_WARMUP[backend.kind] === 1 ? 'render' : 'renders'}, at spp ${sppRange} so that each lasts ${CALIBRATION_TARGET_MS} ms or more, measured once for this majorant; each image's time: median of ${TIMING_RUNS} renders. Reference: the exact T = e^(−τ) from the closed-form optical depth.`;
  }

  /**
   * Sweeps all five estimators over spp = 1 … 256 into one plot of RMSE against
   * time, each curve labelled with its slope fitted over spp ≥ FIT_MIN_SPP.
   */
  private runSweepAll(): Promise<void> {
    return this.sweepAll!.runSeries(async () => {
      const inputs = inputsFrom(this.context.values);
      const backend = await this.context.backend();
      const collected: SweepPoint[][] = ESTIMATOR_ORDER.map(() => []);
      // A slope is shown once two points at spp ≥ FIT_MIN_SPP exist.
      const slopeText = (
        points: readonly SweepPoint[],
        fit: (points: readonly SweepPoint[]) => number | null,
      ): string | null => {
        if (points.filter((p) => p.n >= FIT_MIN_SPP).length < 2) return null;
        const slope = fit(points);
        return slope === null ? null : formatNumber(slope, 2);
      };
      for (const estimator of ESTIMATOR_ORDER)
        for (const column of ['slope', 'spp-slope'] as const)
          this.table?.set(column, estimator, `needs spp ≥ ${FIT_MIN_SPP}`);
      return {
        series: ESTIMATOR_ORDER.map((estimator) => ({
          label: nameOf(estimator),
          ...SERIES_STYLE[estimator],
        })),
        measure: async (series, n) => {
          const estimator = ESTIMATOR_ORDER[series]!;
          const frame = await this.frame(backend, withEstimator(inputs, estimator), n);
          const stats = imageStatistics(frame.image, frame.exact, sampleVariance(frame.image));
          const point = { rmse: stats.rmse, milliseconds: frame.milliseconds };
          const points = collected[series]!;
          points.push({ n, ...point });
          const slope = slopeText(points, timeSlope);
          if (slope !== null) this.table?.set('slope', estimator, slope);
          const bySpp = slopeText(points, sppSlope);
          if (bySpp !== null) this.table?.set('spp-slope', estimator, bySpp);
          return point;
        },
        label: (series, points) => {
          const slope = slopeText(points, timeSlope);
          return `${nameOf(ESTIMATOR_ORDER[series]!)}${slope === null ? '' : `, p = ${slope}`}`;
        },
        finish: () =>
          `5 estimators, ${MAJORANT_NAMES[inputs.majorant] ?? inputs.majorant}, ${backend.kind === 'gpu' ? 'GPU' : 'CPU fallback'}; slopes of RMSE ∝ time^p fitted over spp ≥ ${FIT_MIN_SPP}`,
        failed: () => {
          for (const estimator of ESTIMATOR_ORDER)
            for (const column of ['slope', 'spp-slope'] as const)
              this.table?.set(column, estimator, 'failed');
        },
      };
    });
  }

  /** Renders spp = 1, 2, 4, …, 256 and fits the slope of log RMSE against log spp. */
  private runSweep(): Promise<void> {
    return this.sweep!.run(async () => {
      const inputs = inputsFrom(this.context.values);
      const backend = await this.context.backend();
      this.set('slope', 'sweeping…');
      const label = `${ESTIMATOR_NAMES[inputs.estimator] ?? inputs.estimator}, ${MAJORANT_NAMES[inputs.majorant] ?? inputs.majorant}`;
      return {
        label,
        measure: async (n) => {
          const frame = await this.frame(backend, inputs, n);
          const stats = imageStatistics(frame.image, frame.exact, sampleVariance(frame.image));
          return { rmse: stats.rmse, milliseconds: frame.milliseconds };
        },
        finish: (points) => {
          const slope = logLogSlope(
            points.map((p) => p.n),
            points.map((p) => p.rmse),
          );
          this.set(
            'slope',
            slope === null ? 'no fit' : `p = ${formatNumber(slope, 3)} (unbiased: −0.5)`,
          );
          return `${label}, ${backend.kind === 'gpu' ? 'GPU' : 'CPU fallback'}`;
        },
        failed: () => this.set('slope', 'failed', 'bad'),
      };
    });
  }
}

export function createView(
  context: ViewContext<DeltaTrackingGpu>,
): WidgetView<TrackingFrame, DeltaTrackingGpu> {
  return new DeltaTrackingView(context);
}
