// The demo deck: every widget in lecture order as full-screen slides, each a
// deep link (`deck.html#slide=3`), with a one-line caption. Slides are data; a
// new widget adds its slides here, in the order the lecture shows them.
import { WIDGET_CATALOG } from '../../widgets/catalog.ts';
import { parseParameters } from '../../widgets/parameters.ts';

export interface DeckSlide {
  title: string;
  /** Widget name without the `sb-` prefix. */
  widget: string;
  attributes: Readonly<Record<string, string>>;
  caption: string;
  /** Chapter slug the slide belongs to, for the "read more" link. */
  chapter: string;
}

export const DECK: readonly DeckSlide[] = [
  {
    title: "Beer's law",
    widget: 'beer-law',
    attributes: {
      'sigma-a': '0.2',
      'sigma-s': '0.8',
      thickness: '2',
      profile: 'homogeneous',
      split: '1',
    },
    caption:
      'Transmittance falls exponentially with optical thickness: T = e^(−σt·d). Drag d and watch T(s).',
    chapter: '02-extinction-and-transmittance',
  },
  {
    title: 'Fog and smoke',
    widget: 'beer-law',
    attributes: {
      'sigma-a': '1.2',
      'sigma-s': '0.8',
      thickness: '2',
      profile: 'homogeneous',
      split: '1',
    },
    caption:
      'Absorption and out-scattering both remove light from the beam: only σt = σa + σs matters for T.',
    chapter: '02-extinction-and-transmittance',
  },
  {
    title: 'The multiplicative property',
    widget: 'beer-law',
    attributes: {
      'sigma-a': '0.2',
      'sigma-s': '0.6',
      thickness: '6',
      profile: 'layered',
      split: '2.5',
    },
    caption:
      'Through any layers, T(0→d) = T(0→s₀)·T(s₀→d): move the split point and the product stays put.',
    chapter: '02-extinction-and-transmittance',
  },
  {
    title: 'Optically thick media',
    widget: 'beer-law',
    attributes: { 'sigma-a': '5', 'sigma-s': '5', thickness: '10', profile: 'smooth', split: '5' },
    caption:
      'At τ = 100 the f32 exponential is subnormal and then exactly 0 — never negative, never NaN.',
    chapter: '02-extinction-and-transmittance',
  },
  {
    title: 'Back scattering: g = −0.3',
    widget: 'hg-lobe',
    attributes: { g: '-0.3', compare: 'isotropic', scale: 'linear', samples: '16', seed: '1' },
    caption:
      'A Henyey–Greenstein lobe with g < 0 sends more light back toward the source; the mean cosine of the samples is g.',
    chapter: '03-phase-functions-and-in-scattering',
  },
  {
    title: 'Isotropic scattering: g = 0',
    widget: 'hg-lobe',
    attributes: { g: '0', compare: 'rayleigh', scale: 'linear', samples: '16', seed: '1' },
    caption:
      'At g = 0 HG is the isotropic 1/(4π); Rayleigh scattering (outline) is close to it but prefers forward and back.',
    chapter: '03-phase-functions-and-in-scattering',
  },
  {
    title: 'Forward scattering: g = 0.6',
    widget: 'hg-lobe',
    attributes: { g: '0.6', compare: 'isotropic', scale: 'log', samples: '16', seed: '1' },
    caption:
      'Most media scatter forward. On a log radius the backward tail shows; turn the 3D lobe with the arrow keys. The χ² test and the error-vs-time sweep (L1 ∝ N^−½) check the sampler against the closed form.',
    chapter: '03-phase-functions-and-in-scattering',
  },
  {
    title: 'Why the sky is blue',
    widget: 'rayleigh-sky',
    attributes: { 'sun-elevation': '60', scattering: 'on', steps: '32', exposure: '0' },
    caption:
      'Skylight is sunlight scattered once by air molecules, and σs ∝ λ⁻⁴: at noon the zenith has 4.5 times more blue than red.',
    chapter: '03-phase-functions-and-in-scattering',
  },
  {
    title: 'Why sunsets are red',
    widget: 'rayleigh-sky',
    attributes: { 'sun-elevation': '2', scattering: 'on', steps: '32', exposure: '1' },
    caption:
      'At 2° the sunlight crosses about 19 times the air of the vertical path, and Beer’s law removes the blue first: T_sun ≈ (0.42, 0.13, 0.007).',
    chapter: '03-phase-functions-and-in-scattering',
  },
  {
    title: 'The sky’s accuracy against its cost',
    widget: 'rayleigh-sky',
    attributes: { 'sun-elevation': '20', scattering: 'on', steps: '8', exposure: '0' },
    caption:
      'Run the sweep: the error falls as N⁻², but each view sample also marches N/4 sun samples, so against GPU time it falls more slowly, with a slope between −2 and −1.',
    chapter: '03-phase-functions-and-in-scattering',
  },
  {
    title: 'The volume rendering equation',
    widget: 'vre-ray',
    attributes: {
      sigma: '1',
      albedo: '0.5',
      emission: '0.5',
      inscatter: '0.3',
      background: '1',
      length: '2',
    },
    caption:
      'Radiance at the eye = emission and in-scattering along the ray, each weighted by T(0,s), plus the background times T(0,d).',
    chapter: '04-the-volume-rendering-equation',
  },
  {
    title: 'Ray marching: left versus midpoint samples',
    widget: 'raymarch-steps',
    attributes: { steps: '8', placement: 'midpoint', update: 'exact', density: '1.5', seed: '0' },
    caption:
      'The same 8 steps per ray, sampled at the middle of each step instead of its start: the error falls from O(h) to O(h²). Run the sweep to measure the order.',
    chapter: '05-emission-absorption-and-ray-marching',
  },
  {
    title: 'The linearised update fails',
    widget: 'raymarch-steps',
    attributes: { steps: '4', placement: 'left', update: 'linear', density: '1.5', seed: '0' },
    caption:
      'T ← T·(1 − σt·h) turns negative where σt·h > 1; the book clamps it to 0 and counts the clamped steps. The exact factor e^(−σt·h) never fails.',
    chapter: '05-emission-absorption-and-ray-marching',
  },
  {
    title: 'Delta tracking: unbiased, binary transmittance',
    widget: 'delta-tracking',
    attributes: { estimator: 'delta', spp: '4', majorant: 'tight', seed: '0' },
    caption:
      'Each sample is 0 or 1 and its mean is exactly T, with variance T(1 − T). Switch to exp(−τ̂) and the mean bias stays, however many samples: run the sweep for both.',
    chapter: '06-unbiased-transmittance',
  },
  {
    title: 'Five estimators at equal samples and equal time',
    widget: 'delta-tracking',
    attributes: { view: 'compare', estimator: 'delta', spp: '8', majorant: 'tight', seed: '0' },
    caption:
      'Top row: the same spp for all five; bottom row: the same GPU time as delta tracking at that spp. exp(−τ̂) stays biased however many samples it gets; unbiased ray marching wins by orders of magnitude. Sweep all five: four curves fall with slope −½, one levels off.',
    chapter: '06-unbiased-transmittance',
  },
  {
    title: 'A majorant that is too low',
    widget: 'delta-tracking',
    attributes: { estimator: 'delta', spp: '16', majorant: 'low', seed: '0' },
    caption:
      'With σ̄ below σt, delta tracking accepts too few collisions and the image is too bright: E[X] = exp(−∫min(σt, σ̄)). Ratio tracking with the same majorant stays unbiased, at a higher variance.',
    chapter: '06-unbiased-transmittance',
  },
  {
    title: 'Transfer functions: from Hounsfield units to light',
    widget: 'transfer-function',
    attributes: { step: '1', termination: 'on', colormap: 'tissue' },
    caption:
      'A CT head phantom in HU, ray cast with emission–absorption. Drag the opacity points over the histogram or press 1–4 for presets; drag the image to orbit. The error image shows the wood-grain rings of one-voxel steps.',
    chapter: '07-volume-visualization',
  },
  {
    title: 'Early ray termination: the skin surface',
    widget: 'transfer-function',
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
  {
    title: 'Inverse rendering: fit a grid to photographs',
    widget: 'inverse-render',
    attributes: { grid: '32', views: '8', regularizer: 'none' },
    caption:
      'Press Start: Adam fits 131,072 grid parameters to eight images with the gradient of the ray marcher. The training loss falls tenfold within about a hundred iterations; the held-out view from above shows what eight views pin down.',
    chapter: '08-inverse-volume-rendering',
  },
  {
    title: 'Three views: low loss, wrong volume',
    widget: 'inverse-render',
    attributes: { grid: '32', views: '3', regularizer: 'none' },
    caption:
      'With three cameras the fit explains its images almost perfectly, yet the held-out view stays wrong: many volumes produce the same three pictures. The loss curve and the held-out error part ways.',
    chapter: '08-inverse-volume-rendering',
  },
  {
    title: 'Single scattering: a shaft of shadow in the fog',
    widget: 'single-scatter',
    attributes: { light: 'spot', medium: 'fog', occluder: 'sphere', spp: '256' },
    caption:
      'Every visible point of the fog sends a shadow ray to the spot light; where the sphere blocks them, a dark cone cuts through the beam. The table is the plan: what the kernel compiled, how, and why; the readouts time it against the general kernel.',
    chapter: '09-single-scattering',
  },
  {
    title: 'Switch scattering off: the plan shrinks',
    widget: 'single-scatter',
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
  {
    title: 'Clouds are white: single versus multiple scattering',
    widget: 'volume-path-tracer',
    attributes: { scene: 'sphere', albedo: '0.99', g: '0.8', density: '10', spp: '4' },
    caption:
      'The same cloud rendered with one scattering event and with all of them. At albedo 0.99 most of the light that leaves the cloud has scattered many times: single scattering keeps only a fraction of it and the cloud turns grey.',
    chapter: '10-multiple-scattering',
  },
  {
    title: 'Path tracing converges as one over the square root of time',
    widget: 'volume-path-tracer',
    attributes: { scene: 'cloud', albedo: '0.98', g: '0.7', density: '16', spp: '8' },
    caption:
      'Both images refine progressively; once the converged reference is ready, their relative error is plotted against accumulated GPU time on log–log axes. Both fall with slope −½; the path tracer pays more time per sample for its longer paths.',
    chapter: '10-multiple-scattering',
  },
  {
    title: 'Volume caustics: photon mapping against path tracing',
    widget: 'photon-map',
    attributes: { photons: '65536', radius: '0.04' },
    caption:
      'A glass ball focuses a small sun into fog. Photon mapping resolves the focused cone of light in the time path tracing needs to show noise; shrink the radius and its blur (bias) turns into noise (variance). The sweep plots both errors against time.',
    chapter: '10-multiple-scattering',
  },
  {
    title: 'Skin: the dipole against Monte Carlo',
    widget: 'dipole-profile',
    attributes: { material: 'skin1' },
    caption:
      'R_d(r) per channel on log–log axes: red light travels millimetres, blue barely one. The dipole follows the Monte Carlo far from the beam and misses it within a mean free path; press More photons and watch the error bars shrink.',
    chapter: '11-subsurface-scattering',
  },
  {
    title: 'Colour bleeding: marble and ketchup',
    widget: 'dipole-profile',
    attributes: { material: 'ketchup', exposure: '1' },
    caption:
      'Ketchup absorbs green and blue within a millimetre and lets red wander a centimetre: the glow is red. Press 2 for marble, whose three channels spread alike into a broad white halo.',
    chapter: '11-subsurface-scattering',
  },
  {
    title: 'A translucent sphere: Lambert, dipole BSSRDF, path tracing',
    widget: 'translucent-render',
    attributes: { material: 'skin1', radius: '5', size: '64' },
    caption:
      'The same skin sphere as a Lambertian surface, with the dipole BSSRDF (Jensen–Buhler octree gather) and path traced. Light bleeds past the terminator only with the BSSRDF and the path tracer; drag ε and watch the nodes visited and the error against the reference (64² pixels, as in the chapter’s table; the errors subtract the young reference’s noise).',
    chapter: '11-subsurface-scattering',
  },
];

/** Checks every slide against the widget catalog; a bad slide fails the build. */
export function validateDeck(slides: readonly DeckSlide[] = DECK): void {
  slides.forEach((slide, index) => {
    const entry = WIDGET_CATALOG[slide.widget];
    if (!entry) throw new Error(`deck slide ${index + 1}: unknown widget "${slide.widget}"`);
    const parsed = parseParameters(entry.parameters, (name) => slide.attributes[name]);
    if (parsed.warnings.length)
      throw new Error(`deck slide ${index + 1}: ${parsed.warnings.join('; ')}`);
    const unknown = Object.keys(slide.attributes).filter(
      (name) => !entry.parameters.some((p) => p.name === name),
    );
    if (unknown.length)
      throw new Error(`deck slide ${index + 1}: unknown attributes ${unknown.join(', ')}`);
  });
}
