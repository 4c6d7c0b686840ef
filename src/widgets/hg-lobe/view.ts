// The drawing of <sb-hg-lobe>: the polar picture (WebGPU, or the CPU twin at half
// resolution) with its HTML labels, the 3D lobe (LobeView, on its own schedule),
// the histogram against the closed form, and the error-versus-time sweep over
// N = 2¹⁰ … 2²⁰. Readouts, backends and fallback: widget.ts and the base element.
import type { GpuContext } from '../../gpu/device.ts';
import { hgEval } from '../../reference/phase.ts';
import { gpuFailureReason } from '../base/backend.ts';
import { formatNumber } from '../base/format.ts';
import { LinePlot, type PlotSeries, createPlotArea } from '../base/plot.ts';
import { SweepControls, logLogSlope, type SweepPoint } from '../base/sweep.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import { workerJobs } from '../../workers/compute.ts';
import {
  CPU_FIRST_PICTURE_MS,
  GPU_FIRST_PICTURE_MS,
  Ladder,
  type Refinement,
  type Rung,
  type RungChoice,
} from '../base/refinement.ts';
import { paintPolar, sampleHistogramCpuInChunks } from './cpuBackend.ts';
import type { jobs as hgJobTable } from './jobs.ts';
import { HgLobeGpu } from './gpuBackend.ts';
import { LobeView } from './lobeView.ts';
import {
  ALPHA,
  BIN_COUNT,
  CPU_TIMING_CAP,
  SWEEP_EXPONENTS,
  SWEEP_REPETITIONS,
  binEdge,
  chiSquareTest,
  comparePhase,
  expectedHistogramL1,
  hgBinProbabilities,
  histogramL1,
  inputsFrom,
  meanCosine,
  median,
  polarLayout,
  sphereIntegral,
  type HgHistogram,
  type HgLobeInputs,
  type PolarLayout,
  type RadiusScale,
} from './model.ts';
import { COMPARE_NAMES, superscript, type HgLobeFrame } from './widget.ts';

/** Frames whose sampling time the cost line averages (per N and backend). */
const TIMING_FRAMES = 8;

/** Refinement starts at most this many doublings below the reader's N (and at 2¹⁰)… */
const REFINE_DOUBLINGS = 6;
/** …and climbs this many doublings per stage: the stages before full quality add 1/7 of its cost, not all of it. */
const DOUBLINGS_PER_RUNG = 3;
/** The CPU fallback's polar picture: 1/POLAR_CPU_SCALE of the canvas's resolution (the twin's full quality)… */
const POLAR_CPU_SCALE = 2;
/**
 * …after a first picture at 1/POLAR_CPU_PREVIEW_SCALE (a quarter of the pixels) where the
 * measured cost says the full one does not fit half the CPU's first-picture budget: the
 * float64 shading of 480×240 pixels took 100–330 ms in the compute worker on a loaded
 * two-core machine (issue 23), the CPU's whole budget. The other half is the histogram's.
 */
const POLAR_CPU_PREVIEW_SCALE = 4;
const POLAR_CPU_SCALES: readonly number[] = [POLAR_CPU_PREVIEW_SCALE, POLAR_CPU_SCALE];

/**
 * The histogram's refinement (issue 23): the same streams (samples 0 … 2ᵏ − 1 of the
 * reader's seed) with fewer samples first, 2ᵏ for k = n, n − 3, n − 6
 * (not below 2¹⁰), coarse to fine; work is the sample count.
 */
function sampleRungs(exponent: number): Rung<number>[] {
  const rungs: Rung<number>[] = [];
  for (let k = exponent; k >= Math.max(10, exponent - REFINE_DOUBLINGS); k -= DOUBLINGS_PER_RUNG)
    rungs.unshift({ value: k, work: 2 ** k, label: `2${superscript(k)} = ${2 ** k} samples` });
  return rungs;
}

/** A slope with three decimals and a true minus sign. */
function signed(value: number): string {
  return value.toFixed(3).replace('-', '−');
}

