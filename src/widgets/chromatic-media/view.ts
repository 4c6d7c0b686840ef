// The drawing of <sb-chromatic-media>: four small pictures side by side (the three
// estimators and the reference), accumulated pass by pass. Each frame runs one pass of
// every estimator (GPU kernel, or the float64 twin in the compute worker), adds it to the
// running sums, and reports the statistics (model.ts); while fewer than `target` samples
// per pixel are in, the frame asks for background refinement, so the pictures keep
// converging while the page stays responsive. Under the pictures, a log–log plot of each
// estimator's RMS error against the reference versus its accumulated time (DESIGN.md:
// accuracy next to cost), one point per pass, started again with the accumulation.
// Readouts, backend choice and fallback are the base element's (widget.ts holds the rows).
import { drawPixels } from '../base/pixels.ts';
import { LinePlot, createPlotArea } from '../base/plot.ts';
import { logLogSlope, mergeSeries, type SweepPoint } from '../base/sweep.ts';
import { formatNumber } from '../base/format.ts';
import type { ManagedCanvas, ViewContext, WidgetView } from '../base/view.ts';
import type { FrameRequest } from '../base/refinement.ts';
import { workerJobs } from '../../workers/compute.ts';
import type { GpuTiming } from '../base/timing.ts';
import { ChromaticGpu } from './gpuBackend.ts';
import type { jobs } from './jobs.ts';
import {
  CPU_SIZE,
  ESTIMATORS,
  ESTIMATOR_INDEX,
  ESTIMATOR_LABELS,
  GPU_SIZE,
  REFERENCE_FACTOR,
  REFERENCE_FRAME_OFFSET,
  accumulate,
  accumulationKey,
  emptyAccumulation,
  estimatorStats,
  inputsFrom,
  means,
  toPixels,
  type Accumulation,
  type ChromaticInputs,
  type EstimatorName,
  type EstimatorStats,
} from './model.ts';
import type { ChromaticFrame } from './widget.ts';

type Pass = (
  inputs: ChromaticInputs,
  estimator: number,
  size: number,
  spp: number,
  frame: number,
) => Promise<{ sums: ArrayLike<number>; milliseconds: number }>;

/**
 * The GPU's preview side: its four passes (three estimators and the reference, one sample
 * per pixel each) took about 50 ms of GPU time at GPU_SIZE on SwiftShader, half of the
 * first-picture budget by themselves (issue 23, firstPictureProbe).
 */
const GPU_PREVIEW_SIZE = GPU_SIZE / 2;
/** GPU time one estimator pass may take (ms): an input waits for the pass in flight. */
const ESTIMATOR_PASS_MS = 20;

interface State {
  key: string;
  size: number;
  estimators: Record<EstimatorName, Accumulation>;
  reference: Accumulation;
  pass: number;
  /** The next estimator pass's stream (shared by the three estimators: the same frame). */
  nextStream: number;
  /** GPU ms per sample per pixel of the costliest estimator's last pass (null: none yet). */
  msPerSpp: number | null;
  /** Passes of the reference so far: each has its own stream (REFERENCE_FRAME_OFFSET on). */
  referencePasses: number;
  /** Each estimator's error against the reference after each pass (the plot's points). */
  errors: Record<EstimatorName, SweepPoint[]>;
}

/**
 * Colour and dash of each estimator's curve (Okabe–Ito colours, as delta-tracking's plot),
 * so that the curves differ in more than colour.
 */
const SERIES_STYLE: Record<EstimatorName, { color: string; dash: number[] }> = {
  oneChannel: { color: '#0072b2', dash: [] },
  hero: { color: '#d55e00', dash: [10, 5] },
  spectral: { color: '#009e73', dash: [2, 4] },
};
/** The slope is fitted over the points from this many samples per pixel on (see below). */
const FIT_MIN_SAMPLES = 4;

/**
 * The fitted exponent p of RMS error ∝ time^p over the points with at least
 * FIT_MIN_SAMPLES samples per pixel (the first passes also pay the fixed cost of a
 * dispatch), or null with fewer than two such points. Both the estimator's and the
 * reference's noise fall as N^(−½) (the reference has REFERENCE_FACTOR× the samples at
 * every point), so an unbiased estimator at a constant cost per sample gives p ≈ −½.
 */
