// The presets of <sb-transfer-function>: transfer functions (control points and a
// colour map), not views. Free of the volume and camera code: widget.ts builds its
// presets from it, and every page imports every widget.ts.
import type { ParameterValues } from '../parameters.ts';
import { DEFAULT_POINTS } from './schema.ts';

/** Presets in Hounsfield units: the control points (value, opacity) and a colour map. */
export interface TransferPreset {
  label: string;
  points: readonly (readonly [number, number])[];
  colormap: string;
}

export const TRANSFER_PRESETS: readonly TransferPreset[] = [
  {
    label: 'soft tissue + bone',
    points: DEFAULT_POINTS,
    colormap: 'tissue',
  },
  {
    label: 'skin (air/tissue surface at −500 HU)',
    points: [
      [-1024, 0],
      [-700, 0],
      [-450, 0.4],
      [100, 0.5],
      [1000, 0.6],
      [3071, 0.6],
    ],
    colormap: 'tissue',
  },
  {
    label: 'bone (> 300 HU)',
    points: [
      [-1024, 0],
      [0, 0],
      [250, 0],
      [700, 0.7],
      [1500, 0.7],
      [3071, 0.7],
    ],
    colormap: 'bone',
  },
  {
    label: 'lesions (+30 HU window)',
    points: [
      [-1024, 0],
      [22, 0],
      [27, 0.25],
      [33, 0.25],
      [37, 0],
      [3071, 0],
    ],
    colormap: 'viridis',
  },
];

/** The parameter values of a preset (control points and colour map). */
export function presetValues(preset: TransferPreset): ParameterValues {
  const values: ParameterValues = { colormap: preset.colormap };
  preset.points.forEach(([hu, opacity], index) => {
    values[`hu-${index + 1}`] = hu;
    values[`opacity-${index + 1}`] = opacity;
  });
  return values;
}
