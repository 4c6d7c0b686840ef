// The drawing of <sb-rayleigh-sky>: the panorama toward the sun (WebGPU, timed over
// frames, or the CPU twin at quarter resolution) with its angle labels, the swatch
// of the direct sun's colour beside its readout, and the sweep over N. Readouts,
// backends and fallback: widget.ts and the base element.
import type { GpuContext } from '../../gpu/device.ts';
import type { Backend } from '../base/backend.ts';
import { formatNumber } from '../base/format.ts';
import { SweepControls } from '../base/sweep.ts';
import { timingLabel } from '../base/timing.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import { workerJobs } from '../../workers/compute.ts';
import {
  GPU_FIRST_PICTURE_MS,
  CPU_FIRST_PICTURE_MS,
  Ladder,
  type FrameRequest,
  type Rung,
  type RungChoice,
} from '../base/refinement.ts';
import { paintSky } from './cpuBackend.ts';
import { RayleighSkyGpu, type GpuProbes, type PanoramaTime } from './gpuBackend.ts';
import type { jobs as skyJobTable } from './jobs.ts';
import {
  CANVAS_HEIGHT,
  CANVAS_WIDTH,
  ELEVATION_MAX_DEG,
  ELEVATION_MIN_DEG,
  FIELD_OF_VIEW_DEG,
  FIT_FROM_STEPS,
  SUN_ENLARGEMENT,
  SWEEP_STEPS,
  fitSweep,
  inputsFrom,
  median,
  nextPassCount,
  probeError,
  probesFor,
  relativeError,
  srgbEncode,
  sunStepsFor,
  type SkyInputs,
  type SkyProbes,
  type SweepFit,
} from './model.ts';
import { CPU_SCALE, type RayleighSkyFrame, type SkyTiming } from './widget.ts';

/** Frame times kept per N and resolution for the readout's median. */
const FRAME_HISTORY = 5;
/** The sweep times each N as the median of up to this many frames… */
const SWEEP_FRAMES = 3;
/** …but stops at fewer once a point has taken this long (SwiftShader: N = 128 ≈ 7 s a frame). */
const SWEEP_POINT_BUDGET_MS = 1500;

/**
 * The panorama's refinement (issue 23): the same integral per pixel (the reader's N
 * and M), on fewer pixels first; the browser scales the canvas up smoothly. Work is
 * the pixel count relative to the full canvas. The GPU climbs to the full canvas, the
 * CPU twin to a quarter of it (its full quality: 1/CPU_SCALE of the resolution).
 */
function skyRungs(divisors: readonly number[]): Rung<number>[] {
  return divisors.map((divisor) => ({
    value: divisor,
    work: 1 / divisor ** 2,
    label: `${CANVAS_WIDTH / divisor}×${CANVAS_HEIGHT / divisor} pixels`,
  }));
}
const GPU_RUNGS = skyRungs([8, 4, 2, 1]);
const CPU_RUNGS = skyRungs([4 * CPU_SCALE, 2 * CPU_SCALE, CPU_SCALE]);

/** Angle labels over the canvas, in per cent of its size so they follow its CSS size. */
function drawLabels(labels: HTMLElement, inputs: SkyInputs): void {
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
  labels.replaceChildren(...spans);
}

