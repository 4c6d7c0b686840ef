// <sb-translucent-room>: subsurface scattering inside global illumination (chapter 12). A
// translucent sphere in a Cornell-box-like room, rendered twice: by volumetric path tracing
// through its smooth dielectric boundary (the reference), and with the dipole BSSRDF summed over
// irradiance samples that path tracing of the room computed (pass 1), the walls path traced the
// same way in both. Both accumulate progressively; each shows its GPU time, the dipole its error
// against the reference with both pictures' noise subtracted, and pass 1 the share of the
// sphere's light that came off the walls. Without WebGPU the float64 twins draw both pictures
// at 24² pixels with a few samples per pixel in the compute worker.
//
// The frame holds pass 1's numbers; the two pictures' rows are the view's (they change as the
// pictures accumulate, between frames).
import { defineWidget, type Preset } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import type { Refinement } from '../base/refinement.ts';
import type { GpuTiming } from '../base/timing.ts';
import { timingLabel } from '../base/timing.ts';
import { findMaterial } from '../../subsurface/materials.ts';
import { IRRADIANCE_PASSES } from './model.ts';
import { TRANSLUCENT_ROOM } from './schema.ts';

/** One frame: pass 1 of the dipole method (the irradiance samples) and what it found. */
export interface RoomFrame {
  size: number;
  samples: number;
  rays: number;
  irradiance: { milliseconds: number; timing: GpuTiming | 'cpu' };
  /** Share of the sphere's transmitted power ΣΔA·E that came off the walls, per channel and all. */
  indirect: { channels: readonly number[]; all: number };
  /** The preview after an input (pass 1 at preview size); absent: pass 1 at full size. */
  stage?: Refinement;
}

function preset(name: string, extra: Record<string, number | string> = {}): Preset {
  const label = findMaterial(name)!.label;
  const suffix = Object.entries(extra)
    .map(([k, v]) => (k === 'radius' ? `R = ${v} mm` : `${String(v)} walls`))
    .join(', ');
  return { label: suffix ? `${label}, ${suffix}` : label, values: { material: name, ...extra } };
}

const percent = (x: number): string => (Number.isFinite(x) ? `${formatNumber(100 * x, 3)}%` : '—');

export const widget = defineWidget<RoomFrame>({
  entry: TRANSLUCENT_ROOM,
  presets: [
    preset('skin1'),
    preset('skin1', { walls: 'black' }),
    preset('marble'),
    preset('wholemilk'),
    preset('ketchup'),
    preset('skin1', { radius: 1 }),
  ],
  readouts: {
    rows: [
      { key: 'path-spp', label: 'Path tracing: samples per pixel' },
      { key: 'path-time', label: 'Path tracing: time' },
      { key: 'path-se', label: 'Path tracing: noise on the sphere (RMS standard error)' },
      {
        key: 'irradiance',
        label: 'Dipole pass 1: irradiance samples × rays × passes · time',
        format: ({ samples, rays, irradiance }) =>
          `${samples} × ${rays} × ${IRRADIANCE_PASSES} · ${formatMilliseconds(irradiance.milliseconds)} (${timingLabel(irradiance.timing)})`,
      },
      { key: 'dipole-spp', label: 'Dipole picture: samples per pixel' },
      { key: 'dipole-time', label: 'Dipole: total time (pass 1 + picture)' },
      {
        key: 'dipole-error',
        label: 'Dipole vs path tracing on the sphere: relative RMSE (noise-corrected) · mean error',
      },
      {
        key: 'indirect',
        label: 'Share of the sphere’s light from the walls (R, G, B · all)',
        format: ({ indirect }) =>
          `${indirect.channels.map(percent).join(', ')} · ${percent(indirect.all)}`,
      },
      { key: 'capped', label: 'Paths stopped by a cap' },
    ],
    cost: ({ irradiance }) => ({
      milliseconds: irradiance.milliseconds,
      timing: irradiance.timing,
    }),
    costLine: ({ size, samples, rays, irradiance }, _how, backend) =>
      backend.kind === 'gpu'
        ? `${size}² pixels; pass 1: ${samples} irradiance samples × ${rays} rays × ${IRRADIANCE_PASSES} pass in ${formatMilliseconds(irradiance.milliseconds)}; both pictures accumulate on.`
        : `the float64 twins in the worker, ${size}² pixels, ${samples} irradiance samples × ${rays} rays × ${IRRADIANCE_PASSES} pass in ${formatMilliseconds(irradiance.milliseconds)}.`,
  },
  slides: [
    {
      title: 'A translucent sphere in a lit room: path tracing vs the dipole',
      attributes: { material: 'skin1', radius: '5', size: '48' },
      caption:
        'A skin sphere between a red and a green wall. Left, volumetric path tracing through its boundary; right, the dipole BSSRDF fed by irradiance that path tracing of the room computed. Both see the walls’ colour; switch the walls to black to see how much of the sphere’s light was indirect, and shrink the sphere to watch the dipole’s error grow.',
      chapter: '12-beyond-the-lecture',
    },
  ],
  deckOrder: 3,
  load: () => import('./view.ts'),
});
