// The grading core on Dawn: the page's entry point (public checks by exercise id),
// compile errors at the student's line and column after instrumentation, endless
// loops, NaN, and the exercise folders' consistency (starter.wgsl = the starter the
// page shows; a statement per exercise).
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { EXERCISE_IDS, loadExercise } from '../../exercises/index.ts';
import { GradeStop, gradeSubmission, withDeviceGuards } from '../../src/grading/grade.ts';
import { EXERCISES_DIR, loadFullExercise } from '../../src/grading/node.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

describe('exercise folders', () => {
  it('have a statement, a starter equal to the page starter, and wrong submissions', async () => {
    for (const id of EXERCISE_IDS) {
      const exercise = await loadExercise(id);
      expect(exercise.id).toBe(id);
      const folder = join(EXERCISES_DIR, id);
      expect(readFileSync(join(folder, 'starter.wgsl'), 'utf8')).toBe(exercise.starter);
      expect(existsSync(join(folder, 'statement.md'))).toBe(true);
      expect(existsSync(join(folder, 'wrong', 'expected.json'))).toBe(true);
      expect(exercise.hiddenChecks).toBeUndefined();
    }
  });
});

describe('gradeSubmission', () => {
  it('runs only public checks when the page grades by id', async () => {
    const device = await nodeDevice();
    const outcome = await gradeSubmission(
      device,
      SHADER_LIBRARY,
      'beer-law',
      'fn transmittance(sigmaT: f32, d: f32) -> f32 { return exp(-max(sigmaT * d, 0.0)); }',
      { which: 'public', seed: 3 },
    );
    expect(outcome.status).toBe('graded');
    if (outcome.status !== 'graded') return;
    expect(outcome.checks.every((c) => c.visibility === 'public' && c.verdict === 'pass')).toBe(
      true,
    );
    expect(outcome.score).toBe(outcome.maxScore);
    expect(outcome.checks[0]?.figure?.kind).toBe('series');
  });

  it('reports compile errors at the student line and column, past the loop guard', async () => {
    const device = await nodeDevice();
    const source = [
      'fn transmittance(sigmaT: f32, d: f32) -> f32 {',
      '  var t = 1.0;',
      '  for (var i = 0; i < 3; i++) { t = t * undefinedName; }',
      '  return t;',
      '}',
    ].join('\n');
    const outcome = await gradeSubmission(device, SHADER_LIBRARY, 'beer-law', source, {
      which: 'public',
    });
    expect(outcome.status).toBe('compile-error');
    if (outcome.status !== 'compile-error') return;
    const error = outcome.diagnostics.find((d) => d.severity === 'error');
    expect(error?.line).toBe(3);
    expect(error?.column).toBe(source.split('\n')[2]!.indexOf('undefinedName') + 1);
  });

  it('stops an endless loop and fails NaN with a clear message', async () => {
    const device = await nodeDevice();
    const endless = await gradeSubmission(
      device,
      SHADER_LIBRARY,
      'raymarch-exact',
      'fn marchTransmittance(sigma0: f32, amplitude: f32, d: f32, steps: u32) -> f32 {\n  var t = 0.0;\n  while (t < d) { t = t * 2.0; }\n  return 1.0;\n}',
      { which: 'public' },
    );
    expect(endless.status).toBe('loop-budget');
    const nan = await gradeSubmission(
      device,
      SHADER_LIBRARY,
      'hg-eval',
      'fn hgPhase(g: f32, mu: f32) -> f32 { return sqrt(mu - 2.0); }',
      { which: 'public' },
    );
    expect(nan.status).toBe('graded');
    if (nan.status === 'graded') expect(nan.checks[0]?.message).toContain('NaN');
  });

  it('fails only the check whose loop overran, without leaking hidden arguments', async () => {
    const device = await nodeDevice();
    // Loops forever only when the majorant is 0 (the hidden "Majorant of zero" check).
    const source = [
      'fn deltaTracking(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, state: ptr<function, u32>) -> f32 {',
      '  var t = 0.0;',
      '  loop {',
      '    if (sigmaMaj <= 0.0) { continue; }',
      '    t += -log(1.0 - rngNextFloat(state)) / sigmaMaj;',
      '    if (t >= d) { return 1.0; }',
      '    if (rngNextFloat(state) * sigmaMaj < extinction(sigma0, amplitude, t)) { return 0.0; }',
      '  }',
      '}',
    ].join('\n');
    const exercise = await loadFullExercise('delta-tracking');
    const outcome = await gradeSubmission(device, SHADER_LIBRARY, exercise, source, {
      which: 'all',
    });
    expect(outcome.status).toBe('graded');
    if (outcome.status !== 'graded') return;
    const failed = outcome.checks.filter((c) => c.verdict === 'fail');
    expect(failed).toHaveLength(1);
    expect(failed[0]?.visibility).toBe('hidden');
    expect(failed[0]?.points).toBe(0);
    expect(failed[0]?.message).toContain('ran past its budget of 4096 iterations');
    expect(failed[0]?.message).not.toContain('arguments');
    expect(outcome.score).toBe(outcome.maxScore - (failed[0]?.maxPoints ?? 0));
  });

  it('names the expected signature when the function is missing', async () => {
    const device = await nodeDevice();
    const outcome = await gradeSubmission(
      device,
      SHADER_LIBRARY,
      'hg-eval',
      'fn phase(g: f32, mu: f32) -> f32 { return 0.0; }',
      { which: 'public' },
    );
    expect(outcome.status).toBe('wrong-signature');
    if (outcome.status === 'wrong-signature')
      expect(outcome.message).toContain('fn hgPhase(g: f32, mu: f32) -> f32');
  });
});

describe('the watchdog', () => {
  const never = new Promise<never>(() => {});
  it('turns a GPU wait that never ends into a timeout outcome', async () => {
    const device = { lost: never } as unknown as GPUDevice;
    const error = await withDeviceGuards(device, 5, 'running a check', never).catch(
      (e: unknown) => e,
    );
    expect(error).toBeInstanceOf(GradeStop);
    expect((error as GradeStop).outcome.status).toBe('timeout');
  });

  it('turns device loss into a device-lost outcome', async () => {
    const device = {
      lost: Promise.resolve({ reason: 'unknown', message: 'simulated loss' }),
    } as unknown as GPUDevice;
    const error = await withDeviceGuards(device, 10_000, 'running a check', never).catch(
      (e: unknown) => e,
    );
    expect((error as GradeStop).outcome.status).toBe('device-lost');
    expect((error as GradeStop).outcome.message).toContain('simulated loss');
  });

  it('passes results through and says which imports are not available', async () => {
    const device = { lost: never } as unknown as GPUDevice;
    await expect(withDeviceGuards(device, 10_000, 'x', Promise.resolve(7))).resolves.toBe(7);
    const gpu = await nodeDevice();
    const outcome = await gradeSubmission(
      gpu,
      SHADER_LIBRARY,
      'beer-law',
      'import package::transmittance::transmittanceHomogeneous;\nfn transmittance(sigmaT: f32, d: f32) -> f32 { return transmittanceHomogeneous(sigmaT, d); }',
      { which: 'public' },
    );
    expect(outcome.status).toBe('compile-error');
    if (outcome.status === 'compile-error') {
      expect(outcome.message).toContain('Imports other than the helpers');
      expect(outcome.diagnostics[0]?.line).toBe(2);
    }
  });
});
