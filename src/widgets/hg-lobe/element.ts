// <sb-hg-lobe>: the Henyey–Greenstein phase function (chapter 3). Draws the lobe
// as a polar plot and as a 3D surface on the GPU, samples 2^n scattering cosines
// with the library's HG sampler in a compute pass, and shows the histogram against
// the closed form with a chi-square test, the sample mean cosine against g, the
// normalisation of the float64 twin, and the cost of sampling on the GPU next to
// the CPU twin (averaged over frames); a cancellable sweep over N = 2¹⁰ … 2²⁰ plots
// the histogram's L1 error against the sampling time, next to its exact expectation.
import {
  BackendChooser,
  type Backend as ChosenBackend,
  gpuFailureReason,
} from '../base/backend.ts';
import { hgEval } from '../../reference/phase.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel } from '../base/timing.ts';
import { ReadoutList } from '../base/readoutList.ts';
import { LinePlot, type PlotSeries } from '../base/plot.ts';
import { SweepControls, logLogSlope, type SweepPoint } from '../base/sweep.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import { HG_LOBE } from './schema.ts';
import { drawLobeCpu, sampleHistogramCpu, sampleHistogramCpuInChunks } from './cpuBackend.ts';
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

type Backend = ChosenBackend<HgLobeGpu>;

const READOUT_ROWS = [
  ['normalisation', '∫ p dω (float64 quadrature)'],
  ['forward', 'p(θ = 0°), forward'],
  ['backward', 'p(θ = 180°), backward'],
  ['mean-cosine', 'Sample mean cosine ± SE'],
  ['chi-square', 'χ² of 64 bins vs closed form'],
  ['replay', 'Histogram vs float64 replay'],
  ['sweep', 'Sweep: L1 error ∝ N^p'],
  ['sweep-check', 'Sweep: L1 at N = 2²⁰ vs expected'],
] as const;

/** Frames whose sampling time the cost line averages (per N and backend). */
const TIMING_FRAMES = 8;

const COMPARE_NAMES = { none: '', isotropic: 'isotropic', rayleigh: 'Rayleigh' } as const;

export class HgLobeElement extends WidgetElement {
  protected readonly entry = HG_LOBE;
  protected override presets: readonly Preset[] = [
    { label: 'g = −0.3 (back)', values: { g: -0.3 } },
    { label: 'g = 0 (isotropic)', values: { g: 0 } },
    { label: 'g = 0.6 (forward)', values: { g: 0.6 } },
    { label: 'g = 0.9 (clouds)', values: { g: 0.9 } },
    { label: 'Rayleigh vs isotropic', values: { g: 0, compare: 'rayleigh' } },
  ];

  private canvas: HTMLCanvasElement | null = null;
  private labels: HTMLElement | null = null;
  private view: LobeView | null = null;
  private sweep: SweepControls | null = null;
  private sweepRuns = 0;
  /** Recent sampling times in ms, keyed by backend, timing kind and N. */
  private readonly recentTimes = new Map<string, number[]>();
  private plotArea: HTMLElement | null = null;
  private plot: LinePlot | null = null;
  private plotScale: RadiusScale | null = null;
  private readouts: ReadoutList | null = null;
  private readonly backends = new BackendChooser<HgLobeGpu>(
    (gpu) => {
      if (!this.canvas) throw new Error('no canvas');
      return new HgLobeGpu(gpu, this.canvas);
    },
    (reason) => this.fallBackToCpu(reason),
  );

  protected buildStage(stage: HTMLElement): void {
    const figure = document.createElement('div');
    figure.className = 'sb-hg-figure sb-hg-polar-figure';
    this.canvas = this.createCanvas();
    this.labels = document.createElement('div');
    this.labels.className = 'sb-hg-labels';
    this.labels.setAttribute('aria-hidden', 'true');
    figure.append(this.canvas, this.labels);
    stage.appendChild(figure);
    this.view = new LobeView((error) => this.fallBackToCpu(gpuFailureReason(error)));
    stage.appendChild(this.view.figure);
    this.plotArea = document.createElement('div');
    this.plotArea.className = 'sb-plot';
    this.plotArea.setAttribute('role', 'img');
    this.plotArea.setAttribute(
      'aria-label',
      'Histogram of the sampled scattering cosines against the analytic density 2π·p(μ)',
    );
    stage.appendChild(this.plotArea);
    this.sweep = new SweepControls(
      stage,
      this,
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
      () => void this.runSweep(),
    );
  }

  private createCanvas(): HTMLCanvasElement {
    const canvas = document.createElement('canvas');
    canvas.className = 'sb-canvas sb-hg-polar';
    canvas.setAttribute('role', 'img');
    canvas.width = 960;
    canvas.height = 480;
    return canvas;
  }

  /** The 3D view draws on its own schedule, while on screen: printing draws it too. */
  protected override async drawForPrint(): Promise<void> {
    await this.view?.drawNow();
  }

  protected buildReadout(readout: HTMLElement): void {
    this.readouts = new ReadoutList(readout, READOUT_ROWS);
    this.readouts.set('sweep', 'run the sweep');
    this.readouts.set('sweep-check', 'run the sweep');
  }

