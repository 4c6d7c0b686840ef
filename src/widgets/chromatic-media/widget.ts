// <sb-chromatic-media>: colour in a medium (chapter 12). A sphere of medium whose extinction
// differs strongly between channels, rendered with multiple scattering by three estimators
// side by side (shaders/chromatic.wesl): one channel at a time (a delta-tracked walk per
// channel), hero wavelength (Wilkie et al. 2014) and spectral tracking (Kutz et al. 2017),
// each accumulating samples progressively. Readouts per estimator: time, per-channel
// standard error, colour noise, error against a reference picture (the one-channel
// estimator with REFERENCE_FACTOR× the samples, independent streams) and variance × time,
// with the winner of each measure named, and a log–log plot of error against time. Without WebGPU the float64 twin renders a
// smaller picture in the compute worker.
import { defineWidget, type ReadoutValue } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import type { Refinement } from '../base/refinement.ts';
import type { SweepPoint } from '../base/sweep.ts';
import { timingLabel, type GpuTiming } from '../base/timing.ts';
import { CHROMATIC_MEDIA } from './schema.ts';
import {
  ESTIMATORS,
  ESTIMATOR_LABELS,
  type ChromaticInputs,
  type EstimatorName,
  type EstimatorStats,
} from './model.ts';

export interface ChromaticFrame {
  inputs: ChromaticInputs;
  size: number;
  /** Samples per pixel of each estimator so far (the reference has REFERENCE_FACTOR×). */
  samples: number;
  referenceSamples: number;
  stats: Record<EstimatorName, EstimatorStats>;
  /** Total time of each estimator's passes so far (ms). */
  milliseconds: Record<EstimatorName, number>;
  /** This frame's time (all passes of the frame). */
  frameMilliseconds: number;
  timing: GpuTiming | 'cpu';
  /** Each estimator's RMS error against the reference after each pass so far (the plot). */
  errors: Record<EstimatorName, SweepPoint[]>;
  refinement: Refinement;
}

const perEstimator = (
  frame: ChromaticFrame,
  value: (s: EstimatorStats, name: EstimatorName) => string,
): string => ESTIMATORS.map((name) => value(frame.stats[name], name)).join(' · ');

/** A statistic of the samples: '…' until each pixel has two (a standard error needs two). */
const perEstimatorStatistic = (
  frame: ChromaticFrame,
  value: (s: EstimatorStats) => string,
): string => (frame.samples < 2 ? '… (needs 2 samples per pixel)' : perEstimator(frame, value));

/** The estimator(s) with the smallest value of a measure (lower is better; ties all named). */
function best(frame: ChromaticFrame, measure: (s: EstimatorStats) => number): string {
  const lowest = Math.min(...ESTIMATORS.map((name) => measure(frame.stats[name])));
  const winners = ESTIMATORS.filter((name) => measure(frame.stats[name]) === lowest);
  return winners.map((name) => ESTIMATOR_LABELS[name]).join(' = ');
}

const row = (
  key: string,
  label: string,
  format: (frame: ChromaticFrame) => ReadoutValue,
): { key: string; label: string; format: (frame: ChromaticFrame) => ReadoutValue } => ({
  key,
  label,
  format,
});

export const widget = defineWidget<ChromaticFrame>({
  entry: CHROMATIC_MEDIA,
  presets: [
    { label: 'Default: spread 16', values: { spread: 16, density: 2, albedo: 0.9, g: 0 } },
    { label: 'Grey medium (spread 1)', values: { spread: 1, density: 2, albedo: 0.9, g: 0 } },
    { label: 'Wide spread (100), dense', values: { spread: 100, density: 4, albedo: 0.95, g: 0 } },
    {
      label: 'Forward scattering, mild spread',
      values: { spread: 4, density: 2, albedo: 0.99, g: 0.7 },
    },
    { label: 'Absorbing (α = 0.3)', values: { spread: 16, density: 2, albedo: 0.3, g: 0 } },
  ],
  readouts: {
    rows: [
      row(
        'samples',
        'Samples per pixel (one channel · hero · spectral)',
        (f) => `${f.samples} each, reference ${f.referenceSamples} (${f.size}×${f.size} pixels)`,
      ),
      row('time', 'Time so far', (f) =>
        perEstimator(f, (_, name) => formatMilliseconds(f.milliseconds[name])),
      ),
      row('lookups', 'Density lookups per sample', (f) =>
        perEstimator(f, (s) => formatNumber(s.lookupsPerSample, 3)),
      ),
      row('channel-se', 'Standard error R/G/B (RMS over the sphere)', (f) =>
        perEstimatorStatistic(f, (s) => s.channelSe.map((x) => formatNumber(x, 2)).join('/')),
      ),
      row('colour-noise', 'Colour noise: SE of chromaticity ×1000', (f) =>
        perEstimatorStatistic(f, (s) => formatNumber(s.colourNoise, 3)),
      ),
      row('error', 'RMS error against the reference', (f) =>
        perEstimatorStatistic(f, (s) => formatNumber(s.rmsError, 2)),
      ),
      row('efficiency', 'Variance × time per sample (lower wins)', (f) =>
        perEstimatorStatistic(f, (s) => formatNumber(s.varianceTime, 2)),
      ),
      row('winner', 'Lowest colour noise · lowest variance × time', (f) =>
        f.samples < 2
          ? '…'
          : `${best(f, (s) => s.colourNoise)} · ${best(f, (s) => s.varianceTime)}`,
      ),
      row('capped', 'Walks stopped by a cap', (f) => {
        const capped = ESTIMATORS.reduce((n, name) => n + f.stats[name].capped, 0);
        return { text: String(capped), state: capped === 0 ? 'ok' : 'bad' };
      }),
    ],
    cost: (f) => ({ milliseconds: f.frameMilliseconds, timing: f.timing }),
    costLine: (f, _how, backend) =>
      `${backend.kind === 'cpu' ? 'float64 twin in the compute worker, ' : ''}3 estimators + reference, ${f.size}×${f.size} pixels, ${f.inputs.spp} samples per pass; this pass ${formatMilliseconds(f.frameMilliseconds)} (${timingLabel(f.timing)}); spread ${f.inputs.spread}, σt = ${formatNumber(f.inputs.density / Math.sqrt(f.inputs.spread), 3)}/${formatNumber(f.inputs.density, 3)}/${formatNumber(f.inputs.density * Math.sqrt(f.inputs.spread), 3)} 1/m.`,
  },
  slides: [
    {
      title: 'Colour in a medium: three ways to sample a chromatic path',
      attributes: { spread: '16', density: '2', albedo: '0.9' },
      caption:
        'Blue is 16× thicker than red. One channel at a time pays for three walks; hero wavelength shares one walk and weights the channels by the balance heuristic; spectral tracking walks at the blue majorant and lets the throughput steer. Watch the colour noise and variance × time.',
      chapter: '12-beyond-the-lecture',
    },
    {
      title: 'A grey medium: the three estimators agree',
      attributes: { spread: '1', density: '2', albedo: '0.9' },
      caption:
        'With equal extinction in every channel all three sample the same distances: no colour noise at all, and one channel at a time is simply three times the work.',
      chapter: '12-beyond-the-lecture',
    },
  ],
  load: () => import('./view.ts'),
});
