// <sb-photon-map>: photon mapping versus path tracing on a volume caustic (chapter 10).
// A glass ball focuses a small sun into a fog box. Each render traces N photons,
// sorts them into a uniform grid (cell = gather radius) and renders the volume
// radiance estimate along camera rays; path tracing then gets the same time
// (passes of PT_PASS_SPP paths per pixel until its accumulated time reaches the photon
// map's). Both images show their RMSE against a converged path-traced reference
// (public/photon-map/reference.bin, scripts/photon-map-reference.ts; the cost line
// names neither: student-facing text carries no repository paths). The sweep plots
// error against time for three series: photon mapping over N = 4096·n at the current
// radius (its error stops falling once the bias of the radius dominates, so it gets
// no power law, only its plateau: the error at the largest N and its change over the
// last 4× N), progressive photon mapping with r = r₀ (N/N₀)^(−1/7) through the
// current (N₀, r₀) (chapter 10, "Bias versus variance": RMSE ∝ N^(−2/7), fitted vs N
// and vs time), and path tracing over 4·n paths per pixel (fitted vs time, t^−½).
// Without WebGPU the float64 twin renders a 32×24 image with at most
// CPU_MAX_PHOTONS photons and says so.
import { defineWidget } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel, type GpuTiming } from '../base/timing.ts';
import type { Refinement } from '../base/refinement.ts';
import { PHOTON_MAP } from './schema.ts';
import type { PhotonInputs } from './model.ts';

/** Photons the CPU twin traces at most (the GPU traces all of them). */
export const CPU_MAX_PHOTONS = 8192;

/** The photon-mapped and path-traced images of one render, and what they cost. */
export interface PhotonImages {
  width: number;
  height: number;
  photonMap: Float64Array;
  pathTraced: Float64Array;
  pmMs: number;
  ptMs: number;
  ptSpp: number;
  stored: number;
  overflow: number;
  /** Stored photons for the camera view: x, y, z and 1 if through the glass, per photon. */
  view: Float32Array;
  timing: GpuTiming | 'cpu';
  reference: Float64Array;
}

/** One frame: the inputs, both images, and their RMSE against the reference. */
export interface PhotonFrame {
  inputs: PhotonInputs;
  images: PhotonImages;
  pmError: number;
  ptError: number;
  /** The grid the photons were sorted into: cells per axis and cell size (m). */
  grid: { dims: readonly number[]; cellSize: number };
  /** The reference's size and origin, for the cost line. */
  referenceNote: string;
  /** A preview with a fraction of the photons (inputs.photons says how many), or the full picture. */
  stage: Refinement;
}

/** The sweep's rows: written by the sweep (the view), not by a frame. */
export const SWEEP_ROWS = ['plateau', 'progressive', 'pt-rate'] as const;

export const widget = defineWidget<PhotonFrame>({
  entry: PHOTON_MAP,
  presets: [
    { label: 'few photons, wide radius', values: { photons: 8192, radius: 0.1 } },
    { label: 'many photons, narrow radius', values: { photons: 262144, radius: 0.02 } },
    { label: 'default (N = 65536, r = 4 cm)', values: { photons: 65536, radius: 0.04 } },
  ],
  readouts: {
    rows: [
      {
        key: 'stored',
        label: 'Photons stored in the fog',
        format: ({ inputs, images }, backend) => ({
          text:
            `${images.stored.toLocaleString('en-US')} from ${Math.min(inputs.photons, backend.kind === 'gpu' ? inputs.photons : CPU_MAX_PHOTONS).toLocaleString('en-US')} emitted` +
            (images.overflow > 0 ? `, ${images.overflow} lost (buffer full)` : ''),
          ...(images.overflow > 0 ? { state: 'bad' as const } : {}),
        }),
      },
      {
        key: 'pm-time',
        label: 'Photon mapping time (trace, sort, gather)',
        format: ({ images }) =>
          `${formatMilliseconds(images.pmMs)} (${timingLabel(images.timing)})`,
      },
      {
        key: 'pm-error',
        label: 'Photon mapping RMSE vs reference (W/(m²·sr))',
        format: ({ pmError, ptError }) => ({
          text: formatNumber(pmError, 3),
          ...(pmError < ptError ? { state: 'ok' as const } : {}),
        }),
      },
      {
        key: 'pt-spp',
        label: 'Path tracing, paths per pixel in equal time',
        format: ({ images }) => String(images.ptSpp),
      },
      {
        key: 'pt-time',
        label: 'Path tracing time',
        format: ({ images }) => formatMilliseconds(images.ptMs),
      },
      {
        key: 'pt-error',
        label: 'Path tracing RMSE vs reference (W/(m²·sr))',
        format: ({ pmError, ptError }) => ({
          text: formatNumber(ptError, 3),
          ...(pmError < ptError ? {} : { state: 'ok' as const }),
        }),
      },
      { key: 'plateau', label: 'Sweep, fixed r: plateau', initial: 'run the sweep' },
      {
        key: 'progressive',
        label: 'Sweep, progressive r ∝ N^−1/7: RMSE ∝ N^p',
        initial: 'run the sweep',
      },
      {
        key: 'pt-rate',
        label: 'Sweep, path tracing: RMSE ∝ time^p',
        initial: 'run the sweep',
      },
    ],
    cost: ({ images }) => ({ milliseconds: images.pmMs + images.ptMs, timing: images.timing }),
    costLine: ({ images, grid, referenceNote }, _how, backend) =>
      `${backend.kind === 'cpu' ? 'the float64 twin, ' : ''}${images.width}×${images.height} pixels; grid ${grid.dims.join('×')} cells of ${formatNumber(grid.cellSize * 100, 3)} cm. Reference: path tracing, ${referenceNote}.`,
  },
  slides: [
    {
      title: 'Volume caustics: photon mapping against path tracing',
      attributes: {
        photons: '65536',
        radius: '0.04',
      },
      caption:
        'A glass ball focuses a small sun into fog. Photon mapping resolves the focused cone of light in the time path tracing needs to show noise; shrink the radius and its blur (bias) turns into noise (variance). The sweep plots both errors against time.',
      chapter: '10-multiple-scattering',
    },
  ],
  deckOrder: 1,
  load: () => import('./view.ts'),
});
