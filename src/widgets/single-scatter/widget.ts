// <sb-single-scatter>: single scattering through fog or smoke (chapter 9), rendered by
// the scene engine (src/scene/) from a scene the widget builds (model.ts). The image
// accumulates progressively, a few samples per pixel per animation frame, with its
// per-pixel standard error; a reference of the same scene with eight times the samples
// and another seed (cached per scene) gives the error, plotted against the accumulated
// GPU time on log–log axes next to the slope −½ of Monte Carlo. The plan of the scene
// (src/scene/plan.ts) is listed effect by effect, and the specialized kernel's time per
// sample is measured against the general kernel's (DESIGN.md contract 3). On WebGPU the
// image accumulates on the GPU and both pictures are drawn from there
// (src/scene/accumulationView.ts); a frame reads back only reduced statistics.
import { defineWidget } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel } from '../base/timing.ts';
import type { PassTiming } from '../../scene/render.ts';
import type { Refinement } from '../base/refinement.ts';
import { SINGLE_SCATTER } from './schema.ts';

/** Timed passes per kernel for the specialized-versus-general comparison (median). */
export const TIMING_REPEATS = 3;

/**
 * The two kernels on the same scene: time per sample per pixel and the variance of one
 * sample (mean over pixels and channels). Time per sample alone is not the cost of an
 * image: the specialized estimator may spend more per sample (an equiangular point and
 * its shadow ray per spot light) to get less variance. The time to reach a given error
 * is proportional to variance × time per sample (the inverse of the efficiency).
 */
export interface KernelTimes {
  planMs: number;
  generalMs: number;
  planVariance: number;
  generalVariance: number;
  timing: PassTiming;
  samples: number;
}

/** One frame of the progressive image, its reference and the kernel comparison. */
export interface SingleScatterFrame {
  width: number;
  height: number;
  samples: number;
  target: number;
  /** RMS of the per-pixel standard errors (NaN below 2 samples). */
  rmsStandardError: number;
  reference: { samples: number; target: number; done: boolean };
  /** RMSE of the image against the finished reference (NaN while it is not done). */
  rmse: number;
  /** Fitted log–log slope of RMSE against spp (null: not enough points yet). */
  slope: number | null;
  /** The last pass of the image: its time (ms) and size (spp). */
  lastFrameMs: number;
  perPass: number;
  /** Accumulated pass time of the image (ms), and how it was measured. */
  elapsedMs: number;
  timing: PassTiming;
  /** Null until both kernels were timed (after the reference). */
  times: KernelTimes | null;
  /** The run's first frame is a preview (one pass); then the image accumulates. */
  stage: Refinement;
}

function savedText(times: KernelTimes): { text: string; state: 'ok' | 'bad' } {
  // Time to a given error ∝ variance × time per sample.
  const planCost = times.planVariance * times.planMs;
  const generalCost = times.generalVariance * times.generalMs;
  const perSample = 1 - times.planMs / times.generalMs;
  const equalError = 1 - planCost / generalCost;
  return {
    text: `${formatNumber(100 * equalError, 2)} % of the time to the same error (${formatNumber(100 * perSample, 2)} % per sample)`,
    state: equalError > 0 ? 'ok' : 'bad',
  };
}

