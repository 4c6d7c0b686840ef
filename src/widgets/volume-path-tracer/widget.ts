// <sb-volume-path-tracer>: single versus multiple scattering in a cloud (chapter 10).
// Two images of the same scene are refined progressively by the scene engine
// (src/scene/): one with scatteringOrder 1, one with unlimited order (volumetric path
// tracing: spectral tracking, next-event estimation, Russian roulette). Each frame adds
// `spp` samples per pixel to both, timed on the GPU. A converged reference of each
// (independent seed, many more samples) is accumulated one pass per frame, cached per
// parameter set, with progress and a cancel button; once it is there, the error of
// every snapshot of the progressive images is plotted against accumulated GPU time on
// log–log axes, where an unbiased estimator falls with slope −½. On WebGPU the images
// accumulate on the GPU and are drawn from there (src/scene/accumulationView.ts); a
// frame reads back only reduced statistics. Without WebGPU the float64 CPU twin renders
// a smaller image with fewer samples, and says so.
import { defineWidget } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel } from '../base/timing.ts';
import type { ImageStatistics } from '../../scene/accumulation.ts';
import type { PassTiming } from '../../scene/render.ts';
import type { Refinement } from '../base/refinement.ts';
import type { SweepPoint } from '../base/sweep.ts';
import type { Budget, PathTracerInputs } from './model.ts';
import { VOLUME_PATH_TRACER } from './schema.ts';

export const ORDERS = ['single', 'multiple'] as const;
export type Order = (typeof ORDERS)[number];

/** One progressive image as a frame reports it. */
export interface ImageNumbers {
  samples: number;
  /** Accumulated pass time (ms). */
  milliseconds: number;
  /** The last pass's time (ms). */
  lastPassMs: number;
  stats: ImageStatistics;
}

/** Error of each image against the finished reference, per snapshot, and the fitted slopes. */
export interface ReferenceErrors {
  points: Record<Order, SweepPoint[]>;
  /** log–log slope of error against time and against spp, from 4 spp on (null: no fit yet). */
  slopes: Record<Order, { time: number | null; spp: number | null }>;
}

/** One frame: both images' numbers, and the reference's state and errors. */
export interface VolumePathTracerFrame {
  inputs: PathTracerInputs;
  budget: Budget;
  paused: boolean;
  images: Record<Order, ImageNumbers>;
  /** How the multiple-scattering image's passes were timed. */
  timing: PassTiming;
  reference: { done: boolean; cancelled: boolean };
  /** Null until the reference is done. */
  errors: ReferenceErrors | null;
  /** A preview (fewer samples than a frame's spp) or the accumulating image. */
  stage: Refinement;
}

/** A fitted slope as the readout and the plot's legend write it. */
export const slopeText = (v: number | null): string =>
  v === null ? 'no fit yet' : formatNumber(v, 3);

function standardErrorText({ stats }: ImageNumbers): string {
  const error = stats.meanStandardError;
  const relative = error / stats.meanRadiance;
  return Number.isFinite(error)
    ? `${formatNumber(error, 3)} W/(m²·sr) (${formatNumber(100 * relative, 3)} % of mean L)`
    : 'needs 2 samples';
}

function errorText(frame: VolumePathTracerFrame, order: Order): string {
  if (!frame.errors)
    return frame.reference.cancelled ? 'no reference' : 'waiting for the reference';
  const latest = frame.errors.points[order].at(-1);
  return latest
    ? `${formatNumber(100 * latest.rmse, 3)} % at ${latest.n} spp`
    : 'within the reference noise';
}