/** Ring values and directions over the canvas, in per cent of its size so they follow its CSS size. */
function drawLabels(labels: HTMLElement, inputs: HgLobeInputs, layout: PolarLayout): void {
  const label = (text: string, x: number, y: number, className: string): HTMLElement => {
    const span = document.createElement('span');
    span.className = className;
    span.textContent = text;
    span.style.left = `${(100 * x) / layout.width}%`;
    span.style.top = `${(100 * y) / layout.height}%`;
    return span;
  };
  const spans: HTMLElement[] = [
    label('incident beam →', 12, layout.centreY - 12, 'sb-hg-label sb-hg-label--start'),
    label(
      'θ = 0° (forward)',
      layout.width - 12,
      layout.centreY - 12,
      'sb-hg-label sb-hg-label--end',
    ),
    label('θ = 90°', layout.centreX - 6, 28, 'sb-hg-label sb-hg-label--end'),
  ];
  // Ring values below the beam axis on the backward side, where the beam is the only other mark.
  // Every ring when they are at least 56 px apart, otherwise every second one.
  const spacing = layout.rings[0]?.radius ?? 0;
  const every = spacing >= 56 ? 1 : 2;
  layout.rings.forEach((ring, index) => {
    const x = layout.centreX - ring.radius;
    if (x < 24 || (index + 1) % every !== 0) return;
    const text =
      inputs.scale === 'log'
        ? `10${superscript(Math.round(Math.log10(ring.value)))}`
        : formatNumber(ring.value, 3);
    spans.push(label(text, x, layout.centreY + 6, 'sb-hg-label sb-hg-label--ring'));
  });
  const other = COMPARE_NAMES[inputs.compare];
  spans.push(
    label(
      `filled: Henyey–Greenstein${other ? ` · outline: ${other}` : ''}`,
      12,
      layout.height - 14,
      'sb-hg-label sb-hg-label--note',
    ),
  );
  spans.push(
    label(
      inputs.scale === 'log' ? 'radius ∝ log₁₀ p, rings in sr⁻¹' : 'radius ∝ p, rings in sr⁻¹',
      layout.width - 12,
      layout.height - 14,
      'sb-hg-label sb-hg-label--end sb-hg-label--note',
    ),
  );
  labels.replaceChildren(...spans);
}

/** The inputs of a refinement stage: the first 2ᵏ samples of the reader's streams. */
function stageInputs(inputs: HgLobeInputs, exponent: number): HgLobeInputs {
  return { ...inputs, samplesExponent: exponent, sampleCount: 2 ** exponent };
}

/**
 * The inputs of the polar picture: it depends on g, the comparison and the scale only, so
 * N and the seed are left out of its job's arguments (and cache key) in the worker.
 */
function polarInputs(inputs: HgLobeInputs): HgLobeInputs {
  return { ...inputs, samplesExponent: 0, sampleCount: 0, seed: 0 };
}

/** The label of a CPU frame: its samples, and the polar picture's resolution while it is coarse. */
function cpuStage(samples: RungChoice<number>, polarScale: number): Refinement {
  const polarFinal = polarScale === POLAR_CPU_SCALE;
  const final = samples.final && polarFinal;
  const polarNote = polarFinal
    ? ''
    : `, polar picture at 1/${polarScale} of the canvas's resolution`;
  return {
    label: `${final ? '' : 'Preview: '}${samples.rung.label}${polarNote}`,
    pending: final ? null : 'frame',
  };
}

