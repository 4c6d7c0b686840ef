// <sb-dipole-profile>: the diffusion dipole and its profiles (chapter 11). Evaluates
// the classic dipole, the better dipole and the Christensen–Burley profile per RGB
// channel on the GPU (the library's dipole module) and plots them on log–log axes
// against a GPU Monte Carlo of the same half-space with ±1 SE error bars; tabulates the
// total R_d of each; shows the Monte Carlo's cost (GPU ms, photons, collisions) next
// to its standard error and to each model's difference from it, with a plot of those
// errors against the Monte Carlo's time; draws a disc of the material lit by a thin
// beam from the dipole. "More photons" continues the Monte Carlo progressively and can
//
// Not yet ported to a view: load() returns the widget's own element class, which
// keeps its shell code (see /work/briefs/porting.md); the data below is already
// the definition's (deck slides, schema).
import { defineWidget } from '../base/definition.ts';
import { DIPOLE_PROFILE } from './schema.ts';

export const widget = defineWidget({
  entry: DIPOLE_PROFILE,
  slides: [
    {
      title: 'Skin: the dipole against Monte Carlo',
      attributes: {
        material: 'skin1',
      },
      caption:
        'R_d(r) per channel on log–log axes: red light travels millimetres, blue barely one. The dipole follows the Monte Carlo far from the beam and misses it within a mean free path; press More photons and watch the error bars shrink.',
      chapter: '11-subsurface-scattering',
    },
    {
      title: 'Colour bleeding: marble and ketchup',
      attributes: {
        material: 'ketchup',
        exposure: '1',
      },
      caption:
        'Ketchup absorbs green and blue within a millimetre and lets red wander a centimetre: the glow is red. Press 2 for marble, whose three channels spread alike into a broad white halo.',
      chapter: '11-subsurface-scattering',
    },
  ],
  load: async () => ({ element: (await import('./element.ts')).DipoleProfileElement }),
});
