// <sb-inverse-render>: inverse volume rendering (chapter 8). The target images of a
// hidden volume, from N training views and one held-out view, are rendered once by
// the book's ray marcher; Start fits a grid of raw density and emission to the
// training images with Adam, on the GPU (shaders/kernels/inverse-render.wesl) or,
// without WebGPU, with the float64 twin in a Web Worker. The training is a long job
// (view.ts): it reports a frame after each batch of iterations.
import { defineWidget, type FrameCost } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import type { Refinement } from '../base/refinement.ts';
import { INVERSE_RENDER } from './schema.ts';

/** What the readouts and the cost line need from the training's current state. */
export interface InverseRenderFrame {
  /** The fitted model: the voxel grid or the neural field (hash grid + MLP). */
  model: 'grid' | 'neural';
  /** Learned parameters (f32 each on the GPU). */
  parameters: number;
  /** Entries per level of the neural field's hash tables. */
  tableSize: number;
  /** Wall time of training so far (s). */
  trainSeconds: number;
  /** The other model's latest run on the same views, for the side-by-side comparison. */
  comparison: {
    model: 'grid' | 'neural';
    iterations: number;
    seconds: number;
    /** Mean batch loss of its last 10 iterations. */
    loss: number;
    novelMse: number | null;
  } | null;
  iteration: number;
  /** The iteration budget (parameter `iterations`). */
  budget: number;
  /** Loss of the last iteration's batch; null before the first iteration. */
  lastLoss: number | null;
  /** Training MSE over all pixels at the last redraw, and at iteration 0. */
  trainMse: number;
  initialTrainMse: number;
  /** First iteration where the mean of the last 10 losses is a tenth of the start. */
  tenfoldAt: number | null;
  /** Held-out view MSE at the last redraw. */
  novelMse: number | null;
  /** Iterations per second over the last few seconds; NaN when not running yet. */
  rate: number;
  /** Time per iteration over the same window (ms); null when no iterations in it. */
  iterationMs: number | null;
  /** How `iterationMs` was measured ('float64, CPU' or the GPU timing label). */
  timing: string;
  dropped: number;
  /** The measured cost: per iteration once training ran, else the render of every view. */
  cost: FrameCost;
  /** Wall time of setting up the problem: the targets and the first render of every view (ms). */
  setupMs: number;
  /** The last batch of iterations (one step of the training job) and its wall time (ms). */
  lastBatch: { iterations: number; milliseconds: number } | null;
  resolution: number;
  trainViews: number;
  size: number;
  steps: number;
  rays: number;
  learningRate: number;
  regularizer: string;
  /**
   * Set during set-up (issue 23): the target views are drawn and the first render of the
   * fit is under way, so the training numbers are not known yet. Absent once set up.
   */
  refinement?: Refinement;
}

/** Bytes as KiB or MiB. */
function formatBytes(bytes: number): string {
  return bytes >= 1024 * 1024
    ? `${formatNumber(bytes / (1024 * 1024), 3)} MiB`
    : `${formatNumber(bytes / 1024, 3)} KiB`;
}

/** The fitted model in the cost line. */
function modelText(frame: InverseRenderFrame): string {
  if (frame.model === 'neural')
    return `a neural field (hash encoding 8 levels × ${frame.tableSize.toLocaleString('en')} entries × 2 features and an MLP 16–16–4, ${frame.parameters.toLocaleString('en')} parameters)`;
  return `a ${frame.resolution}³ grid (${frame.parameters.toLocaleString('en')} parameters)`;
}

