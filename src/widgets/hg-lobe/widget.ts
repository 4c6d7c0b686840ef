// <sb-hg-lobe>: the Henyey–Greenstein phase function (chapter 3). Draws the lobe
// as a polar plot and as a 3D surface on the GPU, samples 2^n scattering cosines
// with the library's HG sampler in a compute pass, and shows the histogram against
// the closed form with a chi-square test, the sample mean cosine against g, the
// normalisation of the float64 twin, and the cost of sampling on the GPU next to
// the CPU twin (averaged over frames); a cancellable sweep over N = 2¹⁰ … 2²⁰ plots
// the histogram's L1 error against the sampling time, next to its exact expectation.
//
// Not yet ported to a view: load() returns the widget's own element class, which
// keeps its shell code (see /work/briefs/porting.md); the data below is already
// the definition's (deck slides, schema).
import { defineWidget } from '../base/definition.ts';
import { HG_LOBE } from './schema.ts';

export const widget = defineWidget({
  entry: HG_LOBE,
  slides: [
    {
      title: 'Back scattering: g = −0.3',
      attributes: {
        g: '-0.3',
        compare: 'isotropic',
        scale: 'linear',
        samples: '16',
        seed: '1',
      },
      caption:
        'A Henyey–Greenstein lobe with g < 0 sends more light back toward the source; the mean cosine of the samples is g.',
      chapter: '03-phase-functions-and-in-scattering',
    },
    {
      title: 'Isotropic scattering: g = 0',
      attributes: {
        g: '0',
        compare: 'rayleigh',
        scale: 'linear',
        samples: '16',
        seed: '1',
      },
      caption:
        'At g = 0 HG is the isotropic 1/(4π); Rayleigh scattering (outline) is close to it but prefers forward and back.',
      chapter: '03-phase-functions-and-in-scattering',
    },
    {
      title: 'Forward scattering: g = 0.6',
      attributes: {
        g: '0.6',
        compare: 'isotropic',
        scale: 'log',
        samples: '16',
        seed: '1',
      },
      caption:
        'Most media scatter forward. On a log radius the backward tail shows; turn the 3D lobe with the arrow keys. The χ² test and the error-vs-time sweep (L1 ∝ N^−½) check the sampler against the closed form.',
      chapter: '03-phase-functions-and-in-scattering',
    },
  ],
  load: async () => ({ element: (await import('./element.ts')).HgLobeElement }),
});
