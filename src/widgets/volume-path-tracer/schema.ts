// Parameters of <sb-volume-path-tracer>: a cloud under sun and sky rendered twice,
// progressively, by the scene engine (src/scene/): once with single scattering only
// (scatteringOrder 1) and once by volumetric path tracing (unlimited order), side by
// side, with the energy the truncation loses and the error of both images against a
// converged reference plotted against accumulated GPU time (chapter 10).
import type { WidgetEntry } from '../parameters.ts';

export const VOLUME_PATH_TRACER: WidgetEntry = {
  name: 'volume-path-tracer',
  title: 'Volumetric path tracing: single versus multiple scattering',
  description:
    'A cloud lit by a directional sun and a blue sky, rendered progressively on the GPU with single scattering only and with every order of scattering (spectral tracking, next-event estimation, Russian roulette). The readouts give the samples so far, the per-pixel standard error and the brightness ratio of the two images; the plot shows the error of each image against a converged reference as a function of accumulated GPU time.',
  parameters: [
    {
      kind: 'choice',
      name: 'scene',
      label: 'Medium',
      choices: [
        { value: 'sphere', label: 'Homogeneous sphere' },
        { value: 'cloud', label: 'Puffy cloud (density grid)' },
      ],
      default: 'sphere',
      description:
        'A homogeneous ball of radius 1 m, or a 24³ density grid of overlapping soft blobs inside the same ball.',
    },
    {
      kind: 'number',
      name: 'albedo',
      label: 'Single-scattering albedo',
      symbol: 'α',
      unit: '',
      min: 0,
      max: 1,
      step: 0.01,
      default: 0.9,
      description: 'α = σs/σt: the probability that a collision scatters rather than absorbs.',
    },
    {
      kind: 'number',
      name: 'g',
      label: 'Henyey–Greenstein g',
      symbol: 'g',
      unit: '',
      min: -0.9,
      max: 0.95,
      step: 0.05,
      default: 0.6,
      description: 'Mean cosine of the scattering angle; g > 0 scatters forward.',
    },
    {
      kind: 'number',
      name: 'optical-thickness',
      // Called density until it was named for what it is; old pages and links still say so.
      aliases: ['density'],
      label: 'Optical thickness (diameter)',
      symbol: 'τ',
      unit: '',
      min: 0.5,
      max: 30,
      step: 0.5,
      default: 8,
      description:
        'τ = σt·2R along a diameter of the ball (for the grid: at its densest value): the number of mean free paths across the medium.',
    },
    {
      kind: 'number',
      name: 'spp',
      label: 'Samples per pixel per frame',
      symbol: 'spp',
      unit: 'samples',
      min: 1,
      max: 64,
      step: 1,
      default: 4,
      description:
        'Each frame adds this many paths per pixel to both images; the images stop refining at 1024 samples per pixel.',
    },
  ],
};
