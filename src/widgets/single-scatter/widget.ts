// <sb-single-scatter>: single scattering through fog or smoke (chapter 9), rendered by
// the scene engine (src/scene/) from a scene the widget builds (model.ts). The image
// accumulates progressively, a few samples per pixel per animation frame, with its
// per-pixel standard error; a reference of the same scene with eight times the samples
// and another seed (cached per scene) gives the error, plotted against the accumulated
// GPU time on log–log axes next to the slope −½ of Monte Carlo. The plan of the scene
// (src/scene/plan.ts) is listed effect by effect, and the specialized kernel's time per
// sample is measured against the general kernel's (DESIGN.md contract 3).
//
// Not yet ported to a view: load() returns the widget's own element class, which
// keeps its shell code (see /work/briefs/porting.md); the data below is already
// the definition's (deck slides, schema).
import { defineWidget } from '../base/definition.ts';
import { SINGLE_SCATTER } from './schema.ts';

export const widget = defineWidget({
  entry: SINGLE_SCATTER,
  slides: [
    {
      title: 'Single scattering: a shaft of shadow in the fog',
      attributes: {
        light: 'spot',
        medium: 'fog',
        occluder: 'sphere',
        spp: '256',
      },
      caption:
        'Every visible point of the fog sends a shadow ray to the spot light; where the sphere blocks them, a dark cone cuts through the beam. The table is the plan: what the kernel compiled, how, and why; the readouts time it against the general kernel.',
      chapter: '09-single-scattering',
    },
    {
      title: 'Switch scattering off: the plan shrinks',
      attributes: {
        scattering: 'off',
        emission: 'on',
        albedo: '0.5',
        floor: 'off',
        occluder: 'none',
      },
      caption:
        'With σs = 0 and no surfaces nothing can scatter light towards the eye: the planner skips in-scattering, phase functions, shadow rays and lights, and the kernel is an emission–absorption integral in closed form.',
      chapter: '09-single-scattering',
    },
  ],
  load: async () => ({ element: (await import('./element.ts')).SingleScatterElement }),
});
