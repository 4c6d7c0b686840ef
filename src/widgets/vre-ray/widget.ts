// <sb-vre-ray>: one ray through an emitting, scattering medium in front of a
// background (chapter 4). Plots what reaches the eye from [0, s] term by term,
// draws the medium and the weighted source T(0,s)·(σa Le + σs L_in) on the GPU,
// and reports the marched radiance at the eye next to the exact integral form
// L = (1 − α)Le(1 − T) + αL_in(1 − T) + T·L_bg and the cost of the march.
import type { CpuPictureStage } from '../base/cpuPicture.ts';
import { defineWidget } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { VRE_RAY } from './schema.ts';
import { MARCH_STEPS, type ExactRadiance, type VreRayInputs, type VreRayResult } from './model.ts';

/** One frame: the inputs, the backend's march, the float64 march and the exact form. */
export interface VreRayFrame {
  inputs: VreRayInputs;
  result: VreRayResult;
  twin: VreRayResult;
  exact: ExactRadiance;
  /** The CPU fallback's picture (painted in the compute worker): its size, cost and stage. */
  picture?: CpuPictureStage;
}

/** T(0→d) as the march ended it. */
export function marchedTransmittance(result: VreRayResult): number {
  return result.transmittance[MARCH_STEPS] ?? NaN;
}

export const widget = defineWidget<VreRayFrame>({
  entry: VRE_RAY,
  presets: [
    {
      label: 'absorbing only',
      values: { sigma: 1, albedo: 0, emission: 0.5, inscatter: 0, background: 1, length: 2 },
    },
    {
      label: 'scattering only',
      values: { sigma: 1, albedo: 1, emission: 0, inscatter: 0.3, background: 1, length: 2 },
    },
    {
      label: 'thick medium hides the background',
      values: { sigma: 3, albedo: 0.5, emission: 0.5, inscatter: 0.3, background: 1, length: 4 },
    },
    {
      label: 'vacuum',
      values: { sigma: 0, albedo: 0.5, emission: 0.5, inscatter: 0.3, background: 1, length: 2 },
    },
  ],
  readouts: {
    rows: [
      {
        key: 'tau',
        label: 'Optical thickness τ(0→d)',
        format: ({ exact }) => formatNumber(exact.opticalDepth),
      },
      {
        key: 'transmittance',
        label: 'T(0→d)',
        format: ({ result, exact }) =>
          `${formatNumber(marchedTransmittance(result))} (exact ${formatNumber(exact.transmittance)})`,
      },
      {
        key: 'terms',
        label: 'Emission + in-scattering + background',
        format: ({ inputs, result }) =>
          `${formatNumber(result.emitted[MARCH_STEPS] ?? NaN, 4)} + ${formatNumber(result.inscattered[MARCH_STEPS] ?? NaN, 4)} + ${formatNumber(marchedTransmittance(result) * inputs.background, 4)}`,
      },
      {
        key: 'total',
        label: 'L at the eye, this backend',
        format: ({ result }, backend) =>
          `${formatNumber(result.total)}${backend.kind === 'gpu' ? ' (GPU, f32)' : ' (CPU, f64)'}`,
      },
      {
        key: 'reference',
        label: 'L at the eye, exact (float64)',
        format: ({ exact }) => `${formatNumber(exact.total)} = J(1−T) + T·L_bg`,
      },
      {
        key: 'error',
        label: 'Relative difference',
        format: ({ result, exact }) => {
          const difference = Math.abs(result.total - exact.total);
          return exact.total > 0
            ? formatNumber(difference / exact.total, 2)
            : `${formatNumber(difference, 2)} (absolute)`;
        },
      },
    ],
    cost: ({ result, picture }) => ({
      milliseconds: result.milliseconds + (picture?.milliseconds ?? 0),
      timing: result.timing,
    }),
    costLine: ({ result, twin, picture }, how) =>
      `${MARCH_STEPS} midpoint steps in ${formatMilliseconds(result.milliseconds)} (${how}); ` +
      `float64 march on the CPU in ${formatMilliseconds(twin.milliseconds)}` +
      (picture
        ? picture.milliseconds > 0
          ? `; ray ${picture.width}×${picture.height} painted in a worker in ${formatMilliseconds(picture.milliseconds)}.`
          : `; ray ${picture.width}×${picture.height} from the cache.`
        : '.'),
  },
  slides: [
    {
      title: 'The volume rendering equation',
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
  ],
  load: () => import('./view.ts'),
});
