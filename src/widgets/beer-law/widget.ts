// <sb-beer-law>: a collimated beam crossing a slab (chapter 2). Plots T(s), draws
// the attenuated beam on the GPU, reports T at the exit next to its float64
// reference and the cost of computing it, and checks the multiplicative property
// T(0→d) = T(0→s₀)·T(s₀→d) at the split point.
import type { CpuPictureStage } from '../base/cpuPicture.ts';
import { defineWidget, type FrameBackend } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { BEER_LAW } from './schema.ts';
import type { BeerLawInputs, BeerLawResult } from './model.ts';

/** One frame: the inputs, what the backend computed, and the float64 reference. */
export interface BeerLawFrame {
  inputs: BeerLawInputs;
  result: BeerLawResult;
  reference: BeerLawResult;
  /** The CPU fallback's picture (painted in the compute worker): its size, cost and stage. */
  picture?: CpuPictureStage;
}

/**
 * The identity is exact; what remains is rounding. On the GPU that is f32 plus WGSL's
 * sin, allowed an absolute error of 2^-11 (≈ 5e-4 relative on τ here).
 */
function splitBudget(backend: FrameBackend): number {
  return backend.kind === 'gpu' ? 5e-4 : 1e-12;
}

/** The CPU picture's part of the cost line. */
export function pictureCost(picture: CpuPictureStage): string {
  const size = `${picture.width}×${picture.height}`;
  return picture.milliseconds > 0
    ? `beam ${size} painted in a worker in ${formatMilliseconds(picture.milliseconds)}`
    : `beam ${size} from the cache`;
}

export const widget = defineWidget<BeerLawFrame>({
  entry: BEER_LAW,
  presets: [
    {
      label: 'thin fog',
      values: { 'sigma-a': 0.02, 'sigma-s': 0.3, thickness: 3, profile: 'homogeneous', split: 1 },
    },
    {
      label: 'smoke',
      values: { 'sigma-a': 1.2, 'sigma-s': 0.8, thickness: 2, profile: 'homogeneous', split: 1 },
    },
    {
      label: 'layered',
      values: { 'sigma-a': 0.2, 'sigma-s': 0.6, thickness: 6, profile: 'layered', split: 2.5 },
    },
    {
      label: 'τ = 100',
      values: { 'sigma-a': 5, 'sigma-s': 5, thickness: 10, profile: 'smooth', split: 5 },
    },
  ],
  readouts: {
    rows: [
      {
        key: 'tau',
        label: 'Optical thickness τ(0→d)',
        format: ({ reference }) =>
          formatNumber(reference.opticalDepth[reference.opticalDepth.length - 1] ?? 0),
      },
      {
        key: 'exit',
        label: 'T(0→d), this backend',
        format: ({ result }, backend) =>
          `${formatNumber(result.exit)}${backend.kind === 'gpu' ? ' (GPU, f32)' : ' (CPU, f64)'}`,
      },
      {
        key: 'reference',
        label: 'T(0→d), float64 reference',
        format: ({ inputs, reference }) =>
          inputs.profile === 'homogeneous'
            ? `${formatNumber(reference.exit)} = e^(−σt·d)`
            : formatNumber(reference.exit),
      },
      {
        key: 'error',
        label: 'Relative difference',
        format: ({ result, reference }) => {
          const difference = Math.abs(result.exit - reference.exit);
          return reference.exit > 0
            ? formatNumber(difference / reference.exit, 2)
            : `${formatNumber(difference, 2)} (absolute)`;
        },
      },
      {
        key: 'split',
        label: 'T(0→s₀) · T(s₀→d)',
        format: ({ result }) =>
          `${formatNumber(result.beforeSplit)} × ${formatNumber(result.afterSplit)} = ${formatNumber(result.beforeSplit * result.afterSplit)}`,
      },
      {
        key: 'split-check',
        label: 'Multiplicative property',
        format: ({ result }, backend) => {
          const product = result.beforeSplit * result.afterSplit;
          const budget = splitBudget(backend);
          const difference =
            Math.abs(product - result.exit) / Math.max(result.exit, Number.MIN_VALUE);
          const holds = difference <= budget || Math.abs(product - result.exit) < 1e-37;
          return holds
            ? {
                text: `holds: equals T(0→d) to ${formatNumber(difference, 2)} (rounding budget ${formatNumber(budget, 1)})`,
                state: 'ok',
              }
            : {
                text: `differs by ${formatNumber(difference, 2)}, above the rounding budget ${formatNumber(budget, 1)}`,
                state: 'bad',
              };
        },
      },
      {
        key: 'mfp',
        label: 'Mean free path 1/σ̄t',
        format: ({ inputs }) =>
          inputs.sigmaT > 0 ? `${formatNumber(1 / inputs.sigmaT, 4)} m` : '∞ (no medium)',
      },
    ],
    cost: ({ result, picture }) => ({
      milliseconds: result.milliseconds + (picture?.milliseconds ?? 0),
      timing: result.timing,
    }),
    costLine: ({ result, reference, picture }, how) =>
      `${result.transmittance.length} samples of T(s) in ${formatMilliseconds(result.milliseconds)} (${how}); ` +
      `float64 reference on the CPU in ${formatMilliseconds(reference.milliseconds)}` +
      (picture ? `; ${pictureCost(picture)}.` : '.'),
  },
  slides: [
    {
      title: "Beer's law",
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
      attributes: {
        'sigma-a': '5',
        'sigma-s': '5',
        thickness: '10',
        profile: 'smooth',
        split: '5',
      },
      caption:
        'At τ = 100 the f32 exponential is subnormal and then exactly 0 — never negative, never NaN.',
      chapter: '02-extinction-and-transmittance',
    },
  ],
  load: () => import('./view.ts'),
});
