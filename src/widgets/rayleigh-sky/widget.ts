// <sb-rayleigh-sky>: why the sky is blue and sunsets red (chapter 3). Draws a
// panorama toward the sun on the GPU, one single-scattering march per pixel,
// evaluates three probe directions and the direct sun in a compute pass, and shows
// them next to a converged float64 reference (cached once per sun elevation) with
// the relative error and the GPU time of the panorama (timestamp queries, median
// over frames). A cancellable sweep over N plots the probes' relative RMS error
// against that time and fits the order of convergence.
import { defineWidget } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel, type GpuTiming } from '../base/timing.ts';
import { RAYLEIGH_SKY } from './schema.ts';
import { CANVAS_HEIGHT, CANVAS_WIDTH, FIT_FROM_STEPS, REFERENCE_STEPS } from './constants.ts';
import type { Refinement } from '../base/refinement.ts';
import type { Rgb, SkyInputs, SkyProbes } from './model.ts';

export type SkyTiming = GpuTiming | 'cpu';

/** The CPU fallback refines the panorama up to 1/CPU_SCALE of the canvas's resolution. */
export const CPU_SCALE = 4;

/** Probe keys in probesFor order, and the readout each one fills. */
const PROBE_KEYS = ['zenith', 'toward', 'away'] as const;

/** One frame: the backend's probes and their cost, the picture's cost, and the cached reference. */
export interface RayleighSkyFrame {
  inputs: SkyInputs;
  probes: SkyProbes;
  /** Time of one evaluation of the probes (ms); 0 when under the GPU timer's resolution. */
  probeMilliseconds: number;
  probeTiming: SkyTiming;
  /** Evaluations the CPU time is a mean over (1 on the GPU). */
  probeRepeats: number;
  capped: boolean;
  picture: {
    /** This frame's resolution: a refinement stage draws fewer pixels than the canvas's full 640×480. */
    width: number;
    height: number;
    /** This frame's time per panorama (ms), the frame's recorded cost. */
    lastMilliseconds: number;
    /** Median time per panorama over the last `frames` frames at this N (ms). */
    milliseconds: number;
    frames: number;
    /** Passes per timed submit (more than 1 when one panorama is under the timer's resolution). */
    passes: number;
    timing: SkyTiming;
  };
  /** Relative error of each probe against the cached float64 reference (null: no light); null while a preview's reference is still being computed. */
  errors: (number | null)[] | null;
  /** Relative RMS error of the probes (null: no light, or no reference yet). */
  rms: number | null;
  /** Which refinement stage the picture is (the probes are always at the reader's N and M). */
  stage: Refinement & { final: boolean };
}

function formatRgb(rgb: Rgb, digits = 4): string {
  return rgb.map((v) => formatNumber(v, digits)).join(', ');
}

function formatPercent(error: number | null): string {
  if (error === null) return '0 (exact: no light)';
  return `${formatNumber(100 * error, 3)}%`;
}

function probeRow(k: number) {
  return {
    key: PROBE_KEYS[k]!,
    format: ({ probes }: RayleighSkyFrame) => formatRgb(probes.radiance[k]!),
  };
}

function errorText({ errors, rms }: RayleighSkyFrame): string {
  if (errors === null) return 'computing the float64 reference…';
  const worst = errors.reduce<number | null>(
    (a, b) => (b === null ? a : Math.max(a ?? 0, b)),
    null,
  );
  return (
    `${formatPercent(worst)} (zenith ${formatPercent(errors[0]!)}, toward ${formatPercent(errors[1]!)}, away ${formatPercent(errors[2]!)})` +
    (rms === null ? '' : `; relative RMS ${formatPercent(rms)}`)
  );
}

/**
 * The probe pass's cost. A GPU timestamp is quantized (100 µs in Chrome), so a pass
 * shorter than that can read 0: it is said to be under the timer's resolution, not 0.
 */
function probeCost(milliseconds: number, timing: SkyTiming): string {
  return milliseconds > 0
    ? `probes in ${formatMilliseconds(milliseconds)} (${timingLabel(timing)})`
    : `probes under the timer's resolution (${timingLabel(timing)} reads 0)`;
}

