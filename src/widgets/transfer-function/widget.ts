// <sb-transfer-function>: direct volume rendering of a CT head phantom (chapter 7).
// The GPU ray casts the volume with emission–absorption compositing through a
// transfer function edited over the data's histogram; the camera orbits by drag or
// arrow keys. Next to the picture: the GPU time per frame, the error against a
// fine-step reference (computed once per transfer function and view, band by band,
// with progress, cancellable), the steps early ray termination takes and saves,
// its bias bound, and a cancellable sweep of RMSE against time over the step size.
//
// Not yet ported to a view: load() returns the widget's own element class, which
// keeps its shell code (see /work/briefs/porting.md); the data below is already
// the definition's (deck slides, schema).
import { defineWidget } from '../base/definition.ts';
import { TRANSFER_FUNCTION } from './schema.ts';

export const widget = defineWidget({
  entry: TRANSFER_FUNCTION,
  slides: [
    {
      title: 'Transfer functions: from Hounsfield units to light',
      attributes: {
        step: '1',
        termination: 'on',
        colormap: 'tissue',
      },
      caption:
        'A CT head phantom in HU, ray cast with emission–absorption. Drag the opacity points over the histogram or press 1–4 for presets; drag the image to orbit. The error image shows the wood-grain rings of one-voxel steps.',
      chapter: '07-volume-visualization',
    },
    {
      title: 'Early ray termination: the skin surface',
      attributes: {
        colormap: 'tissue',
        panel: 'steps',
        'hu-2': '-700',
        'hu-3': '-450',
        'opacity-3': '0.4',
        'hu-4': '100',
        'opacity-4': '0.5',
        'hu-5': '1000',
        'opacity-5': '0.6',
        'hu-6': '3071',
        'opacity-6': '0.6',
      },
      caption:
        'Rays stop once T < ε, a few voxels behind the skin: the steps image shows it. The bias stays below ε·L_max; switch termination off and compare the steps and the GPU time.',
      chapter: '07-volume-visualization',
    },
  ],
  load: async () => ({ element: (await import('./element.ts')).TransferFunctionElement }),
});
