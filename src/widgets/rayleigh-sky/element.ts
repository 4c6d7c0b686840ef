// <sb-rayleigh-sky>: why the sky is blue and sunsets red (chapter 3). Draws a
// panorama toward the sun on the GPU, one single-scattering march per pixel,
// evaluates three probe directions and the direct sun in a compute pass, and shows
// them next to a converged float64 reference (cached once per sun elevation) with
// the relative error and the GPU time of the panorama (timestamp queries, median
// over frames). A cancellable sweep over N plots the probes' relative RMS error
// against that time and fits the order of convergence.
import {
  BackendChooser,
  type Backend as ChosenBackend,
  gpuFailureReason,
} from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel, type GpuTiming } from '../base/timing.ts';
import { ReadoutList } from '../base/readoutList.ts';
import { SweepControls } from '../base/sweep.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import { RAYLEIGH_SKY } from './schema.ts';
import { drawSkyCpu } from './cpuBackend.ts';
import { RayleighSkyGpu, type PanoramaTime } from './gpuBackend.ts';
import {
  CANVAS_HEIGHT,
  CANVAS_WIDTH,
  ELEVATION_MAX_DEG,
  ELEVATION_MIN_DEG,
  FIELD_OF_VIEW_DEG,
  FIT_FROM_STEPS,
  REFERENCE_STEPS,
  SUN_ENLARGEMENT,
  SWEEP_STEPS,
  computeProbes,
  fitSweep,
  inputsFrom,
  median,
  nextPassCount,
  probeError,
  probesFor,
  referenceProbesAsync,
  relativeError,
  srgbEncode,
  sunStepsFor,
  type Rgb,
  type SkyInputs,
  type SkyProbes,
  type SweepFit,
} from './model.ts';

type Backend = ChosenBackend<RayleighSkyGpu>;
type Timing = GpuTiming | 'cpu';

const READOUT_ROWS = [
  ['zenith', 'Zenith radiance L (R, G, B), sr⁻¹'],
  ['toward', '10° up, toward the sun'],
  ['away', '10° up, away from the sun'],
  ['error', `Relative error vs float64, N = M = ${REFERENCE_STEPS}`],
  ['sun', 'Direct sunlight T_sun (R, G, B)'],
  ['zenith-ratio', 'Zenith blue/red, L_B/L_R'],
  ['sun-ratio', 'Direct sun red/blue, T_R/T_B'],
  ['slope', `Sweep: error ∝ N^p (fit over N ≥ ${FIT_FROM_STEPS})`],
  ['time-slope', 'Sweep: error ∝ time^q, time ∝ N^a'],
] as const;

/** Probe keys in probesFor order, and the readout each one fills. */
const PROBE_KEYS = ['zenith', 'toward', 'away'] as const;
const CPU_SCALE = 4;
/** Frame times kept per N for the readout's median. */
const FRAME_HISTORY = 5;
/** The sweep times each N as the median of up to this many frames… */
const SWEEP_FRAMES = 3;
/** …but stops at fewer once a point has taken this long (SwiftShader: N = 128 ≈ 7 s a frame). */
const SWEEP_POINT_BUDGET_MS = 1500;
/** The CPU fallback times the float64 probes in batches of at least this long (timer resolution). */
const CPU_BATCH_MS = 10;

/** What one render shows: the probes, their cost, and the picture's cost. */
interface Shown extends SkyProbes {
  probeMilliseconds: number;
  probeTiming: Timing;
  capped: boolean;
  picture: {
    /** Median time per panorama over the last `frames` frames at this N (ms). */
    milliseconds: number;
    frames: number;
    /** Passes per timed submit (more than 1 when one panorama is under the timer's resolution). */
    passes: number;
    timing: Timing;
  };
}

function formatRgb(rgb: Rgb, digits = 4): string {
  return rgb.map((v) => formatNumber(v, digits)).join(', ');
}

function formatPercent(error: number | null): string {
  if (error === null) return '0 (exact: no light)';
  return `${formatNumber(100 * error, 3)}%`;
}

