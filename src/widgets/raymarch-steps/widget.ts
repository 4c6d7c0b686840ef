// <sb-raymarch-steps>: ray marching an emissive, absorbing volume (chapter 5).
// Marches one ray per pixel with N steps on the GPU, shows the image next to its
// error against a converged reference (false colour, labelled scale), the RMSE,
// the GPU time and the clamped linear factors; a cancellable sweep over
// N = 1, 2, 4, …, 256 plots RMSE against GPU time and fits the order of convergence.
import type { Refinement } from '../base/refinement.ts';
import { defineWidget, type FrameCost } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel } from '../base/timing.ts';
import { RAYMARCH_STEPS } from './schema.ts';
import type { MarchImage, MarchInputs } from './model.ts';

/** One image with N steps on the backend in use, compared with the converged reference. */
export interface RaymarchFrame extends FrameCost {
  inputs: MarchInputs;
  image: MarchImage;
  reference: ArrayLike<number>;
  /** Steps per ray of the reference (midpoint, exact update). */
  referenceSteps: number;
  rmse: number;
  largestError: number;
  /** A march reached its step cap (GPU only): the image is truncated. */
  capped: boolean;
  /** The GPU's refinement stage (a smaller image first); absent on the CPU (one stage). */
  refinement?: Refinement;
}

export const widget = defineWidget<RaymarchFrame>({
  entry: RAYMARCH_STEPS,
  presets: [
    { label: 'left, N = 8', values: { placement: 'left', steps: 8, update: 'exact' } },
    { label: 'midpoint, N = 8', values: { placement: 'midpoint', steps: 8, update: 'exact' } },
    {
      label: 'jittered strata, N = 8',
      values: { placement: 'jittered-strata', steps: 8, update: 'exact' },
    },
    {
      label: 'linear update, N = 4 (fails)',
      values: { placement: 'left', steps: 4, update: 'linear' },
    },
  ],
  readouts: {
    rows: [
      {
        key: 'rmse',
        label: 'RMSE against the reference',
        format: (frame) => formatNumber(frame.rmse, 3),
      },
      {
        key: 'max-error',
        label: 'Largest pixel error',
        format: (frame) => formatNumber(frame.largestError, 3),
      },
      {
        key: 'time',
        label: 'Time per render',
        format: (frame) =>
          `${formatMilliseconds(frame.milliseconds)} (${timingLabel(frame.timing)})`,
      },
      {
        key: 'clamped',
        label: 'Clamped steps (1 − σt·h < 0)',
        format: ({ inputs, image }) => {
          if (!inputs.linear) return { text: '0 (exact update)', state: 'ok' };
          if (image.clampedSteps === 0) return { text: '0 (σt·h ≤ 1 on every step)', state: 'ok' };
          return {
            text: `${image.clampedSteps} steps in ${image.clampedPixels} of ${image.width * image.height} rays`,
            state: 'bad',
          };
        },
      },
      // Written by the sweep (view.ts).
      { key: 'slope', label: 'Sweep: fitted order, RMSE ∝ N^p', initial: 'run the sweep' },
    ],
    cost: ({ milliseconds, timing }) => ({ milliseconds, timing }),
    costLine: ({ inputs, image, milliseconds, referenceSteps }, how, backend) =>
      `${backend.kind === 'cpu' ? 'the float64 twin, ' : ''}${image.width}×${image.height} rays × N = ${inputs.steps} steps in ${formatMilliseconds(milliseconds)} (${how}). ` +
      `Reference: midpoint, exact update, N = ${referenceSteps}, computed once per density scale.`,
  },
  slides: [
    {
      title: 'Ray marching: left versus midpoint samples',
      attributes: { steps: '8', placement: 'midpoint', update: 'exact', density: '1.5', seed: '0' },
      caption:
        'The same 8 steps per ray, sampled at the middle of each step instead of its start: the error falls from O(h) to O(h²). Run the sweep to measure the order.',
      chapter: '05-emission-absorption-and-ray-marching',
    },
    {
      title: 'The linearised update fails',
      attributes: { steps: '4', placement: 'left', update: 'linear', density: '1.5', seed: '0' },
      caption:
        'T ← T·(1 − σt·h) turns negative where σt·h > 1; the book clamps it to 0 and counts the clamped steps. The exact factor e^(−σt·h) never fails.',
      chapter: '05-emission-absorption-and-ray-marching',
    },
  ],
  load: () => import('./view.ts'),
});
