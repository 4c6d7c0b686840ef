// Parameters of <sb-translucent-render> (chapter 11): a sphere of a measured material
// (Jensen et al. 2001, per mm) lit by one directional light, rendered as a Lambertian surface,
// with the dipole BSSRDF by Jensen & Buhler's hierarchical integration, and by brute-force
// volumetric path tracing (the reference), each with its GPU time and error.
import type { WidgetEntry } from '../parameters.ts';
import { measuredMaterialParameter } from '../base/materialParameter.ts';

export const TRANSLUCENT_RENDER: WidgetEntry = {
  name: 'translucent-render',
  title: 'A translucent sphere three ways: Lambert, dipole BSSRDF (Jensen–Buhler), path tracing',
  description:
    'One sphere of a measured material lit by a directional light, rendered as a Lambertian surface with the material’s total diffuse reflectance, with the dipole BSSRDF summed by Jensen and Buhler’s octree over irradiance samples (the threshold ε trades accuracy for time), and by volumetric path tracing as the reference; each with GPU time and error, a view of the irradiance samples and of the octree cut one pixel uses.',
  parameters: [
    measuredMaterialParameter(
      'A measured material of Jensen et al. 2001: σs′ and σa per channel in 1/mm, and η.',
    ),
    {
      kind: 'number',
      name: 'radius',
      label: 'Sphere radius',
      symbol: 'R',
      unit: 'mm',
      min: 1,
      max: 40,
      step: 0.5,
      default: 5,
      description:
        'Radius of the sphere. The coefficients are per millimetre, so the radius sets how many mean free paths fit in the object: small spheres glow through, large ones look opaque.',
    },
    {
      kind: 'number',
      name: 'light-angle',
      label: 'Light angle from the view axis',
      symbol: 'θ_l',
      unit: '°',
      min: 0,
      max: 150,
      step: 5,
      default: 60,
      description:
        'Angle between the viewing direction and the direction toward the light (over 90°: back lighting).',
    },
    {
      kind: 'number',
      name: 'log-epsilon',
      label: 'Gather threshold log₁₀ ε',
      symbol: 'log₁₀ ε',
      unit: '',
      min: -3,
      max: 0.5,
      step: 0.1,
      default: -1,
      description:
        'Jensen–Buhler’s refinement threshold: an octree node is used whole when the solid angle ΔA/‖x − p̄‖² it subtends is below ε. Smaller is more accurate and slower; −3 is close to the direct sum.',
    },
    {
      kind: 'number',
      name: 'samples',
      label: 'Irradiance samples (log₂ n)',
      symbol: 'log₂ n',
      unit: '',
      min: 8,
      max: 16,
      step: 1,
      default: 12,
      description:
        'Number of irradiance samples of pass 1 on the sphere (Fibonacci lattice), each of area 4πR²/n.',
    },
    {
      kind: 'number',
      name: 'size',
      label: 'Image size',
      symbol: 'N',
      unit: 'px',
      min: 16,
      max: 256,
      step: 16,
      default: 64,
      description: 'Width and height of each of the three pictures in pixels.',
    },
    {
      kind: 'number',
      name: 'spp',
      label: 'Path tracing target (log₂ samples per pixel)',
      symbol: 'log₂ spp',
      unit: '',
      min: 2,
      max: 14,
      step: 1,
      default: 10,
      description:
        'How many samples per pixel the reference accumulates before it stops (each runs one walk per colour channel).',
    },
    {
      kind: 'number',
      name: 'g',
      label: 'Path tracer anisotropy g',
      symbol: 'g',
      unit: '',
      min: 0,
      max: 0.9,
      step: 0.05,
      default: 0,
      description:
        'Henyey–Greenstein g of the path tracer, which scatters with σs = σs′/(1 − g); the dipole sees only σs′.',
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
      default: 2,
      description: 'Brightness of all three pictures in stops (radiance × 2^EV, then sRGB).',
    },
    {
      kind: 'choice',
      name: 'overlay',
      label: 'Show on the BSSRDF picture',
      // The picture comes first: the cut of a pixel is hundreds of circles that cover the
      // sphere (issue 17), so by default only the selected pixel's small marker is drawn.
      choices: [
        { value: 'none', label: 'Only the selected pixel' },
        { value: 'cut', label: 'The octree cut of the selected pixel' },
        { value: 'samples', label: 'The irradiance samples, coloured by E' },
      ],
      default: 'none',
      description:
        'Draw only the selected pixel (its nodes visited are in the readouts), the nodes its gather used (circles of their area, at their mean position), or the irradiance samples of pass 1.',
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
      description: 'Seed of the path tracer’s random streams.',
    },
  ],
};