function pause(): Promise<void> {
  return new Promise((resolve) => setTimeout(resolve, 0));
}

/**
 * CPU wall time (ms) of the three float64 probes and the sun at these N and M:
 * one evaluation takes µs to ms, below the browser timer's resolution at small N,
 * so each of three batches repeats it for at least CPU_BATCH_MS; the median of
 * the batch means. Yields between batches so the page stays live.
 */
async function timeProbesCpu(
  inputs: SkyInputs,
): Promise<{ probes: SkyProbes; milliseconds: number }> {
  let probes = computeProbes(inputs);
  const perEvaluation: number[] = [];
  for (let batch = 0; batch < 3; batch++) {
    await pause();
    let repeats = 0;
    const start = performance.now();
    let elapsed = 0;
    do {
      probes = computeProbes(inputs);
      repeats += 1;
      elapsed = performance.now() - start;
    } while (elapsed < CPU_BATCH_MS);
    perEvaluation.push(elapsed / repeats);
  }
  return { probes, milliseconds: median(perEvaluation) };
}

export class RayleighSkyElement extends WidgetElement {
  protected readonly entry = RAYLEIGH_SKY;
  protected override presets: readonly Preset[] = [
    { label: 'noon', values: { 'sun-elevation': 60, scattering: 'on' } },
    { label: 'afternoon', values: { 'sun-elevation': 20, scattering: 'on' } },
    { label: 'sunset', values: { 'sun-elevation': 2, scattering: 'on' } },
    { label: 'no scattering', values: { 'sun-elevation': 30, scattering: 'off' } },
  ];

  private canvas: HTMLCanvasElement | null = null;
  private labels: HTMLElement | null = null;
  private readouts: ReadoutList | null = null;
  private swatch: HTMLElement | null = null;
  private sweep: SweepControls | null = null;
  /** Recent panorama times per backend, timing method and N, for the median readout. */
  private readonly frameTimes = new Map<string, number[]>();
  /** Passes per timed submit, per N (see nextPassCount). */
  private readonly passCounts = new Map<number, number>();
  /** Counts sweep runs, so a superseded run leaves the readouts to the newer one. */
  private sweepRuns = 0;
  private readonly backends = new BackendChooser<RayleighSkyGpu>(
    (gpu) => {
      if (!this.canvas) throw new Error('no canvas');
      return new RayleighSkyGpu(gpu, this.canvas);
    },
    (reason) => this.fallBackToCpu(reason),
  );

  protected buildStage(stage: HTMLElement): void {
    const figure = document.createElement('div');
    figure.className = 'sb-sky-figure';
    this.canvas = this.createCanvas();
    this.labels = document.createElement('div');
    this.labels.className = 'sb-sky-labels';
    this.labels.setAttribute('aria-hidden', 'true');
    figure.append(this.canvas, this.labels);
    stage.appendChild(figure);
    this.sweep = new SweepControls(
      stage,
      this,
      {
        name: 'N',
        buttonText: `Run sweep N = ${SWEEP_STEPS[0]} … ${SWEEP_STEPS[SWEEP_STEPS.length - 1]}`,
        hint: `Run the sweep to plot the probes' relative RMS error against the GPU time of one panorama for N = ${SWEEP_STEPS.join(', ')} (M = max(4, ⌈N/4⌉) with each), and fit the order of convergence over N ≥ ${FIT_FROM_STEPS}.`,
        color: '#2f7fd1',
        statusClass: 'sb-sky-sweep-status',
        points: SWEEP_STEPS,
        errorName: 'relative RMS error',
      },
      () => void this.runSweep(),
    );
  }

  private createCanvas(): HTMLCanvasElement {
    const canvas = document.createElement('canvas');
    canvas.className = 'sb-canvas';
    canvas.setAttribute('role', 'img');
    canvas.width = CANVAS_WIDTH;
    canvas.height = CANVAS_HEIGHT;
    return canvas;
  }