function timeSlope(points: readonly SweepPoint[]): number | null {
  const usable = points.filter((p) => p.n >= FIT_MIN_SAMPLES);
  if (usable.length < 2) return null;
  return logLogSlope(
    usable.map((p) => p.milliseconds),
    usable.map((p) => p.rmse),
  );
}

export function createView(context: ViewContext): WidgetView<ChromaticFrame, ChromaticGpu> {
  const pictures: Record<EstimatorName | 'reference', ManagedCanvas> = {
    oneChannel: context.canvas({
      width: GPU_SIZE,
      height: GPU_SIZE,
      label: ESTIMATOR_LABELS.oneChannel,
    }),
    hero: context.canvas({ width: GPU_SIZE, height: GPU_SIZE, label: ESTIMATOR_LABELS.hero }),
    spectral: context.canvas({
      width: GPU_SIZE,
      height: GPU_SIZE,
      label: ESTIMATOR_LABELS.spectral,
    }),
    reference: context.canvas({ width: GPU_SIZE, height: GPU_SIZE, label: 'Reference' }),
  };
  const cpuJobs = workerJobs<typeof jobs>('chromatic-media');
  let state: State | null = null;
  let plot: LinePlot | null = null;
  let plotArea: HTMLElement | null = null;
  let plotHint: HTMLElement | null = null;

  /** Draws the frame's error points; until there are any, the hint stands in for the plot. */
  function plotErrors(errors: ChromaticFrame['errors']): void {
    if (!plot || !plotArea || !plotHint) return;
    const series = ESTIMATORS.map((name) => errors[name]);
    plotArea.dataset['points'] = series.map((points) => points.length).join(',');
    const empty = series.every((points) => points.length === 0);
    plotHint.hidden = !empty;
    plotArea.hidden = empty;
    if (empty) return;
    const merged = mergeSeries(series);
    // A guide of slope −½ (error ∝ time^(−½), Monte Carlo at a constant cost per sample)
    // through the first point of one channel at a time.
    const anchor = errors.oneChannel[0];
    const guide = merged.x.map((x) =>
      anchor
        ? anchor.rmse * 10 ** (-0.5 * (x - Math.log10(Math.max(anchor.milliseconds, 1e-4))))
        : Number.NaN,
    );
    plot.update(merged.x, [
      ...ESTIMATORS.map((name, i) => {
        const slope = timeSlope(errors[name]);
        return {
          label: `${ESTIMATOR_LABELS[name]}${slope === null ? '' : `, p = ${formatNumber(slope, 3)}`}`,
          ...SERIES_STYLE[name],
          spanGaps: true,
          values: merged.values[i]!,
        };
      }),
      { label: 'slope −½', color: '#888888', dash: [6, 4], values: guide },
    ]);
  }

  function fresh(inputs: ChromaticInputs, size: number): State {
    return {
      key: `${accumulationKey(inputs)}@${size}`,
      size,
      estimators: {
        oneChannel: emptyAccumulation(size),
        hero: emptyAccumulation(size),
        spectral: emptyAccumulation(size),
      },
      reference: emptyAccumulation(size),
      pass: 0,
      nextStream: 0,
      msPerSpp: null,
      referencePasses: 0,
      errors: { oneChannel: [], hero: [], spectral: [] },
    };
  }

  async function frame(
    request: FrameRequest,
    fullSize: number,
    previewSize: number,
    run: Pass,
    timing: GpuTiming | 'cpu',
  ): Promise<ChromaticFrame | null> {
    const inputs = inputsFrom(context.values);
    // The first frame after an input is a preview of one sample per pixel (a quarter of a
    // default pass, within the first-picture budget of issue 23), at `previewSize`; later
    // passes take spp at the full size. A preview at a smaller size is a picture of its own:
    // the full size starts its accumulation afresh (one sample per pixel is not missed).
    const restart = request.stage === 0 && !request.background;
    const preview = restart && inputs.spp > 1;
    const size = preview ? previewSize : fullSize;
    const key = `${accumulationKey(inputs)}@${size}`;
    if (!state || state.key !== key || restart) state = fresh(inputs, size);
    const s = state;
    const spp = preview
      ? 1
      : Math.min(inputs.spp, Math.max(inputs.target - s.estimators.hero.samples, 1));
    let frameMilliseconds = 0;
    // Each estimator's samples in passes of about ESTIMATOR_PASS_MS (the spectral one took
    // 49 ms for 4 spp on SwiftShader, and an input's picture waited for the pass in flight),
    // the sub-passes' streams shared by the three estimators as one pass's were.
    const chunk =
      s.msPerSpp === null
        ? spp
        : Math.max(1, Math.min(spp, Math.floor(ESTIMATOR_PASS_MS / s.msPerSpp)));
    let msPerSpp = 0;
    if (preview) {
      // The preview's four passes (one sample per pixel for each estimator, and the
      // reference's) go to the GPU together and come back together: awaited one by one,
      // each cost a read-back round trip of 7–10 ms in Chrome on SwiftShader
      // (firstPictureProbe). The same streams, accumulated in the same order.
      const passes = await Promise.all([
        ...ESTIMATORS.map((name) => run(inputs, ESTIMATOR_INDEX[name], size, 1, s.nextStream)),
        run(
          inputs,
          ESTIMATOR_INDEX.oneChannel,
          size,
          1,
          REFERENCE_FRAME_OFFSET + s.referencePasses,
        ),
      ]);
      if (request.signal.aborted) return null;
      ESTIMATORS.forEach((name, i) => {
        const pass = passes[i]!;
        accumulate(s.estimators[name], pass.sums, 1, pass.milliseconds);
        frameMilliseconds += pass.milliseconds;
        msPerSpp = Math.max(msPerSpp, pass.milliseconds);
      });
      const reference = passes[ESTIMATORS.length]!;
      s.referencePasses++;
      accumulate(s.reference, reference.sums, 1, reference.milliseconds);
      frameMilliseconds += reference.milliseconds;
    }
    for (const name of preview ? [] : ESTIMATORS) {
      for (let done = 0, part = 0; done < spp; part++) {
        const samples = Math.min(chunk, spp - done);
        const pass = await run(inputs, ESTIMATOR_INDEX[name], size, samples, s.nextStream + part);
        // New inputs meanwhile: the rest of this frame is stale (the next frame draws theirs).
        if (request.signal.aborted) return null;
        accumulate(s.estimators[name], pass.sums, samples, pass.milliseconds);
        frameMilliseconds += pass.milliseconds;
        msPerSpp = Math.max(msPerSpp, pass.milliseconds / samples);
        done += samples;
      }
    }
    s.nextStream += Math.ceil(spp / chunk);
    if (msPerSpp > 0) s.msPerSpp = msPerSpp;
    // The reference: one channel at a time, REFERENCE_FACTOR× the estimators' samples, its
    // own streams, in passes of `chunk` samples (about ESTIMATOR_PASS_MS each) with an input
    // checked between them: one pass of REFERENCE_FACTOR × spp took 60 ms on SwiftShader,
    // and passes of `spp` still 35 ms, which an input's picture waited for
    // (firstPictureProbe). The preview's reference has as many samples as its estimators, not
    // REFERENCE_FACTOR× (its 4 spp cost the first picture 29 ms); the next frame makes up
    // the difference, so every point of the error plot (from 2 samples on) has the ratio.
    const referenceTarget = (preview ? 1 : REFERENCE_FACTOR) * s.estimators.hero.samples;
    while (s.reference.samples < referenceTarget) {
      const samples = Math.min(chunk, referenceTarget - s.reference.samples);
      const reference = await run(
        inputs,
        ESTIMATOR_INDEX.oneChannel,
        size,
        samples,
        REFERENCE_FRAME_OFFSET + s.referencePasses,
      );
      if (request.signal.aborted) return null;
      s.referencePasses++;
      accumulate(s.reference, reference.sums, samples, reference.milliseconds);
      frameMilliseconds += reference.milliseconds;
    }
    s.pass++;
    const referenceMeans = means(s.reference);
    const stats = {} as Record<EstimatorName, EstimatorStats>;
    const milliseconds = {} as Record<EstimatorName, number>;
    for (const name of ESTIMATORS) {
      stats[name] = estimatorStats(s.estimators[name], referenceMeans);
      milliseconds[name] = s.estimators[name].milliseconds;
      // A point per pass once the error is defined (estimatorStats needs two samples per
      // pixel); it is measured against the reference as accumulated so far.
      const rmse = stats[name].rmsError;
      if (s.estimators[name].samples >= 2 && Number.isFinite(rmse) && rmse > 0)
        s.errors[name].push({
          n: s.estimators[name].samples,
          rmse,
          milliseconds: milliseconds[name],
        });
      drawPixels(
        pictures[name].element,
        toPixels(means(s.estimators[name]), size, inputs.exposure),
        size,
        size,
      );
    }
    drawPixels(
      pictures.reference.element,
      toPixels(referenceMeans, size, inputs.exposure),
      size,
      size,
    );
    const samples = s.estimators.hero.samples;
    const done = samples >= inputs.target;
    // The stage line says what the pictures are, as the other accumulating widgets do
    // (volume-path-tracer: "64 spp, done"); the base appends "· accumulating" meanwhile.
    const pictureText = `${size}×${size} pixels, reference ${s.reference.samples}`;
    return {
      inputs,
      size,
      samples,
      referenceSamples: s.reference.samples,
      stats,
      milliseconds,
      frameMilliseconds,
      timing,
      errors: {
        oneChannel: [...s.errors.oneChannel],
        hero: [...s.errors.hero],
        spectral: [...s.errors.spectral],
      },
      refinement: {
        label: done
          ? `${samples} samples per pixel each, done (${pictureText})`
          : `${preview ? 'Preview: ' : ''}${samples} of ${inputs.target} samples per pixel each (${pictureText})`,
        pending: done ? null : preview ? 'frame' : 'background',
      },
    };
  }

  return {
    cpuNotice: `Showing the float64 twin at ${CPU_SIZE}×${CPU_SIZE} pixels; the GPU draws ${GPU_SIZE}×${GPU_SIZE}.`,
    build(stage) {
      const row = document.createElement('div');
      // Two by two, square (the layout is in widgets.css, with the other image widgets').
      row.className = 'sb-chromatic-row';
      for (const [name, picture] of Object.entries(pictures)) {
        const figure = document.createElement('figure');
        figure.appendChild(picture.element);
        const caption = document.createElement('figcaption');
        caption.textContent =
          name === 'reference'
            ? `Reference (${REFERENCE_FACTOR}× samples)`
            : ESTIMATOR_LABELS[name as EstimatorName];
        figure.appendChild(caption);
        row.appendChild(figure);
      }
      stage.appendChild(row);

      plotHint = document.createElement('p');
      plotHint.className = 'sb-sweep-hint';
      plotHint.textContent =
        'The error plot fills in as the passes accumulate (from 2 samples per pixel): the RMS error of each estimator against the reference, against its accumulated time, on log–log axes.';
      plotArea = createPlotArea(
        'Log–log plot of the RMS error against the reference of one channel at a time, hero wavelength and spectral tracking, against accumulated time',
      );
      plotArea.classList.add('sb-chromatic-plot');
      plotArea.hidden = true;
      stage.append(plotHint, plotArea);
      plot = new LinePlot(plotArea, {
        xLabel: 'log₁₀ accumulated time (ms)',
        yLabel: 'RMS error',
        yLog: true,
        height: 220,
      });
    },
    destroy() {
      plot?.destroy();
      plot = null;
    },
    createRenderer: (gpu) => new ChromaticGpu(gpu),
    async renderGpu(renderer, _gpu, request) {
      let timing: GpuTiming = 'gpu-timestamp';
      const run: Pass = async (...args) => {
        const pass = await renderer.pass(...args);
        if (pass.timing === 'gpu-wall') timing = 'gpu-wall';
        return pass;
      };
      const result = await frame(request, GPU_SIZE, GPU_PREVIEW_SIZE, run, 'gpu-timestamp');
      return result && { ...result, timing };
    },
    async renderCpu(request) {
      const run: Pass = (...args) => cpuJobs.run('pass', args);
      return frame(request, CPU_SIZE, CPU_SIZE, run, 'cpu');
    },
    refinement: (f) => f.refinement,
    show(f) {
      plotErrors(f.errors);
      for (const name of ESTIMATORS) {
        const s = f.stats[name];
        pictures[name].element.setAttribute(
          'aria-label',
          `${ESTIMATOR_LABELS[name]}: a sphere of chromatic medium, ${f.samples} samples per pixel, colour noise ${s.colourNoise.toFixed(3)} (×1000).`,
        );
      }
      pictures.reference.element.setAttribute(
        'aria-label',
        `Reference picture, one channel at a time with ${f.referenceSamples} samples per pixel.`,
      );
    },
  };
}
