// The "Early termination saves" readout of <sb-transfer-function> (chapter 7), from a
// full-quality frame and, once measured, the time of the same frame with the other
// termination setting. GPU- and DOM-free, so that Vitest checks it.
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import type { FrameInputs, VolumeImage } from './model.ts';
import { formatCount } from './widget.ts';

/** Time with and without early termination for one full-quality frame (two frames each). */
export interface TerminationTimes {
  /** Milliseconds of the frame's own setting, and of the other one. */
  current: [number, number];
  other: [number, number];
  /** Steps the other setting took (the frame's own are in the frame). */
  otherSteps: number;
}

/** The share a part is of a whole, in per cent, to three digits ("0.00225%", "100%"). */
const percentOf = (part: number, whole: number): string =>
  `${formatNumber(whole > 0 ? (100 * part) / whole : 0, 3)}%`;

/**
 * What early termination saves, for this frame and nothing older (issue 17: the row kept
 * an old view's numbers until a reference finished, and quoted a 77 % time saving that
 * timing noise made up while 0.00225 % of the steps were saved). Steps come from the frame
 * itself with termination on (the kernel counts the steps each ray would take without
 * it), so they agree with "Steps taken"; time needs the other setting rendered
 * (`measured`, undefined while it runs), and a difference within the spread of repeated
 * frames is called timing noise rather than a saving.
 */
export function terminationSaving(
  frame: { inputs: Pick<FrameInputs, 'termination'>; image: VolumeImage },
  measured: TerminationTimes | undefined,
): string {
  const { inputs, image } = frame;
  const stepsOn = inputs.termination ? image.steps : measured?.otherSteps;
  const stepsOff = inputs.termination ? image.plannedSteps : image.steps;
  const steps =
    stepsOn === undefined
      ? 'steps: measuring…'
      : `${percentOf(stepsOff - stepsOn, stepsOff)} of the steps (${formatCount(stepsOff - stepsOn)} of ${formatCount(stepsOff)})`;
  if (!measured) return `${steps}; time: measuring…`;
  const on = inputs.termination ? measured.current : measured.other;
  const off = inputs.termination ? measured.other : measured.current;
  const best = (pair: [number, number]): number => Math.min(...pair);
  const spread = Math.max(Math.abs(on[0] - on[1]), Math.abs(off[0] - off[1]));
  const difference = best(off) - best(on);
  const times = `${formatMilliseconds(best(on))} with, ${formatMilliseconds(best(off))} without, best of 2 frames each`;
  const time =
    Math.abs(difference) <= spread
      ? `no time saved beyond the timing noise (${times}; frames vary by ${formatMilliseconds(spread)})`
      : `${percentOf(difference, best(off))} of the time (${times})`;
  return `${steps}; ${time}`;
}
