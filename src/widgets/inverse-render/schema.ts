// Parameters of <sb-inverse-render>: inverse volume rendering (chapter 8). A hidden
// volume is photographed from N views on an orbit by the book's own ray marcher; a
// grid of extinction and emission is fitted to those images by Adam with the
// gradient of a differentiable ray marcher (forward and backward passes in WGSL),
// and a held-out view shows what the fit gets right and wrong.
import type { WidgetEntry } from '../parameters.ts';

export const INVERSE_RENDER: WidgetEntry = {
  name: 'inverse-render',
  title: 'Inverse volume rendering: fitting a grid or a neural field to images',
  description:
    'Images of a hidden volume from several views are the data. A grid of raw density and emission (σt = 10·softplus(ρ), colour = sigmoid(e), trilinear) is fitted to them by Adam, with the gradient of the emission–absorption ray marcher computed on the GPU; or a neural field (a multiresolution hash encoding and a small MLP, as in Instant-NGP) is fitted to the same images. The widget shows the target and current views, a held-out view with its error, the loss curve, iterations per second and GPU time per iteration.',
  parameters: [
    {
      kind: 'choice',
      name: 'model',
      label: 'Model',
      choices: [
        { value: 'grid', label: 'Voxel grid' },
        { value: 'neural', label: 'Neural field: hash grid + MLP' },
      ],
      default: 'grid',
      description:
        'What is fitted: a grid of raw density and emission, or Instant-NGP’s multiresolution hash encoding (8 levels, 2 features each) with an MLP of 16 hidden units. The loss plot keeps the other model’s last run on the same views for comparison. Changing it starts afresh.',
    },
    {
      kind: 'choice',
      name: 'table',
      label: 'Hash table size (neural field)',
      choices: [
        { value: '10', label: 'T = 2¹⁰ entries per level' },
        { value: '12', label: 'T = 2¹² entries per level' },
        { value: '14', label: 'T = 2¹⁴ entries per level' },
      ],
      default: '12',
      description:
        'Entries per level of the neural field’s hash tables (2 features each; the CPU fallback uses at most 2¹²). Coarse levels with fewer vertices than T are stored densely, finer ones hashed. Changing it starts afresh.',
    },
    {
      kind: 'choice',
      name: 'grid',
      label: 'Grid resolution',
      choices: [
        { value: '16', label: '16³ voxels' },
        { value: '32', label: '32³ voxels' },
      ],
      default: '32',
      description:
        'Voxels per axis of the fitted grid over the 2 m box (the CPU fallback uses 16³). Changing it starts afresh.',
    },
    {
      kind: 'number',
      name: 'views',
      label: 'Training views',
      symbol: 'N',
      unit: '',
      min: 1,
      max: 16,
      step: 1,
      default: 8,
      description:
        'Cameras evenly spaced around the volume, alternately 17° above and below it. Changing it starts afresh.',
    },
    {
      kind: 'number',
      name: 'steps',
      label: 'Samples per ray',
      symbol: 'n',
      unit: '',
      min: 8,
      max: 128,
      step: 8,
      default: 32,
      description:
        'Midpoint samples of the ray marcher through the box, in the fit and in its gradient. Changing it starts afresh.',
    },
    {
      kind: 'number',
      name: 'rate',
      label: 'Learning rate',
      symbol: 'η',
      unit: '',
      min: 0.005,
      max: 0.3,
      step: 0.005,
      default: 0.05,
      description: 'Adam’s step size: each iteration moves a raw parameter by about η at most.',
    },
    {
      kind: 'number',
      name: 'batch',
      label: 'Rays per iteration',
      symbol: 'B',
      unit: '',
      min: 128,
      max: 16384,
      step: 128,
      default: 1024,
      description:
        'A stratified random subset of the training pixels per iteration (all of them when B is at least their number).',
    },
    {
      kind: 'choice',
      name: 'regularizer',
      label: 'Regularizer',
      choices: [
        { value: 'none', label: 'None' },
        { value: 'tv', label: 'Total variation of ρ' },
        { value: 'sparsity', label: 'Sparsity: ln(1 + 2σt²)' },
      ],
      default: 'none',
      description:
        'A prior added to the loss: smoothness of the raw density, or a Cauchy penalty that empties thin haze.',
    },
    {
      kind: 'number',
      name: 'weight',
      label: 'Regularizer weight',
      symbol: 'λ',
      unit: '',
      min: 0,
      max: 0.05,
      step: 0.0005,
      default: 0.001,
      description:
        'λ: the regularizer adds λ times its mean over the voxels to the loss (which is ≈ 10⁻² at the start).',
    },
    {
      kind: 'number',
      name: 'iterations',
      label: 'Iteration budget',
      symbol: 'K',
      unit: '',
      min: 50,
      max: 4000,
      step: 50,
      default: 1000,
      description: 'The run stops after this many iterations.',
    },
    {
      kind: 'number',
      name: 'novel',
      label: 'Held-out view azimuth',
      symbol: 'φ',
      unit: '°',
      min: 0,
      max: 360,
      step: 5,
      default: 60,
      description:
        'Where the held-out camera stands, 43° above the volume; no training camera looks from that high.',
    },
    {
      kind: 'number',
      name: 'seed',
      label: 'Seed',
      symbol: 'seed',
      unit: '',
      min: 0,
      max: 1000000,
      step: 1,
      default: 0,
      description:
        'Seed of the initial noise on the grid and of the random batches. Changing it starts afresh.',
    },
  ],
};
