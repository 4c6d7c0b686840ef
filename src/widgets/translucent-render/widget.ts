// <sb-translucent-render>: a translucent sphere rendered three ways (chapter 11). Left, a
// Lambertian surface with the material's total diffuse reflectance R_d; middle, the dipole
// BSSRDF by Jensen & Buhler's two-pass hierarchical integration (irradiance samples on the
// sphere, an octree built in TypeScript, the gather on the GPU with the threshold ε); right,
// volumetric path tracing of the same sphere as the reference, accumulated progressively
// within a time budget per step, cancellable, with its per-pixel standard error. Each picture
// shows its GPU time and its error against the reference, with the reference's noise variance
// subtracted so that a young reference does not inflate it; an ε sweep plots the gather's error
//
// Not yet ported to a view: load() returns the widget's own element class, which
// keeps its shell code (see /work/briefs/porting.md); the data below is already
// the definition's (deck slides, schema).
import { defineWidget } from '../base/definition.ts';
import { TRANSLUCENT_RENDER } from './schema.ts';

export const widget = defineWidget({
  entry: TRANSLUCENT_RENDER,
  slides: [
    {
      title: 'A translucent sphere: Lambert, dipole BSSRDF, path tracing',
      attributes: {
        material: 'skin1',
        radius: '5',
        size: '64',
      },
      caption:
        'The same skin sphere as a Lambertian surface, with the dipole BSSRDF (Jensen–Buhler octree gather) and path traced. Light bleeds past the terminator only with the BSSRDF and the path tracer; drag ε and watch the nodes visited and the error against the reference (64² pixels, as in the chapter’s table; the errors subtract the young reference’s noise).',
      chapter: '11-subsurface-scattering',
    },
  ],
  deckOrder: 1,
  load: async () => ({ element: (await import('./element.ts')).TranslucentRenderElement }),
});
