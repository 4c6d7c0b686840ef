// Parameters of <sb-beer-law>: a beam crossing a slab of absorbing and
// scattering medium (chapter 2, Beer's law and the multiplicative property).
import type { WidgetEntry } from '../parameters.ts';

export const BEER_LAW: WidgetEntry = {
  name: 'beer-law',
  title: "Beer's law: transmittance through a slab",
  description:
    'A collimated beam crosses a slab of thickness d. The widget plots T(s) = exp(−τ(0,s)), draws the attenuated beam on the GPU, and shows T at the exit and the multiplicative property at a split point.',
  parameters: [
    {
      kind: 'number',
      name: 'sigma-a',
      label: 'Absorption σa',
      symbol: 'σa',
      unit: '1/m',
      min: 0,
      max: 10,
      step: 0.01,
      default: 0.2,
      description: 'Absorption coefficient (mean over the slab for heterogeneous profiles).',
    },
    {
      kind: 'number',
      name: 'sigma-s',
      label: 'Scattering σs',
      symbol: 'σs',
      unit: '1/m',
      min: 0,
      max: 10,
      step: 0.01,
      default: 0.8,
      description: 'Scattering coefficient: light scattered out of the beam (mean over the slab).',
    },
    {
      kind: 'number',
      name: 'thickness',
      label: 'Thickness d',
      symbol: 'd',
      unit: 'm',
      min: 0,
      max: 10,
      step: 0.01,
      default: 2,
      description: 'Length of the beam inside the medium.',
    },
    {
      kind: 'choice',
      name: 'profile',
      label: 'Density profile',
      choices: [
        { value: 'homogeneous', label: 'Homogeneous' },
        { value: 'smooth', label: 'Smooth: σ̄(1 + 0.8 sin 3s)' },
        { value: 'layered', label: 'Layered (piecewise constant)' },
      ],
      default: 'homogeneous',
      description:
        'How extinction varies along the beam; all three have the same mean coefficients.',
    },
    {
      kind: 'number',
      name: 'split',
      label: 'Split point s₀',
      symbol: 's₀',
      unit: 'm',
      min: 0,
      max: 10,
      step: 0.01,
      default: 1,
      description:
        'A point inside the slab where the widget checks T(0→d) = T(0→s₀)·T(s₀→d); clamped to the slab.',
    },
  ],
};
