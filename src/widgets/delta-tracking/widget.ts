// <sb-delta-tracking>: unbiased and biased transmittance estimators (chapter 6).
// Averages spp estimates per pixel on the GPU, shows the mean transmittance
// next to the per-pixel variance (false colour, labelled scale), the RMSE and
// mean bias against the exact T, the lookups per estimate and the GPU time; a
// cancellable sweep over spp = 1, 2, 4, …, 256 plots RMSE against GPU time.
// The comparison view (view=compare) renders all five estimators side by side,
// once at the same spp and once at the same GPU time (the spp of each from its
// measured cost per sample, compare.ts), and sweeps all five into one log–log
//
// Not yet ported to a view: load() returns the widget's own element class, which
// keeps its shell code (see /work/briefs/porting.md); the data below is already
// the definition's (deck slides, schema).
import { defineWidget } from '../base/definition.ts';
import { DELTA_TRACKING } from './schema.ts';

export const widget = defineWidget({
  entry: DELTA_TRACKING,
  slides: [
    {
      title: 'Delta tracking: unbiased, binary transmittance',
      attributes: {
        estimator: 'delta',
        spp: '4',
        majorant: 'tight',
        seed: '0',
      },
      caption:
        'Each sample is 0 or 1 and its mean is exactly T, with variance T(1 − T). Switch to exp(−τ̂) and the mean bias stays, however many samples: run the sweep for both.',
      chapter: '06-unbiased-transmittance',
    },
    {
      title: 'Five estimators at equal samples and equal time',
      attributes: {
        view: 'compare',
        estimator: 'delta',
        spp: '8',
        majorant: 'tight',
        seed: '0',
      },
      caption:
        'Top row: the same spp for all five; bottom row: the same GPU time as delta tracking at that spp. exp(−τ̂) stays biased however many samples it gets; unbiased ray marching wins by orders of magnitude. Sweep all five: four curves fall with slope −½, one levels off.',
      chapter: '06-unbiased-transmittance',
    },
    {
      title: 'A majorant that is too low',
      attributes: {
        estimator: 'delta',
        spp: '16',
        majorant: 'low',
        seed: '0',
      },
      caption:
        'With σ̄ below σt, delta tracking accepts too few collisions and the image is too bright: E[X] = exp(−∫min(σt, σ̄)). Ratio tracking with the same majorant stays unbiased, at a higher variance.',
      chapter: '06-unbiased-transmittance',
    },
  ],
  load: async () => ({ element: (await import('./element.ts')).DeltaTrackingElement }),
});
