// Parameters of <sb-mie-lobe>: one homogeneous sphere in light of one wavelength
// (chapter 3, Mie scattering). The radius is set by its decimal logarithm, so that a
// slider spans 0.01–100 µm evenly.
import type { WidgetEntry } from '../parameters.ts';

export const MIE_LOBE: WidgetEntry = {
  name: 'mie-lobe',
  title: 'Mie scattering: the lobe of a sphere',
  description:
    'The phase function of a sphere from the Lorenz–Mie series (computed in float64 in a worker, tabulated and evaluated on the GPU from the WGSL library), against Henyey–Greenstein with the same g and against Rayleigh, with the efficiencies and the colour of the scattered light.',
  parameters: [
    {
      kind: 'number',
      name: 'log-radius',
      label: 'Radius r, decimal log',
      symbol: 'log₁₀ r',
      unit: 'log₁₀ µm',
      min: -2,
      max: 2,
      step: 0.01,
      default: 0,
      description:
        'Decimal logarithm of the sphere radius in micrometres: −2 is 10 nm (a molecule-sized scatterer), 0 is 1 µm (a fog droplet), 2 is 100 µm (a drizzle drop).',
    },
    {
      kind: 'number',
      name: 'wavelength',
      label: 'Wavelength λ',
      symbol: 'λ',
      unit: 'nm',
      min: 380,
      max: 780,
      step: 1,
      default: 550,
      description: 'Wavelength of the light in the surrounding medium.',
    },
    {
      kind: 'number',
      name: 'n',
      label: 'Refractive index n (relative)',
      symbol: 'n',
      unit: '',
      min: 1.01,
      max: 3,
      step: 0.001,
      default: 1.33,
      description: 'Real part of the sphere’s refractive index relative to the surrounding medium.',
    },
    {
      kind: 'number',
      name: 'kappa',
      label: 'Absorption index κ',
      symbol: 'κ',
      unit: '',
      min: 0,
      max: 10,
      step: 0.001,
      default: 0,
      description: 'Imaginary part of the relative index m = n + iκ (0: no absorption).',
    },
  ],
};