  protected buildReadout(readout: HTMLElement): void {
    this.readouts = new ReadoutList(readout, READOUT_ROWS);
    // The direct sun's colour, next to its numbers.
    const sunRow = readout.querySelector('[data-readout="sun"]')?.parentElement;
    this.swatch = document.createElement('span');
    this.swatch.className = 'sb-sky-swatch';
    this.swatch.setAttribute('aria-hidden', 'true');
    sunRow?.appendChild(this.swatch);
    this.set('slope', 'run the sweep');
    this.set('time-slope', 'run the sweep');
    const orders = document.createElement('p');
    orders.className = 'sb-sky-scope';
    orders.textContent = `Expected: the midpoint rule's error falls as N⁻² for a smooth integrand (p ≈ −2); each view sample costs a fixed part plus M = N/4 sun samples, so the time grows between N and N² (a between 1 and 2) and the error falls as time^(p/a), q between −2 and −1. Below N = ${FIT_FROM_STEPS} the sun ray keeps M = 4 and the curve flattens; with the sun below the horizon the Earth's shadow cuts the integrand and the order drops.`;
    const scope = document.createElement('p');
    scope.className = 'sb-sky-scope';
    scope.textContent =
      'Single Rayleigh scattering only: no ozone, no aerosols, no multiple scattering.';
    readout.append(orders, scope);
  }

  private set(key: string, text: string, state?: 'ok' | 'bad'): void {
    this.readouts?.set(key, text, state);
  }

  /** After a device loss: a fresh canvas (a WebGPU canvas cannot become 2D) and the CPU path. */
  private fallBackToCpu(reason: string): void {
    this.sweep?.cancel('stopped: the GPU was lost');
    if (this.canvas) {
      const fresh = this.createCanvas();
      this.canvas.replaceWith(fresh);
      this.canvas = fresh;
    }
    this.backends.useCpu(reason);
    this.scheduleRender();
  }

  /** Keeps the last FRAME_HISTORY times for this backend, timing and N; returns their median. */
  private recordFrame(
    backend: Backend,
    timing: Timing,
    steps: number,
    milliseconds: number,
  ): { milliseconds: number; frames: number } {
    const key = `${backend.kind}:${timing}:${steps}`;
    const times = [...(this.frameTimes.get(key) ?? []), milliseconds].slice(-FRAME_HISTORY);
    this.frameTimes.set(key, times);
    return { milliseconds: median(times), frames: times.length };
  }

  /** One timed panorama at inputs.steps, with the pass count learned for that N. */
  private async drawTimed(renderer: RayleighSkyGpu, inputs: SkyInputs): Promise<PanoramaTime> {
    const passes = this.passCounts.get(inputs.steps) ?? 1;
    const frame = await renderer.draw(inputs, passes);
    this.passCounts.set(inputs.steps, nextPassCount(passes, frame.spanMilliseconds));
    return frame;
  }

  protected async render(): Promise<void> {
    const inputs = inputsFrom(this.values);
    const backend = await this.backends.choose();
    if (!this.canvas) return;
    let shown: Shown;
    if (backend.kind === 'gpu') {
      try {
        const probes = await backend.renderer.probes(inputs);
        const frame = await this.drawTimed(backend.renderer, inputs);
        const recent = this.recordFrame(backend, frame.timing, inputs.steps, frame.milliseconds);
        this.recordFrameCost(frame.milliseconds, timingLabel(frame.timing));
        shown = {
          radiance: probes.radiance,
          sunTransmittance: probes.sunTransmittance,
          probeMilliseconds: probes.milliseconds,
          probeTiming: probes.timing,
          capped: probes.capped,
          picture: { ...recent, passes: frame.passes, timing: frame.timing },
        };
      } catch (error) {
        this.fallBackToCpu(gpuFailureReason(error));
        return;
      }
      this.clearNotice('backend');
    } else {
      const pictureMilliseconds = drawSkyCpu(this.canvas, inputs, CPU_SCALE);
      const start = performance.now();
      const probes = computeProbes(inputs);
      const recent = this.recordFrame(backend, 'cpu', inputs.steps, pictureMilliseconds);
      shown = {
        ...probes,
        probeMilliseconds: performance.now() - start,
        probeTiming: 'cpu',
        capped: false,
        picture: { ...recent, passes: 1, timing: 'cpu' },
      };
      this.showCpuFallbackNotice(
        backend.reason,
        `Showing the float64 CPU twin: the same integral with the same N and M, the picture drawn at quarter resolution.`,
      );
    }
    if (shown.capped) {
      this.showNotice('capped', 'warning', 'A march reached its step cap; the sky is truncated.');
    } else {
      this.clearNotice('capped');
    }
    // Computed once per (sun elevation, scattering) and cached; never per frame.
    const reference = await referenceProbesAsync(inputs);
    this.drawLabels(inputs);
    this.showResult(inputs, shown, reference, backend);
  }

