// <sb-delta-tracking>: unbiased and biased transmittance estimators (chapter 6).
// Averages spp estimates per pixel on the GPU, shows the mean transmittance
// next to the per-pixel variance (false colour, labelled scale), the RMSE and
// mean bias against the exact T, the lookups per estimate and the GPU time; a
// cancellable sweep over spp = 1, 2, 4, …, 256 plots RMSE against GPU time.
// The comparison view (view=compare) renders all five estimators side by side,
// once at the same spp and once at the same GPU time (the spp of each from its
// measured cost per sample, compare.ts), and sweeps all five into one log–log
// plot of RMSE against time with each curve's fitted slope. The comparison is a
// long job with readouts of its own (view.ts); the rows below are the single view's.
import type { Refinement } from '../base/refinement.ts';
import { defineWidget, type FrameCost } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel } from '../base/timing.ts';
import { DELTA_TRACKING } from './schema.ts';
import type { ImageStatistics, TrackingImage, TrackingInputs } from './model.ts';

export const MAJORANT_NAMES: Readonly<Record<string, string>> = {
  tight: 'tight majorant',
  loose: 'loose majorant (×3)',
  low: 'majorant too low (×0.5)',
};

/** One image of the single view: spp estimates per pixel against the exact T. */
export interface TrackingFrame extends FrameCost {
  inputs: TrackingInputs;
  image: TrackingImage;
  variance: Float64Array;
  stats: ImageStatistics;
  estimatorName: string;
  /** Which stage of the refinement (fewer samples of the same streams first), if staged. */
  refinement?: Refinement;
}

/** The mean bias is significant at 5 SE (the book's threshold for "biased", physics.md §4.5). */
export function significantBias(image: TrackingImage, stats: ImageStatistics): boolean {
  return image.spp >= 2 && Math.abs(stats.bias) > 5 * stats.biasError;
}

export const widget = defineWidget<TrackingFrame>({
  entry: DELTA_TRACKING,
  presets: [
    { label: 'delta tracking, tight', values: { estimator: 'delta', majorant: 'tight' } },
    { label: 'ratio tracking', values: { estimator: 'ratio', majorant: 'tight' } },
    { label: 'biased exp(−τ̂)', values: { estimator: 'biased', majorant: 'tight' } },
    { label: 'majorant too low', values: { estimator: 'delta', majorant: 'low' } },
    {
      label: 'all five, equal time',
      values: { view: 'compare', estimator: 'delta', majorant: 'tight' },
    },
    {
      label: 'all five, loose majorant',
      values: { view: 'compare', estimator: 'delta', majorant: 'loose' },
    },
  ],
  readouts: {
    rows: [
      {
        key: 'rmse',
        label: 'RMSE against the exact T',
        format: ({ stats }) => formatNumber(stats.rmse, 3),
      },
      {
        key: 'bias',
        label: 'Mean bias (± 1 SE)',
        format: ({ image, stats }) => {
          if (image.spp < 2) return `${formatNumber(stats.bias, 3)} (SE needs spp ≥ 2)`;
          const significant = significantBias(image, stats);
          const text = `${formatNumber(stats.bias, 3)} ± ${formatNumber(stats.biasError, 2)}${significant ? ' (biased)' : ''}`;
          return significant ? { text, state: 'bad' } : text;
        },
      },
      {
        key: 'lookups',
        label: 'Density lookups per estimate',
        format: ({ stats }) => formatNumber(stats.lookupsPerEstimate, 3),
      },
      {
        key: 'time',
        label: 'Time per render',
        format: (frame) =>
          `${formatMilliseconds(frame.milliseconds)} (${timingLabel(frame.timing)})`,
      },
      {
        key: 'capped',
        label: 'Capped estimates',
        format: ({ image }) => ({
          text: String(image.capped),
          state: image.capped > 0 ? 'bad' : 'ok',
        }),
      },
      // Written by the sweep (view.ts).
      { key: 'slope', label: 'Sweep: fitted RMSE ∝ spp^p', initial: 'run the sweep' },
    ],
    cost: ({ milliseconds, timing }) => ({ milliseconds, timing }),
    costLine: ({ inputs, image, milliseconds, estimatorName }, how, backend) =>
      `${backend.kind === 'cpu' ? 'the float64 twin, ' : ''}${image.width}×${image.height} rays × spp = ${image.spp} estimates (${estimatorName}, ${MAJORANT_NAMES[inputs.majorant] ?? inputs.majorant}) in ${formatMilliseconds(milliseconds)} (${how}). ` +
      'Reference: the exact T = e^(−τ) from the closed-form optical depth.',
  },
  slides: [
    {
      title: 'Delta tracking: unbiased, binary transmittance',
      attributes: {
        estimator: 'delta',
        spp: '4',
        majorant: 'tight',
        seed: '0',
      },
      caption:
        'Each sample is 0 or 1 and its mean is exactly T, with variance T(1 − T). Switch to exp(−τ̂) and the mean bias stays, however many samples: run the sweep for both.',
      chapter: '06-unbiased-transmittance',
    },
    {
      title: 'Five estimators at equal samples and equal time',
      attributes: {
        view: 'compare',
        estimator: 'delta',
        spp: '8',
        majorant: 'tight',
        seed: '0',
      },
      caption:
        'Top row: the same spp for all five; bottom row: the same GPU time as delta tracking at that spp. exp(−τ̂) stays biased however many samples it gets; unbiased ray marching wins by orders of magnitude. Sweep all five: four curves fall with slope −½, one levels off.',
      chapter: '06-unbiased-transmittance',
    },
    {
      title: 'A majorant that is too low',
      attributes: {
        estimator: 'delta',
        spp: '16',
        majorant: 'low',
        seed: '0',
      },
      caption:
        'With σ̄ below σt, delta tracking accepts too few collisions and the image is too bright: E[X] = exp(−∫min(σt, σ̄)). Ratio tracking with the same majorant stays unbiased, at a higher variance.',
      chapter: '06-unbiased-transmittance',
    },
  ],
  load: () => import('./view.ts'),
});
