// <sb-raymarch-steps>: ray marching an emissive, absorbing volume (chapter 5).
// Marches one ray per pixel with N steps on the GPU, shows the image next to its
// error against a converged reference (false colour, labelled scale), the RMSE,
// the GPU time and the clamped linear factors; a cancellable sweep over
// N = 1, 2, 4, …, 256 plots RMSE against GPU time and fits the order of convergence.
//
// Not yet ported to a view: load() returns the widget's own element class, which
// keeps its shell code (see /work/briefs/porting.md); the data below is already
// the definition's (deck slides, schema).
import { defineWidget } from '../base/definition.ts';
import { RAYMARCH_STEPS } from './schema.ts';

export const widget = defineWidget({
  entry: RAYMARCH_STEPS,
  slides: [
    {
      title: 'Ray marching: left versus midpoint samples',
      attributes: {
        steps: '8',
        placement: 'midpoint',
        update: 'exact',
        density: '1.5',
        seed: '0',
      },
      caption:
        'The same 8 steps per ray, sampled at the middle of each step instead of its start: the error falls from O(h) to O(h²). Run the sweep to measure the order.',
      chapter: '05-emission-absorption-and-ray-marching',
    },
    {
      title: 'The linearised update fails',
      attributes: {
        steps: '4',
        placement: 'left',
        update: 'linear',
        density: '1.5',
        seed: '0',
      },
      caption:
        'T ← T·(1 − σt·h) turns negative where σt·h > 1; the book clamps it to 0 and counts the clamped steps. The exact factor e^(−σt·h) never fails.',
      chapter: '05-emission-absorption-and-ray-marching',
    },
  ],
  load: async () => ({ element: (await import('./element.ts')).RaymarchStepsElement }),
});