export function createView(context: ViewContext<HgLobeGpu>): WidgetView<HgLobeFrame, HgLobeGpu> {
  const polar = context.canvas({ width: 960, height: 480, className: 'sb-canvas sb-hg-polar' });
  const labels = document.createElement('div');
  let lobe: LobeView | null = null;
  let sweep: SweepControls | null = null;
  let sweepRuns = 0;
  let plotArea: HTMLElement | null = null;
  let plot: LinePlot | null = null;
  let plotScale: RadiusScale | null = null;
  /** The float64 replays and the CPU polar picture, in the compute worker, cached by arguments. */
  const jobs = workerJobs<typeof hgJobTable>('hg-lobe');
  /** One ladder per backend and reader's N (its rungs end at that N); each learns its cost per sample. */
  const ladders = new Map<string, Ladder<number>>();
  const ladder = (kind: 'gpu' | 'cpu', exponent: number): Ladder<number> => {
    const key = `${kind}:${exponent}`;
    let found = ladders.get(key);
    if (!found) {
      // On the CPU the polar picture takes the other half of the budget (POLAR_CPU_PREVIEW_SCALE).
      const budget = kind === 'gpu' ? GPU_FIRST_PICTURE_MS : CPU_FIRST_PICTURE_MS / 2;
      found = new Ladder(sampleRungs(exponent), budget);
      ladders.set(key, found);
    }
    return found;
  };
  /** The 3D lobe's scene last shown (see show). */
  let lobeScene = '';
  /** The polar picture's inputs last drawn (it does not depend on N or the seed). */
  let polarKey = '';
  /** The CPU polar picture's resolution last drawn (1/scale of the canvas's). */
  let polarScale: number = POLAR_CPU_SCALE;
  /** The CPU polar picture's rungs; its cost per pixel is learnt from the worker's float64 time. */
  const polarLadder = new Ladder<number>(
    POLAR_CPU_SCALES.map((scale) => ({
      value: scale,
      work: (polar.element.width / scale) * (polar.element.height / scale),
      label: `1/${scale} resolution`,
    })),
    CPU_FIRST_PICTURE_MS / 2,
  );
  const polarKeyOf = (inputs: HgLobeInputs, kind: string): string =>
    `${kind}:${inputs.g}:${inputs.compare}:${inputs.scale}:${polar.element.width}`;

  /** Recent sampling times in ms, keyed by timing kind and N. */
  const recentTimes = new Map<string, number[]>();

  /** The mean of the last TIMING_FRAMES sampling times with this N and timing kind, this frame included. */
  const averageTime = (histogram: HgHistogram): { averageMs: number; averagedFrames: number } => {
    const key = `${histogram.timing}:${histogram.sampleCount}`;
    const times = [...(recentTimes.get(key) ?? []), histogram.milliseconds].slice(-TIMING_FRAMES);
    recentTimes.set(key, times);
    return {
      averageMs: times.reduce((a, b) => a + b, 0) / times.length,
      averagedFrames: times.length,
    };
  };

  /** The frame: the histograms, the averaged time and the checks of the readouts. */
  const frameOf = (
    inputs: HgLobeInputs,
    histogram: HgHistogram,
    replay: HgHistogram,
    stage: HgLobeFrame['stage'],
  ): HgLobeFrame => {
    const g = inputs.g;
    let moved = 0;
    for (let k = 0; k < BIN_COUNT; k++)
      moved += Math.abs((histogram.bins[k] ?? 0) - (replay.bins[k] ?? 0));
    return {
      inputs,
      histogram,
      replay,
      ...averageTime(histogram),
      integral: sphereIntegral((mu) => hgEval(g, mu)),
      forward: hgEval(g, 1),
      backward: hgEval(g, -1),
      mean: meanCosine(histogram, g),
      chi: chiSquareTest(histogram.bins, hgBinProbabilities(g), histogram.sampleCount),
      alpha: ALPHA,
      moved: moved / 2,
      stage,
    };
  };

  /**
   * Error against time for N = 2¹⁰ … 2²⁰ (the inputs of the moment the sweep starts):
   * per N, SWEEP_REPETITIONS sampling passes with seeds s, s + 1, …; x is the
   * median time of a pass (GPU timestamps where the device has them, wall time
   * otherwise; the CPU twin's time on the fallback), y the mean L1 distance of the
   * histograms to the analytic bin probabilities (physics.md §2.4). The second,
   * dashed series is the exact expected L1 at the same time, from the binomial law
   * of each bin count, so the measured curve is judged against an analytic value.
   */
  const runSweep = async (controls: SweepControls): Promise<void> => {
    const run = ++sweepRuns;
    let ended = false;
    await controls.runSeries(async () => {
      const inputs = inputsFrom(context.values);
      const backend = await context.backend();
      const layout = polarLayout(inputs, 960, 480);
      const probabilities = hgBinProbabilities(inputs.g);
      const timings = new Set<HgHistogram['timing']>();
      const timesByN = new Map<number, number>();
      context.setReadout('sweep', 'sweeping…');
      context.setReadout('sweep-check', 'sweeping…');
      const where = backend.kind === 'gpu' ? 'GPU' : 'CPU twin';
      const measure = async (n: number): Promise<Omit<SweepPoint, 'n'>> => {
        const times: number[] = [];
        let error = 0;
        for (let repetition = 0; repetition < SWEEP_REPETITIONS; repetition++) {
          const pass: HgLobeInputs = {
            ...inputs,
            sampleCount: n,
            samplesExponent: Math.round(Math.log2(n)),
            seed: inputs.seed + repetition,
          };
          const histogram =
            backend.kind === 'gpu'
              ? await backend.renderer.sample(pass, layout)
              : await sampleHistogramCpuInChunks(pass.g, n, pass.seed);
          timings.add(histogram.timing);
          times.push(histogram.milliseconds);
          error += histogramL1(histogram.bins, probabilities, n);
        }
        const milliseconds = median(times);
        timesByN.set(n, milliseconds);
        return { rmse: error / SWEEP_REPETITIONS, milliseconds };
      };
      return {
        series: [
          { label: `measured, g = ${formatNumber(inputs.g, 3)}, ${where}`, color: '#d9822b' },
          { label: 'exact expectation', color: '#8a63d2', dash: [6, 4] },
        ],
        measure: async (series, n) =>
          series === 0
            ? measure(n)
            : {
                rmse: expectedHistogramL1(probabilities, n),
                milliseconds: timesByN.get(n) ?? Number.NaN,
              },
        finish: (points) => {
          ended = true;
          const [measured = [], expected = []] = points;
          const slope = logLogSlope(
            measured.map((p) => p.n),
            measured.map((p) => p.rmse),
          );
          const expectedSlope = logLogSlope(
            expected.map((p) => p.n),
            expected.map((p) => p.rmse),
          );
          context.setReadout(
            'sweep',
            slope === null
              ? 'no fit'
              : `p = ${signed(slope)} (exact expectation ${signed(expectedSlope ?? -0.5)})`,
            slope !== null && Math.abs(slope - (expectedSlope ?? -0.5)) < 0.1 ? 'ok' : 'bad',
          );
          const last = measured.at(-1);
          const lastExpected = expected.at(-1);
          if (last && lastExpected) {
            const ratio = last.rmse / lastExpected.rmse;
            context.setReadout(
              'sweep-check',
              `${formatNumber(last.rmse, 3)} vs ${formatNumber(lastExpected.rmse, 3)} (ratio ${formatNumber(ratio, 3)})`,
              // The mean of 3 L1 errors, each a sum over 64 bins, scatters by a few per cent.
              Math.abs(ratio - 1) < 0.2 ? 'ok' : 'bad',
            );
          }
          const how = [...timings]
            .map((t) =>
              t === 'gpu-timestamp'
                ? 'GPU timestamps'
                : t === 'gpu-wall'
                  ? 'wall time (no timestamp queries)'
                  : 'CPU wall time',
            )
            .join(', ');
          return `g = ${formatNumber(inputs.g, 3)}, ${where}, time from ${how}`;
        },
        failed: () => {
          ended = true;
          context.setReadout('sweep', 'failed', 'bad');
          context.setReadout('sweep-check', 'failed', 'bad');
        },
      };
    });
    // Cancelled (or the GPU was lost): say so, unless a newer sweep has taken over.
    if (!ended && run === sweepRuns) {
      context.setReadout('sweep', 'cancelled');
      context.setReadout('sweep-check', 'cancelled');
    }
  };

  const updatePlot = (inputs: HgLobeInputs, histogram: HgHistogram, onGpu: boolean): void => {
    if (!plotArea) return;
    if (!plot || plotScale !== inputs.scale) {
      plot?.destroy();
      plotArea.replaceChildren();
      plot = new LinePlot(plotArea, {
        xLabel: 'μ = cos θ',
        yLabel: 'density of μ, 2π·p(μ)',
        height: 260,
        yLog: inputs.scale === 'log',
      });
      plotScale = inputs.scale;
    }
    // A staircase: each bin's density at both of its ends (nudged inward so x stays increasing).
    const width = 2 / BIN_COUNT;
    const x: number[] = [];
    const sampled: number[] = [];
    for (let k = 0; k < BIN_COUNT; k++) {
      const density = (histogram.bins[k] ?? 0) / (histogram.sampleCount * width);
      x.push(binEdge(k) + 1e-9, binEdge(k + 1) - 1e-9);
      sampled.push(density, density);
    }
    const series: PlotSeries[] = [
      {
        label: onGpu ? 'sampled on the GPU' : 'sampled by the CPU twin',
        color: '#d9822b',
        values: sampled,
      },
      {
        label: 'analytic 2π·p_HG(μ)',
        color: '#8a63d2',
        values: x.map((mu) => 2 * Math.PI * hgEval(inputs.g, mu)),
      },
    ];
    const other = comparePhase(inputs.compare);
    if (other) {
      series.push({
        label: `${COMPARE_NAMES[inputs.compare]} 2π·p(μ)`,
        color: '#5b8def',
        dash: [6, 4],
        values: x.map((mu) => 2 * Math.PI * other(mu)),
      });
    }
    plot.update(x, series);
  };

  return {
    cpuNotice:
      'Showing the float64 CPU twin: the same samples (the same PCG streams), the polar picture at half resolution and the 3D lobe as a wireframe.',
    build(stage) {
      const figure = document.createElement('div');
      figure.className = 'sb-hg-figure sb-hg-polar-figure';
      labels.className = 'sb-hg-labels';
      labels.setAttribute('aria-hidden', 'true');
      figure.append(polar.element, labels);
      stage.appendChild(figure);
      lobe = new LobeView((error) => context.useCpu(gpuFailureReason(error)));
      stage.appendChild(lobe.figure);
      plotArea = createPlotArea(
        'Histogram of the sampled scattering cosines against the analytic density 2π·p(μ)',
      );
      stage.appendChild(plotArea);
      const controls = new SweepControls(
        stage,
        context.host,
        {
          name: 'N',
          buttonText: 'Run sweep N = 2¹⁰ … 2²⁰',
          hint:
            'Run the sweep to plot the histogram’s error against the time of one sampling pass, for N = 2¹⁰ … 2²⁰ ' +
            `(time: median of ${SWEEP_REPETITIONS} passes; error: L1 distance Σ|Oₖ/N − Pₖ| to the analytic bin probabilities, ` +
            'mean of the same passes). A Monte Carlo estimate falls as N^(−½); the dashed curve is its exact expectation.',
          color: '#d9822b',
          points: SWEEP_EXPONENTS.map((n) => 2 ** n),
          errorName: 'L1 error of the histogram',
        },
        () => void runSweep(controls),
      );
      sweep = controls;
    },
    createRenderer: (gpu: GpuContext) => new HgLobeGpu(gpu, polar.element),
    async renderGpu(renderer, gpu, request) {
      const started = performance.now();
      const inputs = inputsFrom(context.values);
      const steps = ladder('gpu', inputs.samplesExponent);
      const choice = steps.pick(request);
      const layout = polarLayout(inputs, polar.element.width, polar.element.height);
      const histogram = await renderer.sample(stageInputs(inputs, choice.rung.value), layout);
      // The polar picture does not depend on N or the seed: drawn once per picture.
      const key = polarKeyOf(inputs, 'gpu');
      if (request.stage === 0 || key !== polarKey) {
        await renderer.draw(inputs, layout);
        polarKey = key;
      }
      lobe?.useGpu(gpu);
      // The twin replays the same streams in the worker, capped so that dragging a slider stays smooth.
      const replay = await jobs.run(
        'histogram',
        [inputs.g, Math.min(histogram.sampleCount, CPU_TIMING_CAP), inputs.seed],
        { signal: request.signal },
      );
      const frame = frameOf(inputs, histogram, replay, steps.refinement(choice));
      steps.record(choice.index, performance.now() - started);
      return frame;
    },
    async renderCpu(request) {
      const inputs = inputsFrom(context.values);
      const steps = ladder('cpu', inputs.samplesExponent);
      const choice = steps.pick(request);
      const key = polarKeyOf(inputs, 'cpu');
      const fresh = request.stage === 0 || key !== polarKey;
      if (fresh || polarScale !== POLAR_CPU_SCALE) {
        // A new picture starts on the rung that fits (at once on the full one if the worker
        // still has it); a later stage draws the full one.
        const { width, height } = polar.element;
        const args = (scale: number) =>
          [polarInputs(inputs), width, height, scale] as [HgLobeInputs, number, number, number];
        const ready = jobs.cached('polar', args(POLAR_CPU_SCALE)) !== undefined;
        const scale = fresh && !ready ? polarLadder.pick({ stage: 0 }).rung.value : POLAR_CPU_SCALE;
        const cached = jobs.cached('polar', args(scale)) !== undefined;
        const image = await jobs.run('polar', args(scale), { signal: request.signal });
        paintPolar(polar.element, image);
        if (!cached) polarLadder.record(POLAR_CPU_SCALES.indexOf(scale), image.milliseconds);
        polarKey = key;
        polarScale = scale;
      }
      lobe?.useCpu();
      const stage = stageInputs(inputs, choice.rung.value);
      const histogramArgs: [number, number, number] = [stage.g, stage.sampleCount, stage.seed];
      // A histogram the worker still has says nothing about the cost of sampling.
      const cached = jobs.cached('histogram', histogramArgs) !== undefined;
      const started = performance.now();
      const histogram = await jobs.run('histogram', histogramArgs, { signal: request.signal });
      if (!cached) steps.record(choice.index, performance.now() - started);
      return frameOf(inputs, histogram, histogram, cpuStage(choice, polarScale));
    },
    refinement: (frame) => frame.stage,
    onCpuFallback: () => {
      polarKey = '';
      lobeScene = '';
      lobe?.useCpu();
      sweep?.cancel('stopped: the GPU path was lost');
    },
    destroyRenderer: (renderer) => renderer.destroy(),
    /** The 3D view draws on its own schedule, while on screen: printing draws it too. */
    drawForPrint: async () => {
      await lobe?.drawNow();
    },
    destroy: () => {
      lobe?.destroy();
      sweep?.cancel('stopped');
      plot?.destroy();
    },
    show({ inputs, histogram }, backend) {
      const layout = polarLayout(inputs, polar.element.width, polar.element.height);
      // The 3D lobe depends on g, the comparison and the scale only: a refinement
      // stage (more samples of the same lobe) does not draw it again.
      const scene = `${inputs.g}:${inputs.compare}:${inputs.scale}:${layout.logFloor}:${backend.kind}`;
      if (scene !== lobeScene) lobe?.show({ inputs, logFloor: layout.logFloor });
      lobeScene = scene;
      drawLabels(labels, inputs, layout);
      const g = inputs.g;
      const other = COMPARE_NAMES[inputs.compare];
      polar.element.setAttribute(
        'aria-label',
        `Polar plot of the Henyey–Greenstein phase function with g = ${formatNumber(g, 3)}: ` +
          `the beam enters from the left; the lobe reaches ${formatNumber(hgEval(g, 1), 3)} per steradian forward ` +
          `and ${formatNumber(hgEval(g, -1), 3)} backward${other ? `, outlined against the ${other} phase function` : ''}.`,
      );
      updatePlot(inputs, histogram, backend.kind === 'gpu');
    },
  };
}