export const widget = defineWidget<SingleScatterFrame>({
  entry: SINGLE_SCATTER,
  presets: [
    {
      label: 'spot light, fog, sphere',
      values: { light: 'spot', medium: 'fog', occluder: 'sphere', scattering: 'on' },
    },
    {
      label: 'sun through fog, box',
      values: { light: 'directional', medium: 'fog', occluder: 'box', scattering: 'on' },
    },
    {
      label: 'smoke grid in the spot',
      values: { light: 'spot', medium: 'smoke', occluder: 'sphere', scattering: 'on' },
    },
    {
      label: 'no scattering, glowing fog',
      values: { scattering: 'off', emission: 'on', albedo: 0.5, floor: 'off', occluder: 'none' },
    },
  ],
  readouts: {
    rows: [
      {
        key: 'spp',
        label: 'Samples per pixel so far',
        format: ({ samples, target }) =>
          samples >= target
            ? { text: `${samples} of ${target}`, state: 'ok' }
            : `${samples} of ${target}`,
      },
      {
        key: 'std-error',
        label: 'Per-pixel standard error (RMS)',
        // One sample has no sample variance (the accumulator returns NaN): say so.
        format: ({ samples, rmsStandardError }) =>
          samples < 2 ? 'needs ≥ 2 samples' : formatNumber(rmsStandardError, 3),
      },
      {
        key: 'error',
        label: 'RMSE against the reference',
        format: ({ reference, rmse }) =>
          reference.done ? formatNumber(rmse, 3) : 'waiting for the reference',
      },
      {
        key: 'reference',
        label: 'Reference',
        format: ({ reference }) =>
          reference.done
            ? `${reference.target} spp, another seed (cached)`
            : `computing: ${reference.samples} of ${reference.target} spp`,
      },
      {
        key: 'slope',
        label: 'Fitted slope, log RMSE vs log spp',
        format: ({ slope }) =>
          slope === null
            ? 'needs the reference and 16 spp'
            : `${formatNumber(slope, 2)} (expected −0.5)`,
      },
      {
        key: 'frame',
        label: 'Last frame (GPU time)',
        format: ({ lastFrameMs, perPass, timing }) =>
          `${formatMilliseconds(lastFrameMs)}, ${perPass} spp per pass (${timingLabel(timing)})`,
      },
      {
        key: 'time-plan',
        label: 'Time per sample, specialized kernel',
        format: ({ times }) =>
          times
            ? `${formatMilliseconds(times.planMs)} per spp, variance ${formatNumber(times.planVariance, 3)} (${timingLabel(times.timing)})`
            : 'after the reference',
      },
      {
        key: 'time-general',
        label: 'Time per sample, general kernel',
        format: ({ times }) =>
          times
            ? `${formatMilliseconds(times.generalMs)} per spp, variance ${formatNumber(times.generalVariance, 3)}`
            : 'after the reference',
      },
      {
        key: 'saved',
        label: 'Time the plan saves',
        // With the reference done the kernels are timed in the same frame (the view says
        // "timing both kernels…" meanwhile), so no times then means they are on their way.
        format: ({ times, reference }) =>
          times
            ? savedText(times)
            : reference.done
              ? 'timing both kernels…'
              : 'after the reference',
      },
    ],
    cost: ({ lastFrameMs, timing }) => ({ milliseconds: lastFrameMs, timing }),
    costLine: (
      { width, height, samples, target, reference, elapsedMs, timing, times },
      how,
      backend,
    ) =>
      `${backend.kind === 'cpu' ? 'the float64 twin, ' : ''}${width}×${height} pixels, ${samples} spp in ${formatMilliseconds(elapsedMs)} of ${timing === 'cpu' ? 'CPU' : 'GPU'} time (${how}). Reference: ${reference.target / target}× the target samples with an independent seed, computed once per scene${times ? `; kernels timed over ${TIMING_REPEATS} passes of ${times.samples} spp each, median` : ''}.`,
  },
  slides: [
    {
      title: 'Single scattering: a shaft of shadow in the fog',
      attributes: {
        light: 'spot',
        medium: 'fog',
        occluder: 'sphere',
        spp: '256',
      },
      caption:
        'Every visible point of the fog sends a shadow ray to the spot light; where the sphere blocks them, a dark cone cuts through the beam. The table is the plan: what the kernel compiled, how, and why; the readouts time it against the general kernel.',
      chapter: '09-single-scattering',
    },
    {
      title: 'Switch scattering off: the plan shrinks',
      attributes: {
        scattering: 'off',
        emission: 'on',
        albedo: '0.5',
        floor: 'off',
        occluder: 'none',
      },
      caption:
        'With σs = 0 and no surfaces nothing can scatter light towards the eye: the planner skips in-scattering, phase functions, shadow rays and lights, and the kernel is an emission–absorption integral in closed form.',
      chapter: '09-single-scattering',
    },
  ],
  load: () => import('./view.ts'),
});
