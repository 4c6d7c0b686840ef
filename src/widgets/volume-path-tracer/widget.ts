// <sb-volume-path-tracer>: single versus multiple scattering in a cloud (chapter 10).
// Two images of the same scene are refined progressively by the scene engine
// (src/scene/): one with scatteringOrder 1, one with unlimited order (volumetric path
// tracing: spectral tracking, next-event estimation, Russian roulette). Each frame adds
// `spp` samples per pixel to both, timed on the GPU. A converged reference of each
// (independent seed, many more samples) is accumulated one pass per frame, cached per
// parameter set, with progress and a cancel button; once it is there, the error of
// every snapshot of the progressive images is plotted against accumulated GPU time on
//
// Not yet ported to a view: load() returns the widget's own element class, which
// keeps its shell code (see /work/briefs/porting.md); the data below is already
// the definition's (deck slides, schema).
import { defineWidget } from '../base/definition.ts';
import { VOLUME_PATH_TRACER } from './schema.ts';

export const widget = defineWidget({
  entry: VOLUME_PATH_TRACER,
  slides: [
    {
      title: 'Clouds are white: single versus multiple scattering',
      attributes: {
        scene: 'sphere',
        albedo: '0.99',
        g: '0.8',
        'optical-thickness': '10',
        spp: '4',
      },
      caption:
        'The same cloud rendered with one scattering event and with all of them. At albedo 0.99 most of the light that leaves the cloud has scattered many times: single scattering keeps only a fraction of it and the cloud turns grey.',
      chapter: '10-multiple-scattering',
    },
    {
      title: 'Path tracing converges as one over the square root of time',
      attributes: {
        scene: 'cloud',
        albedo: '0.98',
        g: '0.7',
        'optical-thickness': '16',
        spp: '8',
      },
      caption:
        'Both images refine progressively; once the converged reference is ready, their relative error is plotted against accumulated GPU time on log–log axes. Both fall with slope −½; the path tracer pays more time per sample for its longer paths.',
      chapter: '10-multiple-scattering',
    },
  ],
  load: async () => ({ element: (await import('./element.ts')).VolumePathTracerElement }),
});
