// What <sb-mie-lobe> computes, independent of the backend: its inputs, the plot's
// angles and the float64 analysis the compute worker returns (jobs.ts).
import type { ParameterValues } from '../parameters.ts';

/** Angles of the plot: every 0.25° from 0° to 180°. */
export const PLOT_ANGLES = 721;

/** The wavelengths of the colour readout (red, green, blue), nm. */
export const RGB_WAVELENGTHS = [680, 550, 440] as const;

export interface MieLobeInputs {
  radiusUm: number;
  wavelengthNm: number;
  n: number;
  kappa: number;
  /** Size parameter x = 2πr/λ. */
  x: number;
}

export function sizeParameter(radiusUm: number, wavelengthNm: number): number {
  return (2 * Math.PI * radiusUm * 1000) / wavelengthNm;
}

export function inputsFrom(values: ParameterValues): MieLobeInputs {
  const radiusUm = 10 ** Number(values['log-radius']);
  const wavelengthNm = Number(values['wavelength']);
  return {
    radiusUm,
    wavelengthNm,
    n: Number(values['n']),
    kappa: Number(values['kappa']),
    x: sizeParameter(radiusUm, wavelengthNm),
  };
}

/** The plot's angles θ (degrees) and their complements 1 ∓ cos θ, each without cancellation. */
export function plotAngles(): {
  degrees: Float64Array;
  oneMinusMu: Float64Array;
  onePlusMu: Float64Array;
} {
  const degrees = new Float64Array(PLOT_ANGLES);
  const oneMinusMu = new Float64Array(PLOT_ANGLES);
  const onePlusMu = new Float64Array(PLOT_ANGLES);
  for (let i = 0; i < PLOT_ANGLES; i++) {
    const theta = (Math.PI * i) / (PLOT_ANGLES - 1);
    degrees[i] = (180 * i) / (PLOT_ANGLES - 1);
    oneMinusMu[i] = 2 * Math.sin(theta / 2) ** 2;
    onePlusMu[i] = 2 * Math.cos(theta / 2) ** 2;
  }
  return { degrees, oneMinusMu, onePlusMu };
}

/** The float64 analysis of one sphere (the worker's result). */
export interface MieAnalysis {
  qExt: number;
  qSca: number;
  qAbs: number;
  qBack: number;
  g: number;
  albedo: number;
  terms: number;
  smallParticle: boolean;
  /** Time of the series (coefficients and efficiencies) and of the table, ms. */
  seriesMs: number;
  tableMs: number;
  /** The table (f32-rounded, as the GPU reads it) and its ∫p dω before normalising. */
  table: {
    oneMinusMu: Float64Array;
    onePlusMu: Float64Array;
    pdf: Float64Array;
    cdf: Float64Array;
  };
  tableNormalization: number;
  /** At the plot's angles: the series, the table (twin), HG with the same g, Rayleigh. */
  exact: Float64Array;
  tabulated: Float64Array;
  hg: Float64Array;
  rayleigh: Float64Array;
  /** HG fit: relative L1 error ∫|p_HG − p|dω (p integrates to 1) and p_HG(180°)/p(180°). */
  hgL1: number;
  hgBackscatterRatio: number;
  /** Q_sca at RGB_WAVELENGTHS for the same radius and index. */
  rgbQsca: [number, number, number];
}
