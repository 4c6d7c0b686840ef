// <sb-hg-lobe>: the Henyey–Greenstein phase function (chapter 3). Draws the lobe
// as a polar plot and as a 3D surface on the GPU, samples 2^n scattering cosines
// with the library's HG sampler in a compute pass, and shows the histogram against
// the closed form with a chi-square test, the sample mean cosine against g, the
// normalisation of the float64 twin, and the cost of sampling on the GPU next to
// the CPU twin (averaged over frames); a cancellable sweep over N = 2¹⁰ … 2²⁰ plots
// the histogram's L1 error against the sampling time, next to its exact expectation.
import { defineWidget, type FrameBackend } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { HG_LOBE } from './schema.ts';
import type { Refinement } from '../base/refinement.ts';
import type { ChiSquareResult, HgHistogram, HgLobeInputs, MeanCosine } from './model.ts';

/**
 * One frame: the inputs, the backend's histogram, the float64 replay of the same
 * streams (the histogram itself on the CPU, its first 2¹⁶ samples next to the GPU),
 * the sampling time averaged over recent frames at this N, and the checks the view
 * computed (model.ts stays out of widget.ts, which every page loads).
 */
export interface HgLobeFrame {
  inputs: HgLobeInputs;
  histogram: HgHistogram;
  replay: HgHistogram;
  averageMs: number;
  averagedFrames: number;
  /** ∫ p dω by float64 quadrature. */
  integral: number;
  /** p at θ = 0° and 180° (sr⁻¹). */
  forward: number;
  backward: number;
  mean: MeanCosine;
  chi: ChiSquareResult;
  /** The χ² test's significance level. */
  alpha: number;
  /** Samples in a different bin than the float64 replay (equal sample counts only). */
  moved: number;
  /** Which refinement stage the histogram is (a preview draws fewer of the same samples). */
  stage: Refinement;
}

export const COMPARE_NAMES = { none: '', isotropic: 'isotropic', rayleigh: 'Rayleigh' } as const;

const SUPERSCRIPT_DIGITS = '⁰¹²³⁴⁵⁶⁷⁸⁹';

export function superscript(value: number): string {
  return [...String(value)]
    .map((c) => (c === '-' ? '⁻' : (SUPERSCRIPT_DIGITS[Number(c)] ?? c)))
    .join('');
}

/** How far the GPU's bins are from the float64 replay of the same streams. */
function replayValue({ histogram, replay, moved }: HgLobeFrame, backend: FrameBackend) {
  if (backend.kind !== 'gpu') return 'this is the float64 replay (CPU fallback)';
  if (replay.sampleCount !== histogram.sampleCount)
    return 'replayed on the CPU for the first 2¹⁶ samples only (timing)';
  return {
    text:
      moved === 0
        ? 'identical bins (GPU f32 vs CPU f64)'
        : `${moved} of ${histogram.sampleCount} samples in a neighbouring bin (f32 rounding at bin edges)`,
    state: moved <= 1e-3 * histogram.sampleCount ? ('ok' as const) : ('bad' as const),
  };
}

