// Parameters of <sb-rayleigh-sky>: single Rayleigh scattering in a spherical,
// exponential atmosphere, seen from sea level (chapter 3, why the sky is blue and
// sunsets red). The GPU marches every view ray of a panorama; probe directions are
// compared with a converged float64 reference.
import type { WidgetEntry } from '../parameters.ts';

export const RAYLEIGH_SKY: WidgetEntry = {
  name: 'rayleigh-sky',
  title: 'Rayleigh scattering: a blue sky and a red sunset',
  description:
    'A panorama of the sky toward the sun from sea level, computed by single Rayleigh scattering in an exponential atmosphere (scale height 8 km) with β ∝ λ⁻⁴ at 680, 550 and 440 nm. Probe directions are compared with a converged float64 integral, next to the GPU time.',
  parameters: [
    {
      kind: 'number',
      name: 'sun-elevation',
      label: 'Sun elevation',
      symbol: 'θ_s',
      unit: '°',
      min: -5,
      max: 90,
      step: 0.5,
      default: 30,
      description:
        'Angle of the sun above the horizon; below 0° the sun has set and only the high air is lit.',
    },
    {
      kind: 'choice',
      name: 'scattering',
      label: 'Rayleigh scattering',
      choices: [
        { value: 'on', label: 'On: β ∝ λ⁻⁴' },
        { value: 'off', label: 'Off: β = 0 (no air)' },
      ],
      default: 'on',
      description: 'Off removes the air: the sky turns black and the sun is white.',
    },
    {
      kind: 'number',
      name: 'steps',
      label: 'View-ray samples N',
      symbol: 'N',
      unit: 'samples',
      min: 4,
      max: 128,
      step: 1,
      default: 32,
      description:
        'Midpoint samples along each view ray; each takes M = max(4, ⌈N/4⌉) midpoint samples along its sun ray.',
    },
    {
      kind: 'number',
      name: 'exposure',
      label: 'Exposure',
      symbol: 'EV',
      unit: 'EV',
      min: -4,
      max: 4,
      step: 0.5,
      default: 0,
      description: 'Scales the sky radiance by 2^EV before display; the sun disc is not exposed.',
    },
  ],
};