  /** Angle labels over the canvas, in per cent of its size so they follow its CSS size. */
  private drawLabels(inputs: SkyInputs): void {
    if (!this.labels) return;
    const span = ELEVATION_MAX_DEG - ELEVATION_MIN_DEG;
    const top = (elevation: number): number => (100 * (ELEVATION_MAX_DEG - elevation)) / span;
    const label = (text: string, x: number, y: number, className: string): HTMLElement => {
      const element = document.createElement('span');
      element.className = className;
      element.textContent = text;
      element.style.left = `${x}%`;
      element.style.top = `${y}%`;
      return element;
    };
    const half = FIELD_OF_VIEW_DEG / 2;
    const spans: HTMLElement[] = [
      label('horizon 0°', 1, top(0), 'sb-sky-label'),
      label('30°', 1, top(30), 'sb-sky-label'),
      label('60°', 1, top(60), 'sb-sky-label'),
      label(`azimuth −${half}°`, 1, 99, 'sb-sky-label sb-sky-label--note'),
      label(`+${half}°`, 99, 99, 'sb-sky-label sb-sky-label--end sb-sky-label--note'),
    ];
    const e = inputs.sunElevationDeg;
    if (e < 0) {
      spans.push(
        label(
          `sun ${formatNumber(-e, 3)}° below the horizon`,
          50,
          99,
          'sb-sky-label sb-sky-label--centre sb-sky-label--note',
        ),
      );
    } else if (e > ELEVATION_MAX_DEG - 1) {
      spans.push(
        label(
          `sun at ${formatNumber(e, 3)}°, above the frame`,
          50,
          4,
          'sb-sky-label sb-sky-label--centre sb-sky-label--below',
        ),
      );
    } else {
      spans.push(
        label(
          `sun (disc enlarged ×${SUN_ENLARGEMENT})`,
          52,
          Math.max(top(e) - 2.5, 4),
          'sb-sky-label sb-sky-label--note',
        ),
      );
    }
    this.labels.replaceChildren(...spans);
  }

