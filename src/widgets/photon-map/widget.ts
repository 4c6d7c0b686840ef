// <sb-photon-map>: photon mapping versus path tracing on a volume caustic (chapter 10).
// A glass ball focuses a small sun into a fog box. Each render traces N photons,
// sorts them into a uniform grid (cell = gather radius) and renders the volume
// radiance estimate along camera rays; path tracing then gets the same time
// (passes of PT_PASS_SPP paths per pixel until its accumulated time reaches the photon
// map's). Both images show their RMSE against a converged path-traced reference
// (public/photon-map/reference.bin, scripts/photon-map-reference.ts). The sweep plots
// error against time for three series: photon mapping over N = 4096·n at the current
//
// Not yet ported to a view: load() returns the widget's own element class, which
// keeps its shell code (see /work/briefs/porting.md); the data below is already
// the definition's (deck slides, schema).
import { defineWidget } from '../base/definition.ts';
import { PHOTON_MAP } from './schema.ts';

export const widget = defineWidget({
  entry: PHOTON_MAP,
  slides: [
    {
      title: 'Volume caustics: photon mapping against path tracing',
      attributes: {
        photons: '65536',
        radius: '0.04',
      },
      caption:
        'A glass ball focuses a small sun into fog. Photon mapping resolves the focused cone of light in the time path tracing needs to show noise; shrink the radius and its blur (bias) turns into noise (variance). The sweep plots both errors against time.',
      chapter: '10-multiple-scattering',
    },
  ],
  deckOrder: 1,
  load: async () => ({ element: (await import('./element.ts')).PhotonMapElement }),
});