export const widget = defineWidget<VolumePathTracerFrame>({
  entry: VOLUME_PATH_TRACER,
  presets: [
    {
      label: 'white cloud (α = 0.99)',
      values: { scene: 'sphere', albedo: 0.99, g: 0.8, 'optical-thickness': 10 },
    },
    {
      label: 'dark smoke (α = 0.3)',
      values: { scene: 'sphere', albedo: 0.3, g: 0.3, 'optical-thickness': 8 },
    },
    {
      label: 'thin haze (τ = 1)',
      values: { scene: 'sphere', albedo: 0.9, g: 0.6, 'optical-thickness': 1 },
    },
    {
      label: 'puffy grid cloud',
      values: { scene: 'cloud', albedo: 0.98, g: 0.7, 'optical-thickness': 16 },
    },
  ],
  readouts: {
    rows: [
      {
        key: 'spp',
        label: 'Samples per pixel so far',
        format: ({ images, budget, paused }) => {
          const spp = images.multiple.samples;
          return `${spp} of ${budget.maxSpp}${spp >= budget.maxSpp ? ' (done)' : paused ? ' (paused)' : ''}`;
        },
      },
      {
        key: 'stderr-single',
        label: 'Mean standard error, single',
        format: ({ images }) => standardErrorText(images.single),
      },
      {
        key: 'stderr-multiple',
        label: 'Mean standard error, multiple',
        format: ({ images }) => standardErrorText(images.multiple),
      },
      {
        key: 'ratio',
        label: 'Brightness where τ ≥ 1, multiple ÷ single',
        format: ({ images }) => {
          const single = images.single.stats.maskedLuminance;
          const multiple = images.multiple.stats.maskedLuminance;
          return single > 0
            ? `${formatNumber(multiple / single, 3)} (single scattering keeps ${formatNumber((100 * single) / multiple, 3)} %)`
            : 'single scattering is black';
        },
      },
      {
        key: 'error-single',
        label: 'Error vs reference, single',
        format: (frame) => errorText(frame, 'single'),
      },
      {
        key: 'error-multiple',
        label: 'Error vs reference, multiple',
        format: (frame) => errorText(frame, 'multiple'),
      },
      {
        key: 'slope',
        label: 'Fitted slope, error ∝ time^p (∝ spp^p)',
        format: ({ errors }) =>
          errors
            ? ORDERS.map(
                (order) =>
                  `${order} ${slopeText(errors.slopes[order].time)} (vs spp ${slopeText(errors.slopes[order].spp)})`,
              ).join(', ') + '; expected −½'
            : '—',
      },
      {
        key: 'frame',
        label: 'Time per frame (both images)',
        format: ({ images, timing }) =>
          `${formatMilliseconds(images.single.lastPassMs + images.multiple.lastPassMs)} (${timingLabel(timing)})`,
      },
      {
        key: 'per-sample',
        label: 'Time per path sample, multiple',
        format: ({ images, budget }) => {
          const spp = images.multiple.samples;
          const perSample =
            spp > 0
              ? (images.multiple.milliseconds * 1e6) / (spp * budget.width * budget.height)
              : NaN;
          return Number.isFinite(perSample) ? `${formatNumber(perSample, 3)} ns per path` : '—';
        },
      },
      {
        key: 'lookups',
        label: 'Density lookups per path sample',
        format: ({ images, budget, inputs }) => {
          const lookups = (order: Order): string => {
            const { stats } = images[order];
            return formatNumber(
              stats.lookups / Math.max(1, stats.samples * budget.width * budget.height),
              3,
            );
          };
          return inputs.scene === 'cloud'
            ? `single ${lookups('single')}, multiple ${lookups('multiple')}`
            : 'none counted (homogeneous medium, no grid)';
        },
      },
      {
        key: 'capped',
        label: 'Walks stopped at the 1024-vertex cap',
        format: ({ images }) => {
          const capped = images.single.stats.capped + images.multiple.stats.capped;
          return { text: String(capped), state: capped > 0 ? 'bad' : 'ok' };
        },
      },
    ],
    cost: ({ images, timing }) => ({
      milliseconds: images.single.lastPassMs + images.multiple.lastPassMs,
      timing,
    }),
    costLine: ({ budget, images, reference }, how, backend) =>
      `${backend.kind === 'cpu' ? 'the float64 twin, ' : ''}${budget.width}×${budget.height} pixels, ${images.multiple.samples} spp each; accumulated time single ${formatMilliseconds(images.single.milliseconds)}, multiple ${formatMilliseconds(images.multiple.milliseconds)} (${how}). Reference: ${budget.referenceSpp} spp, independent seed, cached per parameter set.${reference.done ? '' : ' Not ready yet.'}`,
  },
  slides: [
    {
      title: 'Clouds are white: single versus multiple scattering',
      attributes: {
        scene: 'sphere',
        albedo: '0.99',
        g: '0.8',
        'optical-thickness': '10',
        spp: '4',
      },
      caption:
        'The same cloud rendered with one scattering event and with all of them. At albedo 0.99 most of the light that leaves the cloud has scattered many times: single scattering keeps only a fraction of it and the cloud turns grey.',
      chapter: '10-multiple-scattering',
    },
    {
      title: 'Path tracing converges as one over the square root of time',
      attributes: {
        scene: 'cloud',
        albedo: '0.98',
        g: '0.7',
        'optical-thickness': '16',
        spp: '8',
      },
      caption:
        'Both images refine progressively; once the converged reference is ready, their relative error is plotted against accumulated GPU time on log–log axes. Both fall with slope −½; the path tracer pays more time per sample for its longer paths.',
      chapter: '10-multiple-scattering',
    },
  ],
  load: () => import('./view.ts'),
});
