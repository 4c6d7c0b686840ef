// The slider values of <sb-dipole-profile>'s material presets (Jensen et al. 2001,
// src/subsurface/materials.ts) and the parameters a material sets. Free of GPU code:
// widget.ts builds the presets from it, and Node imports every widget.ts.
import { findMaterial } from '../../subsurface/materials.ts';

const COEFFICIENT_KEYS = [
  'sigma-s-r',
  'sigma-s-g',
  'sigma-s-b',
  'sigma-a-r',
  'sigma-a-g',
  'sigma-a-b',
];
/** The parameters a material sets (editing one by hand makes the material "manual"). */
export const MATERIAL_PARAMETERS = [...COEFFICIENT_KEYS, 'eta'] as const;

/** The slider values of a preset material. */
export function materialValues(name: string): Record<string, number> | null {
  const m = findMaterial(name);
  if (!m) return null;
  return {
    'sigma-s-r': m.sigmaSPrime[0],
    'sigma-s-g': m.sigmaSPrime[1],
    'sigma-s-b': m.sigmaSPrime[2],
    'sigma-a-r': m.sigmaA[0],
    'sigma-a-g': m.sigmaA[1],
    'sigma-a-b': m.sigmaA[2],
    eta: m.eta,
  };
}
