// The CPU fallback's rows in the compute worker (issue 23): a band of the `rows` job is
// exactly the same rows of the whole-image float64 twin, with their statistics, so the
// page's picture does not change by being marched in chunks.
import { describe, expect, it } from 'vitest';
import { parseParameters } from '../../src/widgets/parameters.ts';
import { chunkRows } from '../../src/widgets/transfer-function/cpuBackend.ts';
import { jobs, rowsScene } from '../../src/widgets/transfer-function/jobs.ts';
import { inputsFrom, renderImageCpu } from '../../src/widgets/transfer-function/model.ts';
import { TRANSFER_FUNCTION } from '../../src/widgets/transfer-function/schema.ts';

describe('transfer-function rows job', () => {
  const { values } = parseParameters(TRANSFER_FUNCTION.parameters, () => undefined);
  const inputs = { ...inputsFrom(values), azimuth: 30, elevation: 10 };
  const size = 16;

  it('a band equals the same rows of the whole image, statistics included', () => {
    const whole = renderImageCpu(size, inputs, 1, 0.01);
    const pixels = size * size;
    let steps = 0;
    let planned = 0;
    for (const [start, end] of [
      [0, 5],
      [5, 12],
      [12, 16],
    ] as const) {
      const band = jobs.rows(rowsScene(inputs), size, 1, 0.01, start, end);
      const bandPixels = (end - start) * size;
      expect(band.rows).toBe(end - start);
      for (let c = 0; c < 3; c++)
        expect(Array.from(band.rgb.subarray(c * bandPixels, (c + 1) * bandPixels))).toEqual(
          Array.from(whole.rgb.subarray(c * pixels + start * size, c * pixels + end * size)),
        );
      expect(Array.from(band.stepsPerPixel)).toEqual(
        Array.from(whole.stepsPerPixel.subarray(start * size, end * size)),
      );
      steps += band.steps;
      planned += band.plannedSteps;
    }
    expect(steps).toBe(whole.steps);
    expect(planned).toBe(whole.plannedSteps);
  });

  it('a band past the image ends at its last row', () => {
    expect(jobs.rows(rowsScene(inputs), size, 1, 0, 12, 40).rows).toBe(4);
  });

  it('chunks hold about the same marching whatever the step: ⌊8·Δs⌋ rows, 1 to 16', () => {
    expect(chunkRows(1 / 8)).toBe(1);
    expect(chunkRows(1)).toBe(8);
    expect(chunkRows(0.5)).toBe(4);
    expect(chunkRows(4)).toBe(16);
  });
});
