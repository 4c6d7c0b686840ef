// Red-team submissions that need the GPU (Dawn on SwiftShader): a submission whose
// loops stay within their budget but whose calls do far too much work must end as the
// student's outcome, not as a grader-side timeout that asks for a regrade forever.
import { describe, expect, it } from 'vitest';
import { gradeSubmission } from '../../src/grading/grade.ts';
import { isGraderSideFailure } from '../../src/grading/types.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

/** 200 iterations (within the budget of 4096) of 64 dependent sines, then delta tracking. */
const HEAVY = `fn waste(x: f32) -> f32 {
  var y = x;
${'  y = sin(y) * 1.0001 + 0.5;\n'.repeat(64)}  return y;
}
fn deltaTracking(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, state: ptr<function, u32>) -> f32 {
  var acc = sigma0;
  for (var i = 0u; i < 200u; i++) { acc = waste(acc); }
  if (sigmaMaj <= 0.0 || acc > 1e30) { return 1.0; }
  var t = 0.0;
  loop {
    t -= log(1.0 - rngNextFloat(state)) / sigmaMaj;
    if (t >= d) { return 1.0; }
    if (rngNextFloat(state) * sigmaMaj < extinction(sigma0, amplitude, t)) { return 0.0; }
  }
}
`;

describe('work within the loop budget but past the watchdog', () => {
  it("is the student's loop-budget outcome, not a grader-side timeout", async () => {
    const device = await nodeDevice();
    // 65,536 calls × 12,800 dependent sines (8.4e8): far past a 1 s watchdog on SwiftShader.
    const outcome = await gradeSubmission(device, SHADER_LIBRARY, 'delta-tracking', HEAVY, {
      which: 'public',
      timeoutMs: 1000,
      seed: 1,
    });
    expect(isGraderSideFailure(outcome)).toBe(false);
    expect(outcome.status).toBe('loop-budget');
    expect(outcome.status !== 'graded' && outcome.message).toMatch(
      /did not finish 65536 calls within 1\.0 s/,
    );
    // The abandoned dispatch still runs (about 15 s of SwiftShader on two cores); wait
    // for it here so that releasing the shared device after the file does not time out.
    await device.queue.onSubmittedWorkDone();
  }, 120_000);
});