export function createView(
  context: ViewContext<RayleighSkyGpu>,
): WidgetView<RayleighSkyFrame, RayleighSkyGpu> {
  const sky = context.canvas({ width: CANVAS_WIDTH, height: CANVAS_HEIGHT });
  const labels = document.createElement('div');
  let swatch: HTMLElement | null = null;
  let sweep: SweepControls | null = null;
  /** Recent panorama times per backend, timing method, N and resolution, for the median readout. */
  const frameTimes = new Map<string, number[]>();
  /** Passes per timed submit, per N and resolution (see nextPassCount). */
  const passCounts = new Map<string, number>();
  /** Counts sweep runs, so a superseded run leaves the readouts to the newer one. */
  let sweepRuns = 0;
  /** The float64 work (reference, CPU panorama and probes) in the compute worker, cached by arguments. */
  const jobs = workerJobs<typeof skyJobTable>('rayleigh-sky');
  /** Each backend learns its own cost per pixel (refinement.ts). */
  const gpuLadder = new Ladder(GPU_RUNGS, GPU_FIRST_PICTURE_MS);
  const cpuLadder = new Ladder(CPU_RUNGS, CPU_FIRST_PICTURE_MS);
  /** The GPU probes of the last inputs: later stages of one picture reuse them. */
  let gpuProbes: { key: string; probes: GpuProbes } | null = null;

  /** Keeps the last FRAME_HISTORY times for this backend, timing, N and size; returns their median. */
  const recordFrame = (
    kind: 'gpu' | 'cpu',
    timing: SkyTiming,
    steps: number,
    size: string,
    milliseconds: number,
  ): { milliseconds: number; frames: number } => {
    const key = `${kind}:${timing}:${steps}:${size}`;
    const times = [...(frameTimes.get(key) ?? []), milliseconds].slice(-FRAME_HISTORY);
    frameTimes.set(key, times);
    return { milliseconds: median(times), frames: times.length };
  };

  const referenceArgs = (inputs: SkyInputs): [number, number, boolean] => [
    inputs.sinSun,
    inputs.cosSun,
    inputs.scattering,
  ];

  /**
   * The probes' errors against the float64 reference, computed once per (sun
   * elevation, scattering) in the worker and cached; never per frame. A preview does
   * not wait for a reference not computed yet (it says so, and the job runs on); the
   * full-quality frame does.
   */
  const compared = async (
    inputs: SkyInputs,
    probes: SkyProbes,
    request: FrameRequest,
    final: boolean,
  ): Promise<Pick<RayleighSkyFrame, 'errors' | 'rms'>> => {
    const args = referenceArgs(inputs);
    let reference = jobs.cached('reference', args);
    if (!reference) {
      const pending = jobs.run('reference', args, { signal: request.signal });
      if (!final) {
        pending.catch(() => undefined);
        return { errors: null, rms: null };
      }
      reference = await pending;
    }
    return {
      errors: probes.radiance.map((rgb, k) => relativeError(rgb, reference.radiance[k]!)),
      rms: probeError(probes, reference),
    };
  };

  /** Sets the canvas to 1/divisor of the full panorama (the GPU draws at the canvas's size). */
  const resize = (divisor: number): { width: number; height: number } => {
    const width = CANVAS_WIDTH / divisor;
    const height = CANVAS_HEIGHT / divisor;
    const canvas = sky.element;
    if (canvas.width !== width) canvas.width = width;
    if (canvas.height !== height) canvas.height = height;
    return { width, height };
  };

  /** One timed panorama at inputs.steps and the canvas's size, with the pass count learned for both. */
  const drawTimed = async (renderer: RayleighSkyGpu, inputs: SkyInputs): Promise<PanoramaTime> => {
    const key = `${inputs.steps}:${sky.element.width}`;
    const passes = passCounts.get(key) ?? 1;
    const frame = await renderer.draw(inputs, passes);
    passCounts.set(key, nextPassCount(passes, frame.spanMilliseconds));
    return frame;
  };

  /** The frame's stage, for the readouts and the base (refinement). */
  const stageOf = (choice: RungChoice<number>): RayleighSkyFrame['stage'] => ({
    ...gpuLadder.refinement(choice),
    final: choice.final,
  });

  /**
   * Up to SWEEP_FRAMES timed panoramas at inputs.steps (fewer once the point has
   * used SWEEP_POINT_BUDGET_MS). Draws whose pass count was still being raised
   * (nextPassCount) calibrate and are not kept.
   */
  const sweepFrames = async (
    renderer: RayleighSkyGpu,
    inputs: SkyInputs,
  ): Promise<PanoramaTime[]> => {
    const frames: PanoramaTime[] = [];
    const start = performance.now();
    const { width, height } = resize(1);
    const key = `${inputs.steps}:${width}`;
    let passes = passCounts.get(key) ?? 1;
    let last: PanoramaTime | null = null;
    for (let draws = 0; frames.length < SWEEP_FRAMES && draws < SWEEP_FRAMES + 4; draws++) {
      resize(1); // a refinement stage drawn meanwhile may have made the canvas smaller
      last = await renderer.draw(inputs, passes);
      const next = nextPassCount(passes, last.spanMilliseconds);
      if (next === passes) {
        frames.push(last);
        recordFrame('gpu', last.timing, inputs.steps, `${width}×${height}`, last.milliseconds);
      } else {
        passes = next;
      }
      if (frames.length > 0 && performance.now() - start > SWEEP_POINT_BUDGET_MS) break;
    }
    passCounts.set(key, passes);
    if (frames.length === 0 && last) frames.push(last);
    return frames;
  };

  const showFit = (fit: SweepFit, scattering: boolean): void => {
    const { order, timeExponent, timeOrder } = fit;
    if (order === null) {
      const why = scattering ? 'no fit (an error of 0)' : 'no fit: without air L = 0 at every N';
      context.setReadout('slope', why);
      context.setReadout('time-slope', why);
      return;
    }
    context.setReadout(
      'slope',
      `p = ${formatNumber(order, 3)} (midpoint rule: −2)`,
      Math.abs(order + 2) < 0.25 ? 'ok' : undefined,
    );
    context.setReadout(
      'time-slope',
      timeOrder === null || timeExponent === null
        ? 'no fit (equal times)'
        : `q = ${formatNumber(timeOrder, 3)}, a = ${formatNumber(timeExponent, 3)}`,
    );
  };

  /**
   * Sweeps N over SWEEP_STEPS: at each N the probes' relative RMS error against the
   * cached reference and the median time of a panorama (GPU), or of the float64
   * probes (CPU fallback, which draws no panorama in the sweep: at N = 128 one would
   * hold the page for seconds). Fits the slopes, then redraws at the chosen N.
   */
  const runSweep = async (controls: SweepControls): Promise<void> => {
    const run = ++sweepRuns;
    let ended = false;
    await controls.run(async () => {
      const inputs = inputsFrom(context.values);
      const backend: Backend<RayleighSkyGpu> = await context.backend();
      const reference = await jobs.run('reference', referenceArgs(inputs), {
        signal: context.signal,
      });
      context.setReadout('slope', 'sweeping…');
      context.setReadout('time-slope', 'sweeping…');
      const label = `sun at ${formatNumber(inputs.sunElevationDeg, 3)}°${inputs.scattering ? '' : ', no air'}`;
      let timing: SkyTiming = 'cpu';
      let fewestFrames = SWEEP_FRAMES;
      return {
        label,
        measure: async (n) => {
          const at: SkyInputs = { ...inputs, steps: n, sunSteps: sunStepsFor(n) };
          if (backend.kind === 'gpu') {
            const probes = await backend.renderer.probes(at);
            const frames = await sweepFrames(backend.renderer, at);
            timing = frames[0]!.timing;
            fewestFrames = Math.min(fewestFrames, frames.length);
            return {
              rmse: probeError(probes, reference) ?? 0,
              milliseconds: median(frames.map((f) => f.milliseconds)),
            };
          }
          // Timed in the worker (jobs.ts: batches of repeats, so never below the clock).
          const { probes, milliseconds } = await jobs.run('probes', [at], {
            signal: context.signal,
          });
          return { rmse: probeError(probes, reference) ?? 0, milliseconds };
        },
        finish: (points) => {
          ended = true;
          showFit(fitSweep(points), inputs.scattering);
          return backend.kind === 'gpu'
            ? `${label}; time of one ${CANVAS_WIDTH}×${CANVAS_HEIGHT} panorama (${timingLabel(timing)}), median of ${fewestFrames === SWEEP_FRAMES ? SWEEP_FRAMES : `${fewestFrames} to ${SWEEP_FRAMES}`} frames per N`
            : `${label}; CPU fallback: time of the three float64 probes (${timingLabel('cpu')}), no panorama`;
        },
        failed: () => {
          ended = true;
          context.setReadout('slope', 'failed', 'bad');
          context.setReadout('time-slope', 'failed', 'bad');
        },
      };
    });
    // Cancelled (or stopped by a device loss), and no newer sweep has taken over.
    if (!ended && run === sweepRuns) {
      context.setReadout('slope', 'cancelled; run the sweep again');
      context.setReadout('time-slope', 'cancelled; run the sweep again');
    }
    // The sweep drew the panorama at other N: show the chosen N again.
    context.scheduleRender();
  };

  return {
    cpuNotice:
      'Showing the float64 CPU twin: the same integral with the same N and M, the picture computed in a worker, refined up to quarter resolution.',
    build(stage) {
      const figure = document.createElement('div');
      figure.className = 'sb-sky-figure';
      labels.className = 'sb-sky-labels';
      labels.setAttribute('aria-hidden', 'true');
      figure.append(sky.element, labels);
      stage.appendChild(figure);
      const controls = new SweepControls(
        stage,
        context.host,
        {
          name: 'N',
          buttonText: `Run sweep N = ${SWEEP_STEPS[0]} … ${SWEEP_STEPS[SWEEP_STEPS.length - 1]}`,
          hint: `Run the sweep to plot the probes' relative RMS error against the GPU time of one panorama for N = ${SWEEP_STEPS.join(', ')} (M = max(4, ⌈N/4⌉) with each), and fit the order of convergence over N ≥ ${FIT_FROM_STEPS}.`,
          color: '#2f7fd1',
          statusClass: 'sb-sky-sweep-status',
          points: SWEEP_STEPS,
          errorName: 'relative RMS error',
        },
        () => void runSweep(controls),
      );
      sweep = controls;
    },
    buildReadoutExtras(area) {
      // The direct sun's colour, next to its numbers.
      const sunRow = area.querySelector('[data-readout="sun"]')?.parentElement;
      swatch = document.createElement('span');
      swatch.className = 'sb-sky-swatch';
      swatch.setAttribute('aria-hidden', 'true');
      sunRow?.appendChild(swatch);
      const orders = document.createElement('p');
      orders.className = 'sb-sky-scope';
      orders.textContent = `Expected: the midpoint rule's error falls as N⁻² for a smooth integrand (p ≈ −2); each view sample costs a fixed part plus M = N/4 sun samples, so the time grows between N and N² (a between 1 and 2) and the error falls as time^(p/a), q between −2 and −1. Below N = ${FIT_FROM_STEPS} the sun ray keeps M = 4 and the curve flattens; with the sun below the horizon the Earth's shadow cuts the integrand and the order drops.`;
      const scope = document.createElement('p');
      scope.className = 'sb-sky-scope';
      scope.textContent =
        'Single Rayleigh scattering only: no ozone, no aerosols, no multiple scattering.';
      area.append(orders, scope);
    },
    createRenderer: (gpu: GpuContext) => new RayleighSkyGpu(gpu, sky.element),
    async renderGpu(renderer, _gpu, request) {
      const started = performance.now();
      const inputs = inputsFrom(context.values);
      const choice = gpuLadder.pick(request);
      const { width, height } = resize(choice.rung.value);
      // The probes do not depend on the resolution: one compute pass per picture.
      const key = JSON.stringify(inputs);
      if (request.stage === 0 || gpuProbes?.key !== key)
        gpuProbes = { key, probes: await renderer.probes(inputs) };
      const probes = gpuProbes.probes;
      const frame = await drawTimed(renderer, inputs);
      const size = `${width}×${height}`;
      const recent = recordFrame('gpu', frame.timing, inputs.steps, size, frame.milliseconds);
      const result: RayleighSkyFrame = {
        inputs,
        probes: { radiance: probes.radiance, sunTransmittance: probes.sunTransmittance },
        probeMilliseconds: probes.milliseconds,
        probeTiming: probes.timing,
        probeRepeats: 1,
        capped: probes.capped,
        picture: {
          ...recent,
          width,
          height,
          lastMilliseconds: frame.milliseconds,
          passes: frame.passes,
          timing: frame.timing,
        },
        stage: stageOf(choice),
        ...(await compared(inputs, probes, request, choice.final)),
      };
      // The ladder learns the whole stage's time (probes and read-back too), not only the pass's.
      gpuLadder.record(choice.index, performance.now() - started);
      return result;
    },
    async renderCpu(request) {
      const started = performance.now();
      const inputs = inputsFrom(context.values);
      const choice = cpuLadder.pick(request);
      const width = CANVAS_WIDTH / choice.rung.value;
      const height = CANVAS_HEIGHT / choice.rung.value;
      // The float64 panorama and probes run in the compute worker: the page never waits on them.
      const image = await jobs.run('panorama', [inputs, width, height], {
        signal: request.signal,
      });
      paintSky(sky.element, image.pixels, width, height);
      const timed = await jobs.run('probes', [inputs], { signal: request.signal });
      const recent = recordFrame(
        'cpu',
        'cpu',
        inputs.steps,
        `${width}×${height}`,
        image.milliseconds,
      );
      const result: RayleighSkyFrame = {
        inputs,
        probes: timed.probes,
        probeMilliseconds: timed.milliseconds,
        probeTiming: 'cpu',
        probeRepeats: timed.repeats,
        capped: false,
        picture: {
          ...recent,
          width,
          height,
          lastMilliseconds: image.milliseconds,
          passes: 1,
          timing: 'cpu',
        },
        stage: stageOf(choice),
        ...(await compared(inputs, timed.probes, request, choice.final)),
      };
      cpuLadder.record(choice.index, performance.now() - started);
      return result;
    },
    refinement: (frame) => frame.stage,
    onCpuFallback: () => sweep?.cancel('stopped: the GPU was lost'),
    destroyRenderer: (renderer) => renderer.destroy(),
    show({ inputs, probes, capped }) {
      if (capped) {
        context.showNotice(
          'capped',
          'warning',
          'A march reached its step cap; the sky is truncated.',
        );
      } else {
        context.clearNotice('capped');
      }
      drawLabels(labels, inputs);
      const sun = probes.sunTransmittance;
      if (swatch) {
        const peak = Math.max(...sun, 1e-30);
        const [r, g, b] = sun.map((t) => Math.round(255 * srgbEncode(t / peak)));
        swatch.style.background = sun.every((t) => t === 0) ? '#000' : `rgb(${r}, ${g}, ${b})`;
        swatch.title = 'Colour of the direct sun, T_sun normalised to its largest channel';
      }
      const zenith = probes.radiance[0]!;
      sky.element.setAttribute(
        'aria-label',
        `Panorama of the sky toward the sun, 120° wide, from 5° below the horizon to 85° above, with the sun at ${formatNumber(inputs.sunElevationDeg, 3)}° elevation; ` +
          (inputs.scattering
            ? `zenith blue-to-red radiance ratio ${formatNumber(zenith[0] > 0 ? zenith[2] / zenith[0] : 0, 3)} (${probesFor(inputs).length} probe directions listed beside it).`
            : 'scattering is off, so the sky is black and the sun white.'),
      );
    },
  };
}
