// Parameters of <sb-single-scatter>: single scattering (chapter 9) in a scene built
// from these values (model.ts buildScene) and rendered by the scene engine
// (src/scene/): fog or smoke lit by a spot or directional light, an occluder that
// casts a shaft of shadow through the fog, a floor. The effect toggles change the
// scene, the planner (src/scene/plan.ts) decides what the kernel needs, and the widget
// shows the plan, the time the specialized kernel saves and the error of the
// progressive image against a converged reference.
import type { WidgetEntry } from '../parameters.ts';

const onOff = [
  { value: 'on', label: 'On' },
  { value: 'off', label: 'Off' },
] as const;

export const SINGLE_SCATTER: WidgetEntry = {
  name: 'single-scatter',
  title: 'Single scattering: shadow rays, shafts and the plan',
  description:
    'Fog or smoke lit by a spot or directional light, with an occluder that casts a visible shaft of shadow through the medium, over a floor. Each toggle changes the scene; the planner decides which effects the kernel needs and how to compute them, and the widget times the specialized kernel against the general one and measures the error of the progressive image against a converged reference.',
  parameters: [
    {
      kind: 'choice',
      name: 'medium',
      label: 'Medium',
      choices: [
        { value: 'fog', label: 'Homogeneous fog' },
        { value: 'smoke', label: 'Smoke (density grid)' },
      ],
      default: 'fog',
      description:
        "Homogeneous fog gets Beer's law in closed form for view and shadow rays; the 24³ smoke grid needs ratio tracking.",
    },
    {
      kind: 'choice',
      name: 'light',
      label: 'Light',
      choices: [
        { value: 'spot', label: 'Spot light' },
        { value: 'directional', label: 'Directional (sun)' },
      ],
      default: 'spot',
      description:
        'A spot light (point-like, 1/r² falloff, equiangular sampling in fog) or a directional light (parallel beam, irradiance E).',
    },
    {
      kind: 'number',
      name: 'sigma-s',
      label: 'Scattering coefficient',
      symbol: 'σs',
      unit: '1/m',
      min: 0.05,
      max: 4,
      step: 0.05,
      default: 0.6,
      description: 'σs of the fog (per unit density in the smoke).',
    },
    {
      kind: 'number',
      name: 'albedo',
      label: 'Single-scattering albedo',
      symbol: 'α',
      unit: '',
      min: 0.05,
      max: 1,
      step: 0.05,
      default: 0.9,
      description: 'α = σs/σt; σa = σs(1 − α)/α. With α = 1 the fog cannot emit (σa = 0).',
    },
    {
      kind: 'number',
      name: 'g',
      label: 'Henyey–Greenstein g',
      symbol: 'g',
      unit: '',
      min: -0.9,
      max: 0.9,
      step: 0.05,
      default: 0.3,
      description: 'Mean cosine of the phase function; g > 0 scatters forward.',
    },
    {
      kind: 'choice',
      name: 'scattering',
      label: 'In-scattering',
      choices: [
        { value: 'on', label: 'On (σs as set)' },
        { value: 'off', label: 'Off (σs = 0, same σt)' },
      ],
      default: 'on',
      description:
        'Off moves all of σt into absorption: the fog only darkens, and the planner drops the scattering code.',
    },
    {
      kind: 'choice',
      name: 'occluder',
      label: 'Occluder',
      choices: [
        { value: 'sphere', label: 'Sphere' },
        { value: 'box', label: 'Box' },
        { value: 'none', label: 'None' },
      ],
      default: 'sphere',
      description:
        'An opaque object in the beam: the shadow rays it blocks carve a dark shaft into the lit fog.',
    },
    {
      kind: 'choice',
      name: 'emission',
      label: 'Emission',
      choices: onOff,
      default: 'off',
      description: 'A faint orange glow Le of the medium (source σa·Le; needs α < 1).',
    },
    {
      kind: 'choice',
      name: 'floor',
      label: 'Floor',
      choices: onOff,
      default: 'on',
      description:
        'A diffuse floor. With the floor off and no occluder the scene has no surfaces and the planner drops the surface code.',
    },
    {
      kind: 'number',
      name: 'spp',
      label: 'Target samples per pixel',
      symbol: 'spp',
      unit: '',
      min: 16,
      max: 4096,
      step: 16,
      default: 256,
      description:
        'Accumulation stops here; the reference has eight times as many samples (computed once per scene).',
    },
  ],
};
