// Parameters of <sb-raymarch-steps>: an image of a heterogeneous emissive,
// absorbing volume by orthographic ray marching (chapter 5). The step count, the
// sample placement and the transmittance update trade error against GPU time;
// a sweep over N measures the order of convergence.
import type { WidgetEntry } from '../parameters.ts';

export const RAYMARCH_STEPS: WidgetEntry = {
  name: 'raymarch-steps',
  title: 'Ray marching: step count, sample placement and error',
  description:
    'Each pixel is one ray through an emissive, absorbing medium whose density and emission vary across the image. The image is ray marched with N steps, compared with a converged reference (error image and RMSE) next to the GPU time, and a sweep over N = 1 … 256 measures the order of convergence.',
  parameters: [
    {
      kind: 'number',
      name: 'steps',
      label: 'Steps per ray N',
      symbol: 'N',
      unit: 'steps',
      min: 1,
      max: 256,
      step: 1,
      default: 16,
      description: 'Equal steps h = d/N along each ray of length d = 2 m.',
    },
    {
      kind: 'choice',
      name: 'placement',
      label: 'Sample placement',
      choices: [
        { value: 'left', label: 'Left: t = i·h' },
        { value: 'midpoint', label: 'Midpoint: t = (i + ½)·h' },
        { value: 'jittered-ray', label: 'Jittered per ray: t = (i + ξ)·h' },
        { value: 'jittered-strata', label: 'Jittered per step: t = (i + ξᵢ)·h' },
      ],
      default: 'left',
      description: 'Where each step samples σt and Le.',
    },
    {
      kind: 'choice',
      name: 'update',
      label: 'Transmittance update',
      choices: [
        { value: 'exact', label: 'Exact: T ← T·e^(−σt·h)' },
        { value: 'linear', label: 'Linear: T ← T·(1 − σt·h), clamped' },
      ],
      default: 'exact',
      description:
        'The linear (forward-Euler) factor turns negative for σt·h > 1; it is clamped to 0 and counted.',
    },
    {
      kind: 'number',
      name: 'density',
      label: 'Density scale',
      symbol: 'σ̄',
      unit: '1/m',
      min: 0.2,
      max: 5,
      step: 0.1,
      default: 1.5,
      description: 'Scales σ0 everywhere; the densest ray has σ0 = 2σ̄ and σt up to 3σ̄.',
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
      description: 'Frame index of the random streams of the jittered placements.',
    },
  ],
};
