// <sb-translucent-render>: a translucent sphere rendered three ways (chapter 11). Left, a
// Lambertian surface with the material's total diffuse reflectance R_d; middle, the dipole
// BSSRDF by Jensen & Buhler's two-pass hierarchical integration (irradiance samples on the
// sphere, an octree built in TypeScript, the gather on the GPU with the threshold ε); right,
// volumetric path tracing of the same sphere as the reference, accumulated progressively
// within a time budget per step, cancellable, with its per-pixel standard error. Each picture
// shows its GPU time and its error against the reference, with the reference's noise variance
// subtracted so that a young reference does not inflate it; an ε sweep plots the gather's error
// against its time; the middle picture can show the irradiance samples or the octree cut of a
// selected pixel (click it, or focus the picture and use the arrow keys). Without WebGPU the
// float64 twins draw the first two at reduced size and the reference is not run.
//
// The frame holds the Lambert and gather pictures' numbers; the reference's and the selected
// pixel's rows are the view's (they change as the path tracer runs, between frames).
import { defineWidget, type Preset } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import type { Refinement } from '../base/refinement.ts';
import { timingLabel, type GpuTiming } from '../base/timing.ts';
import { findMaterial } from '../../subsurface/materials.ts';
import { TRANSLUCENT_RENDER } from './schema.ts';

/** How one picture's time was measured. */
export type PictureTiming = GpuTiming | 'cpu';

/** One frame: the Lambert and BSSRDF pictures, their times and the octree they used. */
export interface TranslucentFrame {
  /** Image side in pixels (smaller on the CPU). */
  size: number;
  epsilon: number;
  octree: { samples: number; nodes: number; buildMs: number };
  diffuse: { milliseconds: number; timing: PictureTiming };
  gather: { milliseconds: number; timing: PictureTiming };
  /** The direct sum (ε = 0) on the GPU; null on the CPU, where it is not computed. */
  exact: { milliseconds: number; relativeRmse: number } | null;
  /** Nodes visited per pixel on the sphere, mean. */
  meanVisited: number;
  /** A preview with fewer pixels (issue 23); absent at full quality. */
  refinement?: Refinement;
}

function preset(name: string, extra: Record<string, number> = {}): Preset {
  return { label: findMaterial(name)!.label, values: { material: name, ...extra } };
}

export const widget = defineWidget<TranslucentFrame>({
  entry: TRANSLUCENT_RENDER,
  presets: [
    preset('skin1'),
    preset('marble'),
    preset('ketchup'),
    preset('wholemilk'),
    preset('skin1', { radius: 2 }),
    preset('apple'),
  ],
  readouts: {
    rows: [
      {
        key: 'diffuse-time',
        label: 'Lambert: time',
        format: ({ diffuse }) =>
          `${formatMilliseconds(diffuse.milliseconds)} (${timingLabel(diffuse.timing)})`,
      },
      { key: 'diffuse-error', label: 'Lambert: relative RMSE (noise-corrected) · mean error' },
      {
        key: 'gather-time',
        label: 'BSSRDF gather: time',
        format: ({ gather, epsilon, exact }) =>
          exact
            ? `${formatMilliseconds(gather.milliseconds)} (ε = ${formatNumber(epsilon, 3)}; direct sum ${formatMilliseconds(exact.milliseconds)})`
            : `${formatMilliseconds(gather.milliseconds)} (${timingLabel(gather.timing)})`,
      },
      { key: 'gather-error', label: 'BSSRDF: relative RMSE (noise-corrected) · mean error' },
      {
        key: 'gather-exact',
        label: 'BSSRDF gather vs direct sum (ε = 0)',
        format: ({ exact }) => (exact ? `${formatNumber(100 * exact.relativeRmse, 3)}% RMSE` : '—'),
      },
      {
        key: 'nodes-visited',
        label: 'Nodes visited per pixel (mean)',
        format: ({ meanVisited }) => formatNumber(meanVisited, 4),
      },
      {
        key: 'octree',
        label: 'Irradiance samples · octree nodes',
        format: ({ octree }) => `${octree.samples} · ${octree.nodes}`,
      },
      { key: 'pixel', label: 'Selected pixel: nodes visited · cut' },
      {
        key: 'pixel-values',
        label: 'Selected pixel: Lambert · BSSRDF · reference ± SE (mean of R, G, B)',
      },
      { key: 'path-spp', label: 'Path tracing: samples per pixel' },
      { key: 'path-time', label: 'Path tracing: time' },
      { key: 'path-se', label: 'Reference noise (RMS standard error)' },
      { key: 'path-capped', label: 'Walks stopped by the cap' },
    ],
    cost: ({ gather }) => ({ milliseconds: gather.milliseconds, timing: gather.timing }),
    costLine: ({ size, octree }, _how, backend) =>
      backend.kind === 'gpu'
        ? `${size}² pixels; octree of ${octree.nodes} nodes built on the CPU in ${formatMilliseconds(octree.buildMs)}.`
        : `the float64 twin, ${size}² pixels, octree of ${octree.nodes} nodes built in ${formatMilliseconds(octree.buildMs)}.`,
  },
  slides: [
    {
      title: 'A translucent sphere: Lambert, dipole BSSRDF, path tracing',
      attributes: {
        material: 'skin1',
        radius: '5',
        size: '64',
      },
      caption:
        'The same skin sphere as a Lambertian surface, with the dipole BSSRDF (Jensen–Buhler octree gather) and path traced. Light bleeds past the terminator only with the BSSRDF and the path tracer; drag ε and watch the nodes visited and the error against the reference (64² pixels, as in the chapter’s table; the errors subtract the young reference’s noise).',
      chapter: '11-subsurface-scattering',
    },
  ],
  deckOrder: 1,
  load: () => import('./view.ts'),
});
