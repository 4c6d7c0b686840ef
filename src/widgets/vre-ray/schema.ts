// Parameters of <sb-vre-ray>: one ray through an emitting, scattering medium in
// front of a background (chapter 4, the volume rendering equation in integral form).
import type { WidgetEntry } from '../parameters.ts';

export const VRE_RAY: WidgetEntry = {
  name: 'vre-ray',
  title: 'The volume rendering equation along one ray',
  description:
    'A ray of length d crosses a medium σt(s) = σ0(1 + 0.8 sin 3s) with albedo α, emission Le and a constant in-scattered radiance L_in, in front of a background L_bg. The widget plots what reaches the eye from [0, s], draws the medium and the weighted source T(0,s)·(σa Le + σs L_in) on the GPU, and compares the marched radiance with the exact integral form.',
  parameters: [
    {
      kind: 'number',
      name: 'sigma',
      label: 'Mean extinction σ0',
      symbol: 'σ0',
      unit: '1/m',
      min: 0,
      max: 5,
      step: 0.01,
      default: 1,
      description:
        'Mean extinction coefficient of the sinusoidal profile σt(s) = σ0(1 + 0.8 sin 3s).',
    },
    {
      kind: 'number',
      name: 'albedo',
      label: 'Albedo α',
      symbol: 'α',
      unit: '',
      min: 0,
      max: 1,
      step: 0.01,
      default: 0.5,
      description: 'Single-scattering albedo: σs = α σt and σa = (1 − α) σt everywhere on the ray.',
    },
    {
      kind: 'number',
      name: 'emission',
      label: 'Emission Le',
      symbol: 'Le',
      unit: 'radiance units',
      min: 0,
      max: 2,
      step: 0.01,
      default: 0.5,
      description: 'Emitted radiance of the medium (constant), in radiance units (W·m⁻²·sr⁻¹).',
    },
    {
      kind: 'number',
      name: 'inscatter',
      label: 'In-scattered radiance L_in',
      symbol: 'L_in',
      unit: 'radiance units',
      min: 0,
      max: 2,
      step: 0.01,
      default: 0.3,
      description:
        'The in-scattered radiance ∫p L dω taken as a constant (an assumption of this widget; chapters 9 and 10 compute it).',
    },
    {
      kind: 'number',
      name: 'background',
      label: 'Background L_bg',
      symbol: 'L_bg',
      unit: 'radiance units',
      min: 0,
      max: 2,
      step: 0.01,
      default: 1,
      description: 'Radiance of the surface behind the medium, at the far end of the ray.',
    },
    {
      kind: 'number',
      name: 'length',
      label: 'Ray length d',
      symbol: 'd',
      unit: 'm',
      min: 0.1,
      max: 5,
      step: 0.01,
      default: 2,
      description:
        'Distance from the eye (s = 0) to the background (s = d), all inside the medium.',
    },
  ],
};
