// <sb-dipole-profile>: the diffusion dipole and its profiles (chapter 11). Evaluates
// the classic dipole, the better dipole and the Christensen–Burley profile per RGB
// channel on the GPU (the library's dipole module) and plots them on log–log axes
// against a GPU Monte Carlo of the same half-space with ±1 SE error bars; tabulates the
// total R_d of each; shows the Monte Carlo's cost (GPU ms, photons, collisions) next
// to its standard error and to each model's difference from it, with a plot of those
// errors against the Monte Carlo's time; draws a disc of the material lit by a thin
// beam from the dipole. "More photons" continues the Monte Carlo progressively and can
// be cancelled. Without WebGPU the float64 twins do all of it on the CPU.
import { defineWidget, type Preset, type ReadoutValue } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import type { Refinement } from '../base/refinement.ts';
import { timingLabel, type GpuTiming } from '../base/timing.ts';
import { findMaterial } from '../../subsurface/materials.ts';
import { DIPOLE_PROFILE } from './schema.ts';
import { materialValues } from './materialValues.ts';
import type { ProfileCurves, ProfileInputs, TotalComparison } from './model.ts';

/** The Monte Carlo so far, compared with the models' totals (per channel R, G, B). */
export interface MonteCarloSummary {
  batches: number;
  channels: {
    se: number;
    dipole: TotalComparison;
    better: TotalComparison;
    collisionsPerPhoton: number;
  }[];
  /** Walks stopped by the cap, over all channels, and the most light one channel's held. */
  capped: number;
  cappedWeight: number;
  /** The cap on free flights per walk (MC_MAX_COLLISIONS). */
  cap: number;
}

/** One frame: the profiles and their cost, and the Monte Carlo accumulated for this medium. */
export interface DipoleFrame {
  inputs: ProfileInputs;
  curves: ProfileCurves;
  curvesMilliseconds: number;
  curvesTiming: GpuTiming | 'cpu';
  /** The render's cost: the profiles plus the first Monte Carlo run of a new medium. */
  frameMilliseconds: number;
  photons: number;
  mcMilliseconds: number;
  /** How the Monte Carlo was timed (timingLabel), '' before its first run. */
  mcTiming: string;
  monteCarlo: MonteCarloSummary | null;
  /** A preview (the models before the Monte Carlo's first run); absent at full quality. */
  refinement?: Refinement;
}

/** A photon count exactly, with thin spaces between groups of three digits (65 536). */
export const count = (n: number): string =>
  Math.round(n).toLocaleString('en-US').replace(/,/g, '\u2009');
const signed = (x: number, digits = 2): string =>
  `${x >= 0 ? '+' : '−'}${formatNumber(Math.abs(x), digits)}`;
const percent = (x: number): string =>
  `${x >= 0 ? '+' : '−'}${formatNumber(Math.abs(100 * x), 2)}%`;

function preset(name: string): Preset {
  const m = findMaterial(name)!;
  return { label: m.label, values: { material: name, ...materialValues(name)! } };
}

/** A Monte Carlo row: its value once a run exists ('…' before). */
function monteCarloRow(
  key: string,
  label: string,
  value: (summary: MonteCarloSummary, frame: DipoleFrame) => ReadoutValue,
) {
  return {
    key,
    label,
    format: (frame: DipoleFrame): ReadoutValue =>
      frame.monteCarlo ? value(frame.monteCarlo, frame) : '…',
  };
}

const modelError = (summary: MonteCarloSummary, model: 'dipole' | 'better'): string =>
  summary.channels
    .map((c) => `${percent(c[model].relative)} (${signed(c[model].z, 2)}σ)`)
    .join(' · ');

export const widget = defineWidget<DipoleFrame>({
  entry: DIPOLE_PROFILE,
  presets: [
    preset('skin1'),
    preset('marble'),
    preset('ketchup'),
    preset('wholemilk'),
    preset('skin2'),
    preset('apple'),
    preset('chicken1'),
  ],
  readouts: {
    rows: [
      monteCarloRow(
        'mc-photons',
        'Monte Carlo photons',
        (summary, { photons }) => `${count(photons)} per channel (${summary.batches} batches)`,
      ),
      monteCarloRow(
        'mc-time',
        'Monte Carlo time',
        (_, { mcMilliseconds, mcTiming }) => `${formatMilliseconds(mcMilliseconds)} (${mcTiming})`,
      ),
      monteCarloRow('mc-se', 'Monte Carlo SE of Rd (R · G · B)', (summary) =>
        summary.channels.map((c) => formatNumber(c.se, 2)).join(' · '),
      ),
      monteCarloRow('dipole-error', 'Dipole − MC (R · G · B)', (summary) =>
        modelError(summary, 'dipole'),
      ),
      monteCarloRow('better-error', 'Better dipole (one source) − MC', (summary) =>
        modelError(summary, 'better'),
      ),
      monteCarloRow('collisions', 'Collisions per photon', (summary) =>
        summary.channels.map((c) => formatNumber(c.collisionsPerPhoton, 3)).join(' · '),
      ),
      monteCarloRow('capped', 'Walks stopped by the cap', ({ capped, cappedWeight, cap }) => ({
        text:
          capped === 0
            ? `0 (cap ${cap} flights)`
            : `${capped}, holding up to ${formatNumber(100 * cappedWeight, 2)}% of the light`,
        state: capped === 0 ? 'ok' : 'bad',
      })),
      {
        key: 'curves-time',
        label: 'Diffusion profiles time',
        format: ({ curvesMilliseconds, curvesTiming }) =>
          `${formatMilliseconds(curvesMilliseconds)} (${timingLabel(curvesTiming)})`,
      },
    ],
    cost: ({ frameMilliseconds, curvesTiming }) => ({
      milliseconds: frameMilliseconds,
      timing: curvesTiming,
    }),
    costLine: (
      { inputs, curves, curvesMilliseconds, photons, mcMilliseconds, mcTiming },
      _how,
      backend,
    ) =>
      `${backend.kind === 'cpu' ? 'float64 twins, ' : ''}3 models × 3 channels × ${curves.radii.length} radii in ${formatMilliseconds(curvesMilliseconds)}; ${photons > 0 ? `Monte Carlo ${count(photons)} photons per channel in ${formatMilliseconds(mcMilliseconds)} (${mcTiming || '—'})` : 'the Monte Carlo’s first run follows'}, half-space, ${inputs.g > 0 ? `HG g = ${inputs.g}` : 'isotropic scattering'}, η = ${inputs.eta}.`,
  },
  slides: [
    {
      title: 'Skin: the dipole against Monte Carlo',
      attributes: {
        material: 'skin1',
      },
      caption:
        'R_d(r) per channel on log–log axes: red light travels millimetres, blue barely one. The dipole follows the Monte Carlo far from the beam and misses it within a mean free path; press More photons and watch the error bars shrink.',
      chapter: '11-subsurface-scattering',
    },
    {
      title: 'Colour bleeding: marble and ketchup',
      attributes: {
        material: 'ketchup',
        exposure: '1',
      },
      caption:
        'Ketchup absorbs green and blue within a millimetre and lets red wander a centimetre: the glow is red. Press 2 for marble, whose three channels spread alike into a broad white halo.',
      chapter: '11-subsurface-scattering',
    },
  ],
  load: () => import('./view.ts'),
});
