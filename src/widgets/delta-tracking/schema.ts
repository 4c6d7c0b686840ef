// Parameters of <sb-delta-tracking>: an image of the transmittance through a
// heterogeneous slab (chapter 6), estimated per pixel with spp independent
// estimates of a chosen estimator, compared with the exact T (RMSE, mean bias,
// variance image) next to its cost; a sweep over spp draws RMSE against GPU time.
// The comparison view shows all five estimators side by side at equal spp and at
// equal GPU time, and its sweep draws all five RMSE-against-time curves at once.
import type { WidgetEntry } from '../parameters.ts';

export const DELTA_TRACKING: WidgetEntry = {
  name: 'delta-tracking',
  title: 'Transmittance estimators: bias, variance and cost',
  description:
    'Each pixel is one ray through a heterogeneous slab whose density varies across the image. Its transmittance is estimated with spp samples of the chosen estimator and compared with the exact value: the estimate, the per-pixel variance, the RMSE and mean bias, the density lookups per estimate and the GPU time; a sweep over spp = 1 … 256 plots RMSE against time. The comparison view shows all five estimators at equal spp and at equal GPU time, and sweeps all five into one RMSE-against-time plot.',
  parameters: [
    {
      kind: 'choice',
      name: 'view',
      label: 'View',
      choices: [
        { value: 'single', label: 'One estimator: estimate and variance' },
        { value: 'compare', label: 'All five: equal samples and equal time' },
      ],
      default: 'single',
      description:
        'One estimator in detail, or all five side by side at the same spp and at the same GPU time.',
    },
    {
      kind: 'choice',
      name: 'grid',
      label: 'Comparison shows',
      choices: [
        { value: 'estimate', label: 'Estimated T' },
        { value: 'variance', label: 'Variance of one estimate' },
      ],
      default: 'estimate',
      description:
        'What the ten images of the comparison show: the mean estimate, or the per-pixel variance of a single estimate.',
    },
    {
      kind: 'choice',
      name: 'estimator',
      label: 'Estimator',
      choices: [
        { value: 'biased', label: 'Biased: exp(−τ̂), one jittered step' },
        { value: 'delta', label: 'Delta tracking' },
        { value: 'ratio', label: 'Ratio tracking' },
        { value: 'residual', label: 'Residual ratio tracking' },
        { value: 'urm', label: 'Unbiased ray marching' },
      ],
      default: 'delta',
      description:
        'How each sample estimates T = e^(−τ) along the ray. In the comparison, the estimator whose GPU time at spp sets the equal-time budget.',
    },
    {
      kind: 'number',
      name: 'spp',
      label: 'Samples per pixel',
      symbol: 'spp',
      unit: '',
      min: 1,
      max: 256,
      step: 1,
      default: 4,
      description: 'Independent estimates averaged per pixel.',
    },
    {
      kind: 'choice',
      name: 'majorant',
      label: 'Majorant',
      choices: [
        { value: 'tight', label: 'Tight: σ̄ = max σt' },
        { value: 'loose', label: 'Loose: σ̄ = 3·max σt' },
        { value: 'low', label: 'Too low: σ̄ = 0.5·max σt' },
      ],
      default: 'tight',
      description:
        'The rate of tentative collisions; residual ratio tracking scales its residual majorant the same way.',
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
      description: 'Frame index of the per-pixel random streams.',
    },
  ],
};