export const widget = defineWidget<HgLobeFrame>({
  entry: HG_LOBE,
  presets: [
    { label: 'g = −0.3 (back)', values: { g: -0.3 } },
    { label: 'g = 0 (isotropic)', values: { g: 0 } },
    { label: 'g = 0.6 (forward)', values: { g: 0.6 } },
    { label: 'g = 0.9 (clouds)', values: { g: 0.9 } },
    { label: 'Rayleigh vs isotropic', values: { g: 0, compare: 'rayleigh' } },
  ],
  readouts: {
    rows: [
      {
        key: 'normalisation',
        label: '∫ p dω (float64 quadrature)',
        format: ({ integral }) => ({
          text: integral.toFixed(10),
          state: Math.abs(integral - 1) < 1e-9 ? 'ok' : 'bad',
        }),
      },
      {
        key: 'forward',
        label: 'p(θ = 0°), forward',
        format: ({ forward }) => `${formatNumber(forward)} sr⁻¹`,
      },
      {
        key: 'backward',
        label: 'p(θ = 180°), backward',
        format: ({ backward }) => `${formatNumber(backward)} sr⁻¹`,
      },
      {
        key: 'mean-cosine',
        label: 'Sample mean cosine ± SE',
        format: ({ inputs, mean }) => ({
          text: `${formatNumber(mean.mean, 5)} ± ${formatNumber(mean.standardError, 2)} (g = ${formatNumber(inputs.g, 4)}, ${formatNumber(Math.abs(mean.zScore), 2)} SE)`,
          state: Math.abs(mean.zScore) < 5 ? 'ok' : 'bad',
        }),
      },
      {
        key: 'chi-square',
        label: 'χ² of 64 bins vs closed form',
        format: ({ chi, alpha }) => {
          const pooled = chi.pooled > 0 ? `, ${chi.pooled} sparse bins pooled` : '';
          return {
            text: `${formatNumber(chi.statistic, 4)} (df ${chi.df}${pooled}): ${chi.passes ? 'passes' : 'fails'} at α = ${alpha} (critical ${formatNumber(chi.critical, 4)})`,
            state: chi.passes ? 'ok' : 'bad',
          };
        },
      },
      { key: 'replay', label: 'Histogram vs float64 replay', format: replayValue },
      // The sweep's rows are the view's to write (context.setReadout).
      { key: 'sweep', label: 'Sweep: L1 error ∝ N^p', initial: 'run the sweep' },
      { key: 'sweep-check', label: 'Sweep: L1 at N = 2²⁰ vs expected', initial: 'run the sweep' },
    ],
    cost: ({ histogram }) => ({ milliseconds: histogram.milliseconds, timing: histogram.timing }),
    costLine: ({ inputs, histogram, replay, averageMs, averagedFrames }, how, backend) => {
      const n = histogram.sampleCount;
      const exponent = Math.round(Math.log2(n));
      const nText =
        `2${superscript(exponent)} = ${n} samples` +
        (exponent < inputs.samplesExponent ? ` of 2${superscript(inputs.samplesExponent)}` : '');
      const time =
        averagedFrames > 1
          ? `${formatMilliseconds(averageMs)} (${how}, mean of the last ${averagedFrames} frames at this N)`
          : `${formatMilliseconds(averageMs)} (${how}, one frame so far)`;
      if (backend.kind !== 'gpu') return `${nText} in ${time}, float64 twin.`;
      let twin: string;
      if (replay.sampleCount === n) {
        twin = `float64 twin on the CPU: ${formatMilliseconds(replay.milliseconds)} for the same ${n}`;
      } else {
        const factor = n / replay.sampleCount;
        twin =
          `float64 twin on the CPU: ≈ ${formatMilliseconds(replay.milliseconds * factor)} for ${n}, ` +
          `scaled ×${factor} from ${formatMilliseconds(replay.milliseconds)} measured on ${replay.sampleCount}`;
      }
      return `${nText} in ${time}; ${twin}.`;
    },
  },
  slides: [
    {
      title: 'Back scattering: g = −0.3',
      attributes: {
        g: '-0.3',
        compare: 'isotropic',
        scale: 'linear',
        samples: '16',
        seed: '1',
      },
      caption:
        'A Henyey–Greenstein lobe with g < 0 sends more light back toward the source; the mean cosine of the samples is g.',
      chapter: '03-phase-functions-and-in-scattering',
    },
    {
      title: 'Isotropic scattering: g = 0',
      attributes: {
        g: '0',
        compare: 'rayleigh',
        scale: 'linear',
        samples: '16',
        seed: '1',
      },
      caption:
        'At g = 0 HG is the isotropic 1/(4π); Rayleigh scattering (outline) is close to it but prefers forward and back.',
      chapter: '03-phase-functions-and-in-scattering',
    },
    {
      title: 'Forward scattering: g = 0.6',
      attributes: {
        g: '0.6',
        compare: 'isotropic',
        scale: 'log',
        samples: '16',
        seed: '1',
      },
      caption:
        'Most media scatter forward. On a log radius the backward tail shows; turn the 3D lobe with the arrow keys. The χ² test and the error-vs-time sweep (L1 ∝ N^−½) check the sampler against the closed form.',
      chapter: '03-phase-functions-and-in-scattering',
    },
  ],
  load: () => import('./view.ts'),
});