  private showResult(
    inputs: SkyInputs,
    shown: Shown,
    reference: SkyProbes,
    backend: Backend,
  ): void {
    const errors = PROBE_KEYS.map((key, k) => {
      this.set(key, formatRgb(shown.radiance[k]!));
      return relativeError(shown.radiance[k]!, reference.radiance[k]!);
    });
    const worst = errors.reduce<number | null>(
      (a, b) => (b === null ? a : Math.max(a ?? 0, b)),
      null,
    );
    const rms = probeError(shown, reference);
    this.set(
      'error',
      `${formatPercent(worst)} (zenith ${formatPercent(errors[0]!)}, toward ${formatPercent(errors[1]!)}, away ${formatPercent(errors[2]!)})` +
        (rms === null ? '' : `; relative RMS ${formatPercent(rms)}`),
    );
    const sun = shown.sunTransmittance;
    this.set('sun', sun.every((t) => t === 0) ? '0, 0, 0 (the sun has set)' : formatRgb(sun));
    if (this.swatch) {
      const peak = Math.max(...sun, 1e-30);
      const [r, g, b] = sun.map((t) => Math.round(255 * srgbEncode(t / peak)));
      this.swatch.style.background = sun.every((t) => t === 0) ? '#000' : `rgb(${r}, ${g}, ${b})`;
      this.swatch.title = 'Colour of the direct sun, T_sun normalised to its largest channel';
    }
    const zenith = shown.radiance[0]!;
    this.set(
      'zenith-ratio',
      zenith[0] > 0 ? formatNumber(zenith[2] / zenith[0], 4) : 'no sky light (scattering off)',
    );
    this.set('sun-ratio', sun[2] > 0 ? formatNumber(sun[0] / sun[2], 4) : 'no direct sun');

    const work = `N = ${inputs.steps} view samples × M = ${inputs.sunSteps} sun samples per pixel`;
    const { picture } = shown;
    const frames = `median of ${picture.frames} frame${picture.frames === 1 ? '' : 's'} at this N`;
    const passes =
      picture.passes > 1 ? `, each timed over ${picture.passes} passes in one submit` : '';
    const referenceNote = `Reference: float64, N = M = ${REFERENCE_STEPS}, computed once per sun elevation and cached.`;
    const cost = this.readouts?.cost;
    if (cost) {
      cost.textContent =
        backend.kind === 'gpu'
          ? `WebGPU (${backend.gpu.adapterDescription}): panorama ${CANVAS_WIDTH}×${CANVAS_HEIGHT}, ${work}, in ${formatMilliseconds(picture.milliseconds)} per frame (${timingLabel(picture.timing)}, ${frames}${passes}); probes in ${formatMilliseconds(shown.probeMilliseconds)} (${timingLabel(shown.probeTiming)}). ${referenceNote}`
          : `CPU fallback: panorama ${CANVAS_WIDTH / CPU_SCALE}×${CANVAS_HEIGHT / CPU_SCALE}, ${work}, in ${formatMilliseconds(picture.milliseconds)} per frame (${timingLabel('cpu')}, ${frames}); probes in ${formatMilliseconds(shown.probeMilliseconds)} (${timingLabel('cpu')}, float64 twin). ${referenceNote}`;
    }
    if (this.canvas) {
      const probes = probesFor(inputs);
      this.canvas.setAttribute(
        'aria-label',
        `Panorama of the sky toward the sun, 120° wide, from 5° below the horizon to 85° above, with the sun at ${formatNumber(inputs.sunElevationDeg, 3)}° elevation; ` +
          (inputs.scattering
            ? `zenith blue-to-red radiance ratio ${formatNumber(zenith[0] > 0 ? zenith[2] / zenith[0] : 0, 3)} (${probes.length} probe directions listed beside it).`
            : 'scattering is off, so the sky is black and the sun white.'),
      );
    }
  }

  /**
   * Up to SWEEP_FRAMES timed panoramas at inputs.steps (fewer once the point has
   * used SWEEP_POINT_BUDGET_MS). Draws whose pass count was still being raised
   * (nextPassCount) calibrate and are not kept.
   */
  private async sweepFrames(
    backend: Backend & { kind: 'gpu' },
    inputs: SkyInputs,
  ): Promise<PanoramaTime[]> {
    const frames: PanoramaTime[] = [];
    const start = performance.now();
    let passes = this.passCounts.get(inputs.steps) ?? 1;
    let last: PanoramaTime | null = null;
    for (let draws = 0; frames.length < SWEEP_FRAMES && draws < SWEEP_FRAMES + 4; draws++) {
      last = await backend.renderer.draw(inputs, passes);
      const next = nextPassCount(passes, last.spanMilliseconds);
      if (next === passes) {
        frames.push(last);
        this.recordFrame(backend, last.timing, inputs.steps, last.milliseconds);
      } else {
        passes = next;
      }
      if (frames.length > 0 && performance.now() - start > SWEEP_POINT_BUDGET_MS) break;
    }
    this.passCounts.set(inputs.steps, passes);
    if (frames.length === 0 && last) frames.push(last);
    return frames;
  }

