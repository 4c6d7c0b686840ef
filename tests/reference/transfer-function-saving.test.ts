// The "Early termination saves" readout (src/widgets/transfer-function/saving.ts, issue 17):
// the steps agree with the frame's own counts, the time is reported only once measured,
// and a time difference within the spread of repeated frames is not called a saving.
import { describe, expect, it } from 'vitest';
import { emptyImage } from '../../src/widgets/transfer-function/model.ts';
import { terminationSaving } from '../../src/widgets/transfer-function/saving.ts';

function image(steps: number, plannedSteps: number) {
  return { ...emptyImage(4, new Float32Array(48)), steps, plannedSteps };
}

describe('terminationSaving', () => {
  it('reads the steps saved from the frame with termination on, before any timing', () => {
    const text = terminationSaving(
      { inputs: { termination: true }, image: image(600, 2400) },
      undefined,
    );
    expect(text).toBe('75% of the steps (1800 of 2400); time: measuring…');
  });

  it('with termination off, waits for the other setting for the steps as well', () => {
    const frame = { inputs: { termination: false }, image: image(2400, 2400) };
    expect(terminationSaving(frame, undefined)).toBe('steps: measuring…; time: measuring…');
    const text = terminationSaving(frame, {
      current: [100, 104],
      other: [40, 41],
      otherSteps: 600,
    });
    expect(text).toMatch(
      /^75% of the steps \(1800 of 2400\); 60% of the time \(40\.0 ms with, 100\.0 ms without/,
    );
  });

  it('calls a difference within the frames’ own spread timing noise, not a saving', () => {
    // Issue 17's case: 0.00225 % of the steps saved, and timings that jump between frames.
    const frame = { inputs: { termination: true }, image: image(44_399_001, 44_400_000) };
    const text = terminationSaving(frame, {
      current: [300, 900],
      other: [820, 1300],
      otherSteps: 44_400_000,
    });
    expect(text).toMatch(/^0\.00225% of the steps/);
    expect(text).toMatch(
      /no time saved beyond the timing noise \(300\.0 ms with, 820\.0 ms without/,
    );
    expect(text).not.toMatch(/of the time/);
  });
});