/** What the frame cost: the set-up of the problem before training, then the last batch of iterations. */
function costText(frame: InverseRenderFrame, how: string): string {
  if (frame.refinement)
    return `set-up in progress: the targets of every view drawn in ${formatMilliseconds(frame.cost.milliseconds)} wall time; the first render of the fit follows.`;
  const setup = `set-up (targets and the first render of every view) ${formatMilliseconds(frame.setupMs)} wall time`;
  if (!frame.lastBatch || frame.iteration === 0)
    return `Render of every view in ${formatMilliseconds(frame.cost.milliseconds)} (${how}); ${setup}.`;
  const { iterations, milliseconds } = frame.lastBatch;
  return `${formatMilliseconds(frame.cost.milliseconds)} per iteration (${how}); last step of the run: ${iterations} iteration${iterations === 1 ? '' : 's'} in ${formatMilliseconds(milliseconds)} wall time; ${setup}.`;
}

export const widget = defineWidget<InverseRenderFrame>({
  entry: INVERSE_RENDER,
  presets: [
    {
      label: '8 views, 32³',
      values: { model: 'grid', rate: 0.05, batch: 1024, views: 8, grid: '32', regularizer: 'none' },
    },
    {
      label: '3 views: ambiguity',
      values: { model: 'grid', rate: 0.05, batch: 1024, views: 3, regularizer: 'none' },
    },
    {
      label: '1 view: no depth',
      values: { model: 'grid', rate: 0.05, batch: 1024, views: 1, regularizer: 'none' },
    },
    {
      label: '8 views, 16³: fewer unknowns',
      values: { model: 'grid', rate: 0.05, batch: 1024, views: 8, grid: '16' },
    },
    {
      label: '8 views + smoothness prior',
      values: {
        model: 'grid',
        rate: 0.05,
        batch: 1024,
        views: 8,
        regularizer: 'tv',
        weight: 0.001,
      },
    },
    {
      label: '8 views + sparsity prior',
      values: {
        model: 'grid',
        rate: 0.05,
        batch: 1024,
        views: 8,
        regularizer: 'sparsity',
        weight: 0.003,
      },
    },
    {
      // The neural field's defaults: the problem that one minute of SwiftShader trains
      // to a recognisable held-out view (chapter 8, "Time"; bench/neural.ts).
      label: '4 views, neural field (hash grid + MLP)',
      values: { model: 'neural', views: 4, table: '12', rate: 0.05, batch: 256, steps: 16 },
    },
  ],
  readouts: {
    rows: [
      {
        key: 'iteration',
        label: 'Iteration',
        format: (frame) => `${frame.iteration} of ${frame.budget}`,
      },
      {
        key: 'loss',
        label: 'Training loss (last batch, MSE)',
        format: (frame) =>
          frame.lastLoss === null ? 'press Start' : formatNumber(frame.lastLoss, 3),
      },
      {
        key: 'train-mse',
        label: 'Training MSE, all pixels',
        format: (frame) =>
          frame.refinement
            ? '— (setting up: the first render of the fit follows)'
            : `${formatNumber(frame.trainMse, 3)} (at the last redraw)`,
      },
      {
        key: 'reduction',
        label: 'Reduction from the start',
        format: (frame) => {
          if (frame.refinement) return '— (setting up)';
          const text =
            frame.iteration === 0
              ? `start: ${formatNumber(frame.initialTrainMse, 3)}`
              : `${formatNumber(frame.initialTrainMse / frame.trainMse, 3)}×${frame.tenfoldAt !== null ? `; 10× by iteration ${frame.tenfoldAt}` : ''}`;
          return frame.tenfoldAt !== null ? { text, state: 'ok' } : text;
        },
      },
      {
        key: 'novel-mse',
        label: 'Held-out view MSE (PSNR)',
        format: (frame) =>
          frame.novelMse === null
            ? '—'
            : `${formatNumber(frame.novelMse, 3)} (${formatNumber(10 * Math.log10(1 / frame.novelMse), 3)} dB)`,
      },
      {
        key: 'memory',
        label: 'Model size',
        format: (frame) =>
          `${frame.parameters.toLocaleString('en')} parameters, ${formatBytes(4 * frame.parameters)} (${
            frame.model === 'neural'
              ? `hash tables 8 × ${frame.tableSize.toLocaleString('en')} × 2 + MLP 340`
              : `grid ${frame.resolution}³ × 4`
          })`,
      },
      {
        key: 'comparison',
        label: 'Other model, last run on these views',
        format: (frame) => {
          const other = frame.comparison;
          if (!other) return `none yet: switch the model to compare`;
          const name = other.model === 'neural' ? 'neural field' : 'voxel grid';
          const psnr =
            other.novelMse === null
              ? ''
              : `, held-out PSNR ${formatNumber(10 * Math.log10(1 / other.novelMse), 3)} dB`;
          return `${name}: loss ${formatNumber(other.loss, 3)} after ${other.iterations} iterations in ${formatNumber(other.seconds, 3)} s${psnr}`;
        },
      },
      {
        key: 'rate',
        label: 'Iterations per second',
        format: (frame) =>
          Number.isFinite(frame.rate) && frame.rate > 0
            ? `${formatNumber(frame.rate, 3)} it/s`
            : '—',
      },
      {
        key: 'time',
        label: 'Time per iteration',
        // Over the same window as the rate: the time the iterations themselves took
        // (GPU timestamps where available).
        format: (frame) =>
          frame.iterationMs === null
            ? '—'
            : `${formatMilliseconds(frame.iterationMs)} (${frame.timing})`,
      },
      {
        key: 'dropped',
        label: 'Dropped gradient adds',
        format: (frame, backend) =>
          backend.kind === 'cpu'
            ? 'none: float64 sums, no atomics'
            : { text: String(frame.dropped), state: frame.dropped > 0 ? 'bad' : 'ok' },
      },
    ],
    cost: (frame) => frame.cost,
    costLine: (frame, how, backend) =>
      `${backend.kind === 'cpu' ? 'the float64 twin, ' : ''}${modelText(frame)}, ${frame.trainViews} training view${frame.trainViews === 1 ? '' : 's'} of ${frame.size}×${frame.size} pixels; each iteration marches ${frame.rays} rays × ${frame.steps} samples forward and backward, then Adam (η = ${frame.learningRate}, ${frame.regularizer}). ${
        Number.isFinite(frame.rate) && frame.rate > 0
          ? `${formatNumber(frame.rate, 3)} iterations/s. `
          : ''
      }Targets: the hidden volume, 192 samples per ray. ${costText(frame, how)}`,
  },
  slides: [
    {
      title: 'Inverse rendering: fit a grid to photographs',
      attributes: {
        grid: '32',
        views: '8',
        regularizer: 'none',
      },
      caption:
        'Press Start: Adam fits 131,072 grid parameters to eight images with the gradient of the ray marcher. The training loss falls tenfold within about a hundred iterations; the held-out view from above shows what eight views pin down.',
      chapter: '08-inverse-volume-rendering',
    },
    {
      title: 'Three views: low loss, wrong volume',
      attributes: {
        grid: '32',
        views: '3',
        regularizer: 'none',
      },
      caption:
        'With three cameras the fit explains its images almost perfectly, yet the held-out view stays wrong: many volumes produce the same three pictures. The loss curve and the held-out error part ways.',
      chapter: '08-inverse-volume-rendering',
    },
    {
      title: 'A neural field: hash grid + tiny MLP',
      attributes: {
        model: 'neural',
        views: '4',
        table: '12',
        rate: '0.05',
        batch: '256',
        steps: '16',
      },
      caption:
        'Four images, fitted by Instant-NGP’s multiresolution hash encoding and an MLP of 16 hidden units: 65,876 parameters, half the 32³ grid’s. 256 rays of 16 samples per iteration: within a minute on a CPU the held-out view from above is recognisable. Switch the model to the grid on the same views: the plot keeps both loss curves against time.',
      chapter: '08-inverse-volume-rendering',
    },
  ],
  load: () => import('./view.ts'),
});
