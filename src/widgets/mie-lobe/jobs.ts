// <sb-mie-lobe>'s float64 work, run in the compute worker (src/workers/compute.ts) and
// cached by arguments: the Lorenz–Mie series of the sphere (≈ x + 4x^{1/3} + 2 terms,
// ten thousand at the largest size), the table the GPU evaluates, the comparison curves
// and the colour readout. No DOM, no GPU.
import {
  mieCoefficients,
  mieEfficiencies,
  mieEfficienciesFromCoefficients,
  miePhaseValues,
  mieTabulatePhase,
  phaseTableToF32,
  phaseTabulatedEvalTerms,
} from '../../reference/mie.ts';
import { hgEvalTerms, rayleighEval } from '../../reference/phase.ts';
import {
  plotAngles,
  RGB_WAVELENGTHS,
  sizeParameter,
  type MieAnalysis,
  type MieLobeInputs,
} from './model.ts';

/** Relative L1 distance ∫|p_HG − p| dω over the table's intervals (trapezoids in 1 − μ). */
function hgL1Error(table: MieAnalysis['table'], g: number): number {
  let sum = 0;
  for (let k = 0; k + 1 < table.pdf.length; k++) {
    const lower = Math.abs(
      hgEvalTerms(g, table.oneMinusMu[k]!, table.onePlusMu[k]!) - table.pdf[k]!,
    );
    const upper = Math.abs(
      hgEvalTerms(g, table.oneMinusMu[k + 1]!, table.onePlusMu[k + 1]!) - table.pdf[k + 1]!,
    );
    sum += Math.PI * (lower + upper) * (table.oneMinusMu[k + 1]! - table.oneMinusMu[k]!);
  }
  return sum;
}

export function analyseSphere(inputs: MieLobeInputs): MieAnalysis {
  const m = { n: inputs.n, kappa: inputs.kappa };
  const seriesStart = performance.now();
  const coefficients = mieCoefficients(inputs.x, m);
  const efficiencies = mieEfficienciesFromCoefficients(coefficients);
  const seriesMs = performance.now() - seriesStart;
  const tableStart = performance.now();
  const built = mieTabulatePhase(inputs.x, m);
  const tableMs = performance.now() - tableStart;
  const table = phaseTableToF32(built);
  const angles = plotAngles();
  const mus = Array.from(angles.oneMinusMu, (t, i) =>
    t < angles.onePlusMu[i]! ? 1 - t : angles.onePlusMu[i]! - 1,
  );
  const exact = Float64Array.from(miePhaseValues(coefficients, efficiencies.qSca, mus));
  const tabulated = angles.oneMinusMu.map((t, i) =>
    phaseTabulatedEvalTerms(table, t, angles.onePlusMu[i]!),
  );
  const hg = angles.oneMinusMu.map((t, i) => hgEvalTerms(efficiencies.g, t, angles.onePlusMu[i]!));
  const rayleigh = Float64Array.from(mus, (mu) => rayleighEval(mu));
  const back = exact[exact.length - 1]!;
  const rgbQsca = RGB_WAVELENGTHS.map(
    (lambda) => mieEfficiencies(sizeParameter(inputs.radiusUm, lambda), m).qSca,
  ) as [number, number, number];
  return {
    qExt: efficiencies.qExt,
    qSca: efficiencies.qSca,
    qAbs: efficiencies.qAbs,
    qBack: efficiencies.qBack,
    g: efficiencies.g,
    albedo: efficiencies.albedo,
    terms: efficiencies.terms,
    smallParticle: coefficients.smallParticle,
    seriesMs,
    tableMs,
    table,
    tableNormalization: built.normalization,
    exact,
    tabulated,
    hg,
    rayleigh,
    hgL1: hgL1Error(table, efficiencies.g),
    hgBackscatterRatio: back > 0 ? hg[hg.length - 1]! / back : Infinity,
    rgbQsca,
  };
}

export const jobs = { analyseSphere };