  /** After a device loss: a fresh canvas (a WebGPU canvas cannot become 2D) and the CPU path. */
  private fallBackToCpu(reason: string): void {
    if (this.canvas) {
      const fresh = this.createCanvas();
      this.canvas.replaceWith(fresh);
      this.canvas = fresh;
    }
    this.backends.useCpu(reason);
    this.view?.useCpu();
    this.sweep?.cancel('stopped: the GPU path was lost');
    this.scheduleRender();
  }

  protected async render(): Promise<void> {
    const inputs = inputsFrom(this.values);
    const backend = await this.backends.choose();
    if (!this.canvas) return;
    const layout = polarLayout(inputs, this.canvas.width, this.canvas.height);
    let histogram: HgHistogram;
    let replay: HgHistogram;
    if (backend.kind === 'gpu') {
      try {
        histogram = await backend.renderer.sample(inputs, layout);
        await backend.renderer.draw(inputs, layout);
      } catch (error) {
        this.fallBackToCpu(gpuFailureReason(error));
        return;
      }
      this.clearNotice('backend');
      this.view?.useGpu(backend.gpu);
      // The twin replays the same streams, capped so that dragging a slider stays smooth.
      replay = sampleHistogramCpu(
        inputs.g,
        Math.min(inputs.sampleCount, CPU_TIMING_CAP),
        inputs.seed,
      );
    } else {
      drawLobeCpu(this.canvas, inputs);
      this.view?.useCpu();
      histogram = sampleHistogramCpu(inputs.g, inputs.sampleCount, inputs.seed);
      replay = histogram;
      this.showCpuFallbackNotice(
        backend.reason,
        `Showing the float64 CPU twin: the same samples (the same PCG streams), the polar picture at half resolution and the 3D lobe as a wireframe.`,
      );
    }
    this.view?.show({ inputs, logFloor: layout.logFloor });
    this.drawLabels(inputs, layout);
    this.showResult(inputs, histogram, replay, backend);
    this.updatePlot(inputs, histogram, backend);
  }

  /** Ring values and directions over the canvas, in per cent of its size so they follow its CSS size. */
  private drawLabels(inputs: HgLobeInputs, layout: PolarLayout): void {
    if (!this.labels) return;
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
    this.labels.replaceChildren(...spans);
  }

  private showResult(
    inputs: HgLobeInputs,
    histogram: HgHistogram,
    replay: HgHistogram,
    backend: Backend,
  ): void {
    const set = (key: string, text: string, state?: 'ok' | 'bad'): void =>
      this.readouts?.set(key, text, state);
    const g = inputs.g;
    const integral = sphereIntegral((mu) => hgEval(g, mu));
    set('normalisation', integral.toFixed(10), Math.abs(integral - 1) < 1e-9 ? 'ok' : 'bad');
    set('forward', `${formatNumber(hgEval(g, 1))} sr⁻¹`);
    set('backward', `${formatNumber(hgEval(g, -1))} sr⁻¹`);

    const mean = meanCosine(histogram, g);
    const within = Math.abs(mean.zScore) < 5;
    set(
      'mean-cosine',
      `${formatNumber(mean.mean, 5)} ± ${formatNumber(mean.standardError, 2)} (g = ${formatNumber(g, 4)}, ${formatNumber(Math.abs(mean.zScore), 2)} SE)`,
      within ? 'ok' : 'bad',
    );
    const chi = chiSquareTest(histogram.bins, hgBinProbabilities(g), histogram.sampleCount);
    const pooled = chi.pooled > 0 ? `, ${chi.pooled} sparse bins pooled` : '';
    set(
      'chi-square',
      `${formatNumber(chi.statistic, 4)} (df ${chi.df}${pooled}): ${chi.passes ? 'passes' : 'fails'} at α = ${ALPHA} (critical ${formatNumber(chi.critical, 4)})`,
      chi.passes ? 'ok' : 'bad',
    );
    if (backend.kind === 'gpu') {
      if (replay.sampleCount === histogram.sampleCount) {
        let moved = 0;
        for (let k = 0; k < BIN_COUNT; k++)
          moved += Math.abs((histogram.bins[k] ?? 0) - (replay.bins[k] ?? 0));
        moved /= 2;
        set(
          'replay',
          moved === 0
            ? 'identical bins (GPU f32 vs CPU f64)'
            : `${moved} of ${histogram.sampleCount} samples in a neighbouring bin (f32 rounding at bin edges)`,
          moved <= 1e-3 * histogram.sampleCount ? 'ok' : 'bad',
        );
      } else {
        set('replay', `replayed on the CPU for the first 2¹⁶ samples only (timing)`);
      }
    } else {
      set('replay', 'this is the float64 replay (CPU fallback)');
    }

    const n = histogram.sampleCount;
    const nText = `2${superscript(inputs.samplesExponent)} = ${n} samples`;
    const how = timingLabel(histogram.timing);
    this.recordFrameCost(histogram.milliseconds, how);
    let twin: string;
    if (replay.sampleCount === n) {
      twin = `float64 twin on the CPU: ${formatMilliseconds(replay.milliseconds)} for the same ${n}`;
    } else {
      const factor = n / replay.sampleCount;
      twin =
        `float64 twin on the CPU: ≈ ${formatMilliseconds(replay.milliseconds * factor)} for ${n}, ` +
        `scaled ×${factor} from ${formatMilliseconds(replay.milliseconds)} measured on ${replay.sampleCount}`;
    }
    const { mean: averageMs, frames } = this.averageTime(histogram);
    const time =
      frames > 1
        ? `${formatMilliseconds(averageMs)} (${how}, mean of the last ${frames} frames at this N)`
        : `${formatMilliseconds(averageMs)} (${how}, one frame so far)`;
    if (this.readouts) {
      this.readouts.cost.textContent =
        backend.kind === 'gpu'
          ? `WebGPU (${backend.gpu.adapterDescription}): ${nText} in ${time}; ${twin}.`
          : `CPU fallback: ${nText} in ${time}, float64 twin.`;
    }
    if (this.canvas) {
      const other = COMPARE_NAMES[inputs.compare];
      this.canvas.setAttribute(
        'aria-label',
        `Polar plot of the Henyey–Greenstein phase function with g = ${formatNumber(g, 3)}: ` +
          `the beam enters from the left; the lobe reaches ${formatNumber(hgEval(g, 1), 3)} per steradian forward ` +
          `and ${formatNumber(hgEval(g, -1), 3)} backward${other ? `, outlined against the ${other} phase function` : ''}.`,
      );
    }
  }

