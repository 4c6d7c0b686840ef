// <sb-mie-lobe>: the phase function of one sphere from Lorenz–Mie theory (chapter 3).
// The series runs in float64 in the compute worker (src/reference/mie.ts); the GPU
// evaluates the tabulated phase function from the WGSL library (shaders/mie.wesl) at
// the plot's angles, and the plot shows it on a log scale against the series itself,
// Henyey–Greenstein with the same g and Rayleigh. The readouts give the efficiencies,
// the error of the HG fit, the GPU's difference from the series and the table's, and
// Q_sca at red, green and blue — flat for cloud droplets (white), λ⁻⁴ for molecules (blue).
import { defineWidget, type FrameBackend } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { MIE_LOBE } from './schema.ts';
import { RGB_WAVELENGTHS, type MieAnalysis, type MieLobeInputs } from './model.ts';

/** One frame: the inputs, the worker's float64 analysis and the curve the backend drew. */
export interface MieLobeFrame {
  inputs: MieLobeInputs;
  analysis: MieAnalysis;
  /** p(θ) at the plot's angles from the tabulated phase function on this backend. */
  drawn: Float64Array;
  milliseconds: number;
  timing: 'gpu-timestamp' | 'gpu-wall' | 'cpu';
}

/** Largest relative difference between the drawn curve and a reference curve. */
export function largestRelativeDifference(
  drawn: ArrayLike<number>,
  reference: ArrayLike<number>,
): number {
  let worst = 0;
  for (let i = 0; i < reference.length; i++) {
    const r = reference[i]!;
    if (r > 0) worst = Math.max(worst, Math.abs(drawn[i]! - r) / r);
  }
  return worst;
}

/** The colour readout: Q_sca at R, G, B relative to green, and what it looks like. */
function colourText(rgb: readonly [number, number, number]): string {
  const [r, g, b] = rgb;
  const ratio = (value: number): string => formatNumber(value / g, 3);
  const spread = Math.max(r, g, b) / Math.max(Math.min(r, g, b), Number.MIN_VALUE);
  const look = spread < 1.15 ? 'white (cloud)' : b > r ? 'bluish (sky)' : 'reddish';
  return `R : G : B = ${ratio(r)} : 1 : ${ratio(b)} at ${RGB_WAVELENGTHS.join('/')} nm — ${look}`;
}

const backendName = (backend: FrameBackend): string =>
  backend.kind === 'gpu' ? 'GPU, f32 table' : 'CPU, float64 twin of the table';

export const widget = defineWidget<MieLobeFrame>({
  entry: MIE_LOBE,
  presets: [
    { label: 'fog droplet', values: { 'log-radius': 0, wavelength: 550, n: 1.33, kappa: 0 } },
    { label: 'cloud droplet', values: { 'log-radius': 1, wavelength: 550, n: 1.33, kappa: 0 } },
    // Milk fat in water: 1.46/1.33 relative, globules of ≈ 1–4 µm diameter.
    { label: 'milk fat globule', values: { 'log-radius': 0, wavelength: 550, n: 1.098, kappa: 0 } },
    { label: 'soot', values: { 'log-radius': -1, wavelength: 550, n: 1.75, kappa: 0.44 } },
    {
      label: 'air molecule (Rayleigh)',
      values: { 'log-radius': -2, wavelength: 550, n: 1.01, kappa: 0 },
    },
    {
      label: 'rainbow (100 µm drop)',
      values: { 'log-radius': 2, wavelength: 550, n: 1.333, kappa: 0 },
    },
  ],
  readouts: {
    rows: [
      {
        key: 'size',
        label: 'Size parameter x = 2πr/λ',
        format: ({ inputs }) =>
          `${formatNumber(inputs.x, 4)} (r = ${formatNumber(inputs.radiusUm, 3)} µm, λ = ${inputs.wavelengthNm} nm)`,
      },
      {
        key: 'efficiencies',
        label: 'Q_ext, Q_sca, Q_abs',
        format: ({ analysis }) =>
          `${formatNumber(analysis.qExt, 5)}, ${formatNumber(analysis.qSca, 5)}, ${formatNumber(Math.max(analysis.qAbs, 0), 3)}`,
      },
      {
        key: 'g',
        label: 'Asymmetry g = ⟨cos θ⟩',
        format: ({ analysis }) => formatNumber(analysis.g, 5),
      },
      {
        key: 'albedo',
        label: 'Single-scattering albedo Q_sca/Q_ext',
        format: ({ analysis }) => formatNumber(analysis.albedo, 5),
      },
      {
        key: 'terms',
        label: 'Series',
        format: ({ analysis }) =>
          analysis.smallParticle
            ? `small-particle expansion (Wiscombe), ${formatMilliseconds(analysis.seriesMs)}`
            : `${analysis.terms} terms in ${formatMilliseconds(analysis.seriesMs)}; table of 513 angles in ${formatMilliseconds(analysis.tableMs)}`,
      },
      {
        key: 'hg-error',
        label: 'HG with the same g: error',
        format: ({ analysis }) =>
          `∫|p_HG − p| dω = ${formatNumber(analysis.hgL1, 3)}; backscatter p_HG(180°)/p(180°) = ${formatNumber(analysis.hgBackscatterRatio, 3)}`,
      },
      {
        key: 'drawn-error',
        label: 'Drawn curve vs the series',
        format: ({ analysis, drawn }, backend) =>
          `${formatNumber(largestRelativeDifference(drawn, analysis.exact), 2)} largest relative difference (${backendName(backend)}); vs the float64 table ${formatNumber(largestRelativeDifference(drawn, analysis.tabulated), 2)}; table ∫p dω before normalising ${formatNumber(analysis.tableNormalization, 6)}`,
      },
      {
        key: 'colour',
        label: 'Colour of the scattered light',
        format: ({ analysis }) => colourText(analysis.rgbQsca),
      },
    ],
    cost: ({ milliseconds, timing }) => ({ milliseconds, timing }),
    costLine: ({ analysis, drawn, milliseconds }, how) =>
      `${drawn.length} angles from the table in ${formatMilliseconds(milliseconds)} (${how}); ` +
      `float64 series in the worker: ${formatMilliseconds(analysis.seriesMs)}, table ${formatMilliseconds(analysis.tableMs)}.`,
  },
  slides: [
    {
      title: 'Mie scattering: a fog droplet',
      attributes: { 'log-radius': '0', wavelength: '550', n: '1.33', kappa: '0' },
      caption:
        'A 1 µm water droplet scatters mostly forward: the Lorenz–Mie lobe (solid) against Henyey–Greenstein with the same g (dashed) and Rayleigh.',
      chapter: '03-phase-functions-and-in-scattering',
    },
    {
      title: 'Why clouds are white',
      attributes: { 'log-radius': '1', wavelength: '550', n: '1.33', kappa: '0' },
      caption:
        'For droplets much larger than the wavelength Q_sca ≈ 2 at every colour; shrink the radius to 0.01 µm and blue wins by λ⁻⁴.',
      chapter: '03-phase-functions-and-in-scattering',
    },
  ],
  // After the sky in the deck, as Mie follows Rayleigh in the chapter.
  deckOrder: 2,
  load: () => import('./view.ts'),
});
