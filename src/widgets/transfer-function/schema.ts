// Parameters of <sb-transfer-function>: direct volume rendering of a CT head
// phantom (chapter 7). The transfer function is six control points of a
// piecewise-linear opacity in Hounsfield units plus a colour map; the step size
// and early ray termination trade error (against a fine-step reference) for
// GPU time; the camera orbits the volume.
import type { NumberParameter, Parameter, WidgetEntry } from '../parameters.ts';

/** Control points of the opacity curve (fixed, so that each is a parameter in the link). */
export const CONTROL_POINTS = 6;

/**
 * The defaults: transparent air and ventricles (0 HU), a faint brain (+20 HU) and
 * lesions (+30 HU, the peak), and opacity rising again towards the skull (+1000 HU).
 * The ramps are 30–80 HU wide, so the composite converges as O(Δs²) from one voxel
 * down (a narrower window, like the lesion preset, needs far smaller steps).
 */
export const DEFAULT_POINTS: readonly (readonly [number, number])[] = [
  [-1024, 0],
  [0, 0],
  [30, 0.03],
  [80, 0],
  [400, 0],
  [900, 0.3],
];

function pointParameters(index: number): NumberParameter[] {
  const [hu, opacity] = DEFAULT_POINTS[index]!;
  const k = index + 1;
  return [
    {
      kind: 'number',
      name: `hu-${k}`,
      label: `Point ${k}: value`,
      symbol: `v${k}`,
      unit: 'HU',
      min: -1024,
      max: 3071,
      step: 1,
      default: hu,
      description: `Value of control point ${k} of the opacity curve, in Hounsfield units (air −1000, water 0, bone +1000). Points are kept in increasing order.`,
    },
    {
      kind: 'number',
      name: `opacity-${k}`,
      label: `Point ${k}: opacity`,
      symbol: `α${k}`,
      unit: 'per voxel',
      min: 0,
      max: 1,
      step: 0.01,
      default: opacity,
      description: `Opacity of control point ${k}, per reference step of one voxel (2.5 mm); other steps are opacity-corrected.`,
    },
  ];
}

const parameters: Parameter[] = [
  {
    kind: 'choice',
    name: 'colormap',
    label: 'Colour map',
    choices: [
      { value: 'tissue', label: 'Tissue (red → beige → white)' },
      { value: 'bone', label: 'Bone (blue-grey → white)' },
      { value: 'viridis', label: 'Viridis' },
      { value: 'grey', label: 'Grey' },
    ],
    default: 'tissue',
    description:
      'Emission colour as a function of the value, spread over the opacity ramp (from where the opacity starts to rise to where it last changes).',
  },
  {
    kind: 'number',
    name: 'step',
    label: 'Step Δs',
    symbol: 'Δs',
    unit: 'voxels',
    min: 0.125,
    max: 4,
    step: 0.125,
    default: 1,
    description:
      'Distance between samples along each ray, in voxels of 2.5 mm; opacities are corrected for it.',
  },
  {
    kind: 'choice',
    name: 'termination',
    label: 'Early ray termination',
    choices: [
      { value: 'on', label: 'On: stop when T < ε' },
      { value: 'off', label: 'Off: march every ray to the end' },
    ],
    default: 'on',
    description: 'Stop a ray once its transmittance T falls below ε.',
  },
  {
    kind: 'number',
    name: 'epsilon',
    label: 'Termination threshold ε',
    symbol: 'ε',
    unit: '',
    min: 0.001,
    max: 0.2,
    step: 0.001,
    default: 0.01,
    description:
      'A ray stops when T < ε; the radiance it drops is at most ε times the brightest emission.',
  },
  {
    kind: 'choice',
    name: 'panel',
    label: 'Right image',
    choices: [
      { value: 'error', label: 'Error against the fine-step reference' },
      { value: 'steps', label: 'Steps taken per ray' },
    ],
    default: 'error',
    description:
      'What the right-hand image shows: |image − reference| per pixel, or how many steps each ray took (early termination shortens the rays that become opaque).',
  },
  {
    kind: 'number',
    name: 'azimuth',
    label: 'Camera azimuth',
    symbol: 'φ',
    unit: '°',
    min: -180,
    max: 180,
    step: 1,
    default: 35,
    description:
      'Orbit angle about the vertical axis (drag the image, or use the arrow keys on it).',
  },
  {
    kind: 'number',
    name: 'elevation',
    label: 'Camera elevation',
    symbol: 'θ',
    unit: '°',
    min: -85,
    max: 85,
    step: 1,
    default: 15,
    description: 'Orbit angle above the horizontal plane.',
  },
];
for (let index = 0; index < CONTROL_POINTS; index++) parameters.push(...pointParameters(index));

export const TRANSFER_FUNCTION: WidgetEntry = {
  name: 'transfer-function',
  title: 'Direct volume rendering: transfer function, step size and early termination',
  description:
    'A 3D Shepp–Logan head phantom in Hounsfield units, ray cast on the GPU with emission–absorption compositing. Edit the piecewise-linear opacity over the histogram of the data, pick a colour map or a preset, orbit the camera, and see the error against a fine-step reference next to the GPU time, with the steps and time early ray termination saves.',
  parameters,
};
