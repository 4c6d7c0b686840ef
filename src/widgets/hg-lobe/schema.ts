// Parameters of <sb-hg-lobe>: the Henyey–Greenstein phase function as a polar
// lobe, sampled on the GPU and checked against its closed form (chapter 3).
import type { WidgetEntry } from '../parameters.ts';

export const HG_LOBE: WidgetEntry = {
  name: 'hg-lobe',
  title: 'Henyey–Greenstein phase function: lobe and sampling',
  description:
    'The HG phase function p(θ) as a polar lobe in the plane of the incoming beam, next to an isotropic or Rayleigh lobe. The GPU draws 2^n cosines with the library’s inverse-CDF sampler; the histogram is compared with the closed form by a chi-square test, and its mean cosine with g.',
  parameters: [
    {
      kind: 'number',
      name: 'g',
      label: 'Asymmetry g',
      symbol: 'g',
      unit: '',
      min: -0.99,
      max: 0.99,
      step: 0.01,
      default: 0.6,
      description:
        'Mean cosine of the scattering angle: g > 0 scatters forward, g < 0 backward, g = 0 is isotropic.',
    },
    {
      kind: 'choice',
      name: 'compare',
      label: 'Compare with',
      choices: [
        { value: 'none', label: 'Nothing' },
        { value: 'isotropic', label: 'Isotropic, p = 1/(4π)' },
        { value: 'rayleigh', label: 'Rayleigh, p = 3(1 + cos²θ)/(16π)' },
      ],
      default: 'isotropic',
      description: 'A second phase function drawn as an outline and plotted dashed.',
    },
    {
      kind: 'choice',
      name: 'scale',
      label: 'Radius and plot scale',
      choices: [
        { value: 'linear', label: 'Linear: radius ∝ p' },
        { value: 'log', label: 'Logarithmic: radius ∝ log₁₀ p' },
      ],
      default: 'linear',
      description:
        'Linear shows the true shape; logarithmic shows the backward tail of strongly forward lobes.',
    },
    {
      kind: 'number',
      name: 'samples',
      label: 'Samples 2ⁿ, n',
      symbol: 'n',
      unit: 'log₂ count',
      min: 10,
      max: 20,
      step: 1,
      default: 16,
      description: 'The GPU draws N = 2ⁿ scattering cosines for the histogram and the mean cosine.',
    },
    {
      kind: 'number',
      name: 'seed',
      label: 'Random seed',
      symbol: 'seed',
      unit: '',
      min: 0,
      max: 1000000,
      step: 1,
      default: 1,
      description:
        'Frame index of the PCG streams (rngSeed(i, seed)); the CPU replays the same numbers.',
    },
  ],
};