  private showFit(fit: SweepFit, scattering: boolean): void {
    const { order, timeExponent, timeOrder } = fit;
    if (order === null) {
      const why = scattering ? 'no fit (an error of 0)' : 'no fit: without air L = 0 at every N';
      this.set('slope', why);
      this.set('time-slope', why);
      return;
    }
    this.set(
      'slope',
      `p = ${formatNumber(order, 3)} (midpoint rule: −2)`,
      Math.abs(order + 2) < 0.25 ? 'ok' : undefined,
    );
    this.set(
      'time-slope',
      timeOrder === null || timeExponent === null
        ? 'no fit (equal times)'
        : `q = ${formatNumber(timeOrder, 3)}, a = ${formatNumber(timeExponent, 3)}`,
    );
  }

  /**
   * Sweeps N over SWEEP_STEPS: at each N the probes' relative RMS error against the
   * cached reference and the median time of a panorama (GPU), or of the float64
   * probes (CPU fallback, which draws no panorama in the sweep: at N = 128 one would
   * hold the page for seconds). Fits the slopes, then redraws at the chosen N.
   */
  private async runSweep(): Promise<void> {
    const sweep = this.sweep;
    if (!sweep) return;
    const run = ++this.sweepRuns;
    let ended = false;
    await sweep.run(async () => {
      const inputs = inputsFrom(this.values);
      const backend = await this.backends.choose();
      const reference = await referenceProbesAsync(inputs);
      this.set('slope', 'sweeping…');
      this.set('time-slope', 'sweeping…');
      const label = `sun at ${formatNumber(inputs.sunElevationDeg, 3)}°${inputs.scattering ? '' : ', no air'}`;
      let timing: Timing = 'cpu';
      let fewestFrames = SWEEP_FRAMES;
      return {
        label,
        measure: async (n) => {
          const at: SkyInputs = { ...inputs, steps: n, sunSteps: sunStepsFor(n) };
          if (backend.kind === 'gpu') {
            const probes = await backend.renderer.probes(at);
            const frames = await this.sweepFrames(backend, at);
            timing = frames[0]!.timing;
            fewestFrames = Math.min(fewestFrames, frames.length);
            return {
              rmse: probeError(probes, reference) ?? 0,
              milliseconds: median(frames.map((f) => f.milliseconds)),
            };
          }
          const { probes, milliseconds } = await timeProbesCpu(at);
          return { rmse: probeError(probes, reference) ?? 0, milliseconds };
        },
        finish: (points) => {
          ended = true;
          this.showFit(fitSweep(points), inputs.scattering);
          return backend.kind === 'gpu'
            ? `${label}; time of one ${CANVAS_WIDTH}×${CANVAS_HEIGHT} panorama (${timingLabel(timing)}), median of ${fewestFrames === SWEEP_FRAMES ? SWEEP_FRAMES : `${fewestFrames} to ${SWEEP_FRAMES}`} frames per N`
            : `${label}; CPU fallback: time of the three float64 probes (${timingLabel('cpu')}), no panorama`;
        },
        failed: () => {
          ended = true;
          this.set('slope', 'failed', 'bad');
          this.set('time-slope', 'failed', 'bad');
        },
      };
    });
    // Cancelled (or stopped by a device loss), and no newer sweep has taken over.
    if (!ended && run === this.sweepRuns) {
      this.set('slope', 'cancelled; run the sweep again');
      this.set('time-slope', 'cancelled; run the sweep again');
    }
    // The sweep drew the panorama at other N: show the chosen N again.
    this.scheduleRender();
  }
}

export function defineRayleighSky(): void {
  if (!customElements.get('sb-rayleigh-sky'))
    customElements.define('sb-rayleigh-sky', RayleighSkyElement);
}
