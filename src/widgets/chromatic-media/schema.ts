// Parameters of <sb-chromatic-media> (chapter 12, colour in a medium): a sphere of
// chromatic medium whose extinction differs per channel, σt = σ·(s^-½, 1, s^½) for a spread
// s = σt,b/σt,r, rendered by one channel at a time, hero wavelength and spectral tracking.
import type { WidgetEntry } from '../parameters.ts';

export const CHROMATIC_MEDIA: WidgetEntry = {
  name: 'chromatic-media',
  title: 'Colour in a medium: one channel at a time, hero wavelength, spectral tracking',
  description:
    'A sphere of medium whose extinction differs strongly between red, green and blue, lit by a directional light and rendered with multiple scattering by three estimators side by side: a walk per channel, hero-wavelength sampling with the balance heuristic, and spectral tracking. Each shows its GPU time, per-channel standard error, colour noise (the standard error of the chromaticity), error against a reference and variance × time.',
  parameters: [
    {
      kind: 'number',
      name: 'spread',
      label: 'Channel spread σt,b/σt,r',
      symbol: 'σt,b/σt,r',
      unit: '',
      min: 1,
      max: 100,
      step: 1,
      default: 16,
      description:
        'Ratio of the blue extinction to the red; green is their geometric mean. 1 is a grey medium, where the three estimators sample the same distances.',
    },
    {
      kind: 'number',
      name: 'density',
      label: 'Green extinction σt,g',
      symbol: 'σt,g',
      unit: '1/m',
      min: 0.1,
      max: 20,
      step: 0.1,
      default: 2,
      description:
        'Extinction of the green channel; red is σt,g/√spread and blue σt,g·√spread. The sphere has radius 1 m.',
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
      default: 0.9,
      description:
        'Single-scattering albedo σs/σt, the same in every channel, so that the colour comes from the extinction alone.',
    },
    {
      kind: 'number',
      name: 'g',
      label: 'Anisotropy g',
      symbol: 'g',
      unit: '',
      min: -0.9,
      max: 0.9,
      step: 0.05,
      default: 0,
      description: 'Henyey–Greenstein anisotropy of the phase function.',
    },
    {
      kind: 'number',
      name: 'spp',
      label: 'Samples per pixel per pass',
      symbol: 'spp',
      unit: '',
      min: 1,
      max: 64,
      step: 1,
      default: 4,
      description:
        'Samples each estimator adds to every pixel per pass; passes continue up to the target.',
    },
    {
      kind: 'number',
      name: 'target',
      label: 'Target samples per pixel',
      symbol: 'N',
      unit: '',
      min: 2,
      max: 1024,
      step: 2,
      default: 64,
      description:
        'The picture accumulates passes until every estimator has this many samples per pixel.',
    },
    {
      kind: 'number',
      name: 'exposure',
      label: 'Exposure',
      symbol: 'EV',
      unit: 'EV',
      min: -4,
      max: 6,
      step: 0.5,
      default: 2,
      description: 'Brightness of the pictures in stops.',
    },
  ],
};
