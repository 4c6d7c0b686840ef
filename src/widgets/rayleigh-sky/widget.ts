// <sb-rayleigh-sky>: why the sky is blue and sunsets red (chapter 3). Draws a
// panorama toward the sun on the GPU, one single-scattering march per pixel,
// evaluates three probe directions and the direct sun in a compute pass, and shows
// them next to a converged float64 reference (cached once per sun elevation) with
// the relative error and the GPU time of the panorama (timestamp queries, median
// over frames). A cancellable sweep over N plots the probes' relative RMS error
// against that time and fits the order of convergence.
//
// Not yet ported to a view: load() returns the widget's own element class, which
// keeps its shell code (see /work/briefs/porting.md); the data below is already
// the definition's (deck slides, schema).
import { defineWidget } from '../base/definition.ts';
import { RAYLEIGH_SKY } from './schema.ts';

export const widget = defineWidget({
  entry: RAYLEIGH_SKY,
  slides: [
    {
      title: 'Why the sky is blue',
      attributes: {
        'sun-elevation': '60',
        scattering: 'on',
        steps: '32',
        exposure: '0',
      },
      caption:
        'Skylight is sunlight scattered once by air molecules, and σs ∝ λ⁻⁴: at noon the zenith has 4.5 times more blue than red.',
      chapter: '03-phase-functions-and-in-scattering',
    },
    {
      title: 'Why sunsets are red',
      attributes: {
        'sun-elevation': '2',
        scattering: 'on',
        steps: '32',
        exposure: '1',
      },
      caption:
        'At 2° the sunlight crosses about 19 times the air of the vertical path, and Beer’s law removes the blue first: T_sun ≈ (0.42, 0.13, 0.007).',
      chapter: '03-phase-functions-and-in-scattering',
    },
    {
      title: 'The sky’s accuracy against its cost',
      attributes: {
        'sun-elevation': '20',
        scattering: 'on',
        steps: '8',
        exposure: '0',
      },
      caption:
        'Run the sweep: the error falls as N⁻², but each view sample also marches N/4 sun samples, so against GPU time it falls more slowly, with a slope between −2 and −1.',
      chapter: '03-phase-functions-and-in-scattering',
    },
  ],
  deckOrder: 1,
  load: async () => ({ element: (await import('./element.ts')).RayleighSkyElement }),
});