export const widget = defineWidget<RayleighSkyFrame>({
  entry: RAYLEIGH_SKY,
  presets: [
    { label: 'noon', values: { 'sun-elevation': 60, scattering: 'on' } },
    { label: 'afternoon', values: { 'sun-elevation': 20, scattering: 'on' } },
    { label: 'sunset', values: { 'sun-elevation': 2, scattering: 'on' } },
    { label: 'no scattering', values: { 'sun-elevation': 30, scattering: 'off' } },
  ],
  readouts: {
    rows: [
      { ...probeRow(0), label: 'Zenith radiance L (R, G, B), sr⁻¹' },
      { ...probeRow(1), label: '10° up, toward the sun' },
      { ...probeRow(2), label: '10° up, away from the sun' },
      {
        key: 'error',
        label: `Relative error vs float64, N = M = ${REFERENCE_STEPS}`,
        format: errorText,
      },
      {
        key: 'sun',
        label: 'Direct sunlight T_sun (R, G, B)',
        format: ({ probes: { sunTransmittance: sun } }) =>
          sun.every((t) => t === 0) ? '0, 0, 0 (the sun has set)' : formatRgb(sun),
      },
      {
        key: 'zenith-ratio',
        label: 'Zenith blue/red, L_B/L_R',
        format: ({ probes }) => {
          const zenith = probes.radiance[0]!;
          return zenith[0] > 0
            ? formatNumber(zenith[2] / zenith[0], 4)
            : 'no sky light (scattering off)';
        },
      },
      {
        key: 'sun-ratio',
        label: 'Direct sun red/blue, T_R/T_B',
        format: ({ probes: { sunTransmittance: sun } }) =>
          sun[2] > 0 ? formatNumber(sun[0] / sun[2], 4) : 'no direct sun',
      },
      // The sweep's rows are the view's to write (context.setReadout).
      {
        key: 'slope',
        label: `Sweep: error ∝ N^p (fit over N ≥ ${FIT_FROM_STEPS})`,
        initial: 'run the sweep',
      },
      { key: 'time-slope', label: 'Sweep: error ∝ time^q, time ∝ N^a', initial: 'run the sweep' },
    ],
    cost: ({ picture }) => ({ milliseconds: picture.lastMilliseconds, timing: picture.timing }),
    costLine: ({ inputs, picture, probeMilliseconds, probeTiming, probeRepeats }, how, backend) => {
      const size = `${picture.width}×${picture.height}`;
      const work = `N = ${inputs.steps} view samples × M = ${inputs.sunSteps} sun samples per pixel`;
      const frames = `median of ${picture.frames} frame${picture.frames === 1 ? '' : 's'} at this N`;
      const passes =
        picture.passes > 1 ? `, each timed over ${picture.passes} passes in one submit` : '';
      const referenceNote = `Reference: float64, N = M = ${REFERENCE_STEPS}, computed once per sun elevation and cached.`;
      return backend.kind === 'gpu'
        ? `panorama ${size}${picture.width < CANVAS_WIDTH ? ` of ${CANVAS_WIDTH}×${CANVAS_HEIGHT}` : ''}, ${work}, in ${formatMilliseconds(picture.milliseconds)} per frame (${how}, ${frames}${passes}); ${probeCost(probeMilliseconds, probeTiming)}. ${referenceNote}`
        : `panorama ${size}${picture.width < CANVAS_WIDTH / CPU_SCALE ? ` of ${CANVAS_WIDTH / CPU_SCALE}×${CANVAS_HEIGHT / CPU_SCALE}` : ''}, ${work}, in ${formatMilliseconds(picture.milliseconds)} per frame (${how}, ${frames}, in a worker); probes in ${formatMilliseconds(probeMilliseconds)} each (${timingLabel('cpu')}, float64 twin, mean over ${probeRepeats} evaluations). ${referenceNote}`;
    },
  },
  slides: [
    {
      title: 'Why the sky is blue',
      attributes: {
        'sun-elevation': '60',
        scattering: 'on',
        steps: '32',
        exposure: '0',
      },
      caption:
        'Skylight is sunlight scattered once by air molecules, and σs ∝ λ⁻⁴: at noon the zenith has 4.5 times more blue than red.',
      chapter: '03-phase-functions-and-in-scattering',
    },
    {
      title: 'Why sunsets are red',
      attributes: {
        'sun-elevation': '2',
        scattering: 'on',
        steps: '32',
        exposure: '1',
      },
      caption:
        'At 2° the sunlight crosses about 19 times the air of the vertical path, and Beer’s law removes the blue first: T_sun ≈ (0.42, 0.13, 0.007).',
      chapter: '03-phase-functions-and-in-scattering',
    },
    {
      title: 'The sky’s accuracy against its cost',
      attributes: {
        'sun-elevation': '20',
        scattering: 'on',
        steps: '8',
        exposure: '0',
      },
      caption:
        'Run the sweep: the error falls as N⁻², but each view sample also marches N/4 sun samples, so against GPU time it falls more slowly, with a slope between −2 and −1.',
      chapter: '03-phase-functions-and-in-scattering',
    },
  ],
  deckOrder: 1,
  load: () => import('./view.ts'),
});