  /** The mean of the last TIMING_FRAMES sampling times with this N and timing kind, this frame included. */
  private averageTime(histogram: HgHistogram): { mean: number; frames: number } {
    const key = `${histogram.timing}:${histogram.sampleCount}`;
    const times = [...(this.recentTimes.get(key) ?? []), histogram.milliseconds].slice(
      -TIMING_FRAMES,
    );
    this.recentTimes.set(key, times);
    return { mean: times.reduce((a, b) => a + b, 0) / times.length, frames: times.length };
  }

  /**
   * Error against time for N = 2¹⁰ … 2²⁰ (the inputs of the moment the sweep starts):
   * per N, SWEEP_REPETITIONS sampling passes with seeds s, s + 1, …; x is the
   * median time of a pass (GPU timestamps where the device has them, wall time
   * otherwise; the CPU twin's time on the fallback), y the mean L1 distance of the
   * histograms to the analytic bin probabilities (physics.md §2.4). The second,
   * dashed series is the exact expected L1 at the same time, from the binomial law
   * of each bin count, so the measured curve is judged against an analytic value.
   */
  private async runSweep(): Promise<void> {
    const run = ++this.sweepRuns;
    let ended = false;
    await this.sweep!.runSeries(async () => {
      const inputs = inputsFrom(this.values);
      const backend = await this.backends.choose();
      const layout = polarLayout(inputs, 960, 480);
      const probabilities = hgBinProbabilities(inputs.g);
      const timings = new Set<HgHistogram['timing']>();
      const timesByN = new Map<number, number>();
      this.readouts?.set('sweep', 'sweeping…');
      this.readouts?.set('sweep-check', 'sweeping…');
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
          this.readouts?.set(
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
            this.readouts?.set(
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
          this.readouts?.set('sweep', 'failed', 'bad');
          this.readouts?.set('sweep-check', 'failed', 'bad');
        },
      };
    });
    // Cancelled (or the GPU was lost): say so, unless a newer sweep has taken over.
    if (!ended && run === this.sweepRuns) {
      this.readouts?.set('sweep', 'cancelled');
      this.readouts?.set('sweep-check', 'cancelled');
    }
  }

  private updatePlot(inputs: HgLobeInputs, histogram: HgHistogram, backend: Backend): void {
    if (!this.plotArea) return;
    if (!this.plot || this.plotScale !== inputs.scale) {
      this.plot?.destroy();
      this.plotArea.replaceChildren();
      this.plot = new LinePlot(this.plotArea, {
        xLabel: 'μ = cos θ',
        yLabel: 'density of μ, 2π·p(μ)',
        height: 260,
        yLog: inputs.scale === 'log',
      });
      this.plotScale = inputs.scale;
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
        label: backend.kind === 'gpu' ? 'sampled on the GPU' : 'sampled by the CPU twin',
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
    this.plot.update(x, series);
  }
}

const SUPERSCRIPT_DIGITS = '⁰¹²³⁴⁵⁶⁷⁸⁹';

/** A slope with three decimals and a true minus sign. */
function signed(value: number): string {
  return value.toFixed(3).replace('-', '−');
}

function superscript(value: number): string {
  return [...String(value)]
    .map((c) => (c === '-' ? '⁻' : (SUPERSCRIPT_DIGITS[Number(c)] ?? c)))
    .join('');
}

export function defineHgLobe(): void {
  if (!customElements.get('sb-hg-lobe')) customElements.define('sb-hg-lobe', HgLobeElement);
}
