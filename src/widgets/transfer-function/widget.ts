// <sb-transfer-function>: direct volume rendering of a CT head phantom (chapter 7).
// The GPU ray casts the volume with emission–absorption compositing through a
// transfer function edited over the data's histogram; the camera orbits by drag or
// arrow keys. Next to the picture: the GPU time per frame, the error against a
// fine-step reference (computed once per transfer function and view, band by band,
// with progress, cancellable), the steps early ray termination takes and saves,
// its bias bound, and a cancellable sweep of RMSE against time over the step size.
import { defineWidget } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import type { GpuTiming } from '../base/timing.ts';
import type { FrameInputs, VolumeImage } from './model.ts';
import { TRANSFER_PRESETS, presetValues } from './presets.ts';
import { TRANSFER_FUNCTION } from './schema.ts';

/** One frame: the inputs, the image and its cost, and what the readouts need of the volume. */
export interface TransferFrame {
  inputs: FrameInputs;
  image: VolumeImage;
  milliseconds: number;
  timing: GpuTiming | 'cpu';
  /** How the time was measured (timingLabel of `timing`). */
  how: string;
  /** The bias bound ε·L_max of early termination (0 without it). */
  biasBound: number;
  /** The voxel's side (m), for the step in millimetres. */
  voxel: number;
}

export function formatCount(n: number): string {
  if (n >= 1e6) return `${formatNumber(n / 1e6, 3)} M`;
  if (n >= 1e4) return `${formatNumber(n / 1e3, 3)} k`;
  return String(n);
}

function formatStep(voxels: number, voxel: number): string {
  return `${formatNumber(voxels, 4)} voxel${voxels === 1 ? '' : 's'} (${formatNumber(voxels * voxel * 1000, 3)} mm)`;
}

export const widget = defineWidget<TransferFrame>({
  entry: TRANSFER_FUNCTION,
  presets: TRANSFER_PRESETS.map((preset) => ({
    label: preset.label,
    values: presetValues(preset),
  })),
  // The presets are transfer functions, not views: they keep the camera, the step and the rest.
  presetKeeps: ['step', 'termination', 'epsilon', 'panel', 'azimuth', 'elevation'],
  readouts: {
    rows: [
      {
        key: 'time',
        label: 'Time per frame',
        format: ({ milliseconds, how }) => `${formatMilliseconds(milliseconds)} (${how})`,
      },
      // The error rows wait for the fine-step reference: the view writes them.
      { key: 'rmse', label: 'RMSE against the fine-step reference' },
      { key: 'max-error', label: 'Largest pixel error' },
      {
        key: 'steps',
        label: 'Steps taken / without early termination',
        format: ({ inputs, image }) => {
          const share = image.plannedSteps > 0 ? image.steps / image.plannedSteps : 1;
          return inputs.termination
            ? `${formatCount(image.steps)} of ${formatCount(image.plannedSteps)} (${formatNumber(100 * share, 3)}%), ${formatCount(image.terminatedRays)} rays stopped early`
            : `${formatCount(image.steps)} (every ray to its end)`;
        },
      },
      // Measured after the frame, with the other termination setting: the view writes it.
      { key: 'saving', label: 'Early termination saves' },
      {
        key: 'bias',
        label: 'Termination bias bound ε·L_max',
        format: ({ inputs, biasBound }) => ({
          text: inputs.termination
            ? `≤ ${formatNumber(biasBound, 3)} (ε = ${formatNumber(inputs.epsilon, 3)})`
            : '0 (no termination)',
          state: 'ok',
        }),
      },
      { key: 'slope', label: 'Sweep: fitted order, RMSE ∝ Δs^q', initial: 'run the sweep' },
    ],
    cost: ({ milliseconds, timing }) => ({ milliseconds, timing }),
    costLine: ({ inputs, image, milliseconds, voxel }, how, backend) =>
      `${backend.kind === 'cpu' ? 'float64 twin, ' : ''}${image.size}×${image.size} rays, Δs = ${formatStep(inputs.step, voxel)}, ${formatMilliseconds(milliseconds)} per frame (${how}). Reference: Δs = ⅛ voxel, stopped at T < 10⁻⁶, once per transfer function and view.`,
  },
  slides: [
    {
      title: 'Transfer functions: from Hounsfield units to light',
      attributes: {
        step: '1',
        termination: 'on',
        colormap: 'tissue',
      },
      caption:
        'A CT head phantom in HU, ray cast with emission–absorption. Drag the opacity points over the histogram or press 1–4 for presets; drag the image to orbit. The error image shows the wood-grain rings of one-voxel steps.',
      chapter: '07-volume-visualization',
    },
    {
      title: 'Early ray termination: the skin surface',
      attributes: {
        colormap: 'tissue',
        panel: 'steps',
        'hu-2': '-700',
        'hu-3': '-450',
        'opacity-3': '0.4',
        'hu-4': '100',
        'opacity-4': '0.5',
        'hu-5': '1000',
        'opacity-5': '0.6',
        'hu-6': '3071',
        'opacity-6': '0.6',
      },
      caption:
        'Rays stop once T < ε, a few voxels behind the skin: the steps image shows it. The bias stays below ε·L_max; switch termination off and compare the steps and the GPU time.',
      chapter: '07-volume-visualization',
    },
  ],
  load: () => import('./view.ts'),
});
