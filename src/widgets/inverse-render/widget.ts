// <sb-inverse-render>: inverse volume rendering (chapter 8). The target images of a
// hidden volume, from N training views and one held-out view, are rendered once by
// the book's ray marcher; Start fits a grid of raw density and emission to the
// training images with Adam, on the GPU (shaders/kernels/inverse-render.wesl) or,
// without WebGPU, with the float64 twin in a Web Worker. Iterations run in batches,
// one per animation frame, so the page stays live and Pause/Reset act at once. The
// widget shows targets against the current fit, the held-out view with its error
// image, the loss curve, the iteration rate and the GPU time per iteration.
//
// Not yet ported to a view: load() returns the widget's own element class, which
// keeps its shell code (see /work/briefs/porting.md); the data below is already
// the definition's (deck slides, schema).
import { defineWidget } from '../base/definition.ts';
import { INVERSE_RENDER } from './schema.ts';

export const widget = defineWidget({
  entry: INVERSE_RENDER,
  slides: [
    {
      title: 'Inverse rendering: fit a grid to photographs',
      attributes: {
        grid: '32',
        views: '8',
        regularizer: 'none',
      },
      caption:
        'Press Start: Adam fits 131,072 grid parameters to eight images with the gradient of the ray marcher. The training loss falls tenfold within about a hundred iterations; the held-out view from above shows what eight views pin down.',
      chapter: '08-inverse-volume-rendering',
    },
    {
      title: 'Three views: low loss, wrong volume',
      attributes: {
        grid: '32',
        views: '3',
        regularizer: 'none',
      },
      caption:
        'With three cameras the fit explains its images almost perfectly, yet the held-out view stays wrong: many volumes produce the same three pictures. The loss curve and the held-out error part ways.',
      chapter: '08-inverse-volume-rendering',
    },
  ],
  load: async () => ({ element: (await import('./element.ts')).InverseRenderElement }),
});
