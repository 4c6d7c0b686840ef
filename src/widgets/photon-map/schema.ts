// Parameters of <sb-photon-map>: a glass sphere focusing a small sun into a fog box
// (a volume caustic), rendered by photon mapping (volume radiance estimate, Jensen &
// Christensen 1998) next to path tracing at equal time, each with its error against
// a converged path-traced reference (chapter 10).
import type { WidgetEntry } from '../parameters.ts';

export const PHOTON_MAP: WidgetEntry = {
  name: 'photon-map',
  title: 'Photon mapping and volume caustics',
  description:
    'A glass ball (η = 1.5) focuses a small sun into fog. Photons are traced from the sun through the glass and the fog and stored where they collide; the image is the volume radiance estimate along camera rays. Path tracing gets the same time. Both show their error against a converged path-traced reference, and the plot sweeps photon count and samples to show bias against variance.',
  parameters: [
    {
      kind: 'number',
      name: 'photons',
      label: 'Photons emitted',
      symbol: 'N',
      unit: '',
      min: 1024,
      max: 262144,
      step: 1024,
      default: 65536,
      description:
        'Photons leaving the sun’s emission disc; each carries ΔΦ = E·A/N. About 0.4 are stored per photon (one per collision in the fog).',
    },
    {
      kind: 'number',
      name: 'radius',
      label: 'Gather radius',
      symbol: 'r',
      unit: 'm',
      min: 0.01,
      max: 0.2,
      step: 0.005,
      default: 0.04,
      description:
        'Radius of the sphere over which photons are averaged: larger blurs (bias), smaller is noisier (variance). The fog box is 1.6 m tall.',
    },
  ],
};
