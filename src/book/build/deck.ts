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
      'Most media scatter forward. On a log radius the backward tail shows; the χ² test checks the sampler against the closed-form CDF.',
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
    title: 'A majorant that is too low',
    widget: 'delta-tracking',
    attributes: { estimator: 'delta', spp: '16', majorant: 'low', seed: '0' },
    caption:
      'With σ̄ below σt, delta tracking accepts too few collisions and the image is too bright: E[X] = exp(−∫min(σt, σ̄)). Ratio tracking with the same majorant stays unbiased, at a higher variance.',
    chapter: '06-unbiased-transmittance',
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
