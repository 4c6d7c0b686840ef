// Parameters of <sb-translucent-room> (chapter 12): a sphere of a measured material (Jensen et
// al. 2001, per mm) in a Cornell-box-like room, rendered by volumetric path tracing through
// its boundary (the reference) and with the dipole BSSRDF under the room's light, each with
// its time and the dipole's error against the reference.
import type { WidgetEntry } from '../parameters.ts';
import { measuredMaterialParameter } from '../base/materialParameter.ts';

export const TRANSLUCENT_ROOM: WidgetEntry = {
  name: 'translucent-room',
  title: 'A translucent sphere in a lit room: volumetric path tracing vs the dipole BSSRDF',
  description:
    'A sphere of a measured material on the floor of a small room with a red and a green wall and a square light in the ceiling. Left, volumetric path tracing: paths bounce between the walls, refract into the sphere, random-walk inside it and leave through its boundary. Right, the dipole BSSRDF summed over irradiance samples that path tracing of the room computed, so the walls’ colour reaches it. Each with its GPU time; the dipole’s error is measured against the path-traced picture on the sphere.',
  parameters: [
    measuredMaterialParameter(
      'A measured material of Jensen et al. 2001: σs′ and σa per channel in 1/mm, and η. The path tracer scatters isotropically with σs = σs′.',
    ),
    {
      kind: 'number',
      name: 'radius',
      label: 'Sphere radius',
      symbol: 'R',
      unit: 'mm',
      min: 0.5,
      max: 20,
      step: 0.5,
      default: 5,
      description:
        'Radius of the sphere; the room is 5 R wide, so the picture keeps its framing. The coefficients are per millimetre, so R sets how many mean free paths fit in the sphere: small spheres glow through, and there the dipole’s flat semi-infinite assumption fails.',
    },
    {
      kind: 'choice',
      name: 'walls',
      label: 'Walls',
      choices: [
        { value: 'coloured', label: 'Red and green (Cornell box)' },
        { value: 'white', label: 'All white' },
        { value: 'black', label: 'All black (no indirect light)' },
      ],
      default: 'coloured',
      description:
        'The walls’ albedo. Black walls leave the light’s direct illumination only, which shows how much of the sphere’s light is indirect.',
    },
    {
      kind: 'number',
      name: 'spp',
      label: 'Samples per pixel (log₂)',
      symbol: 'log₂ spp',
      unit: '',
      min: 1,
      max: 12,
      step: 1,
      // 64: on a CPU implementation of WebGPU (SwiftShader) one dipole sample per pixel of
      // the default picture takes seconds, because every sphere hit sums over all samples.
      default: 6,
      description:
        'How many samples per pixel each picture accumulates before it stops (the reference traces one path per colour channel per sample).',
    },
    {
      kind: 'number',
      name: 'size',
      label: 'Image size',
      symbol: 'N',
      unit: 'px',
      min: 16,
      max: 128,
      step: 8,
      default: 48,
      description: 'Width and height of each picture in pixels.',
    },
    {
      kind: 'number',
      name: 'exposure',
      label: 'Exposure',
      symbol: 'EV',
      unit: 'EV',
      min: -4,
      max: 6,
      step: 0.5,
      default: 0,
      description: 'Brightness of both pictures in stops (radiance × 2^EV, then sRGB).',
    },
    {
      kind: 'number',
      name: 'seed',
      label: 'Seed',
      symbol: 'seed',
      unit: '',
      min: 0,
      max: 1000000,
      step: 1,
      default: 0,
      description: 'Seed of both pictures’ random streams and of the irradiance samples.',
    },
  ],
};
