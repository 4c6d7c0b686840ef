// Hostile submissions against the grading core on Dawn: every one ends in an outcome
// (never a thrown Error), refusals say where, a BOM + CR LF file keeps the student's
// line and column, and an exception inside the grader becomes 'internal-error'
// without naming a hidden check.
import { describe, expect, it } from 'vitest';
import { gradeReference, gradeSubmission } from '../../src/grading/grade.ts';
import { loadFullExercise } from '../../src/grading/node.ts';
import type { CheckSpec, ExerciseDefinition } from '../../src/grading/exercise.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

const CORRECT =
  'fn transmittance(sigmaT: f32, d: f32) -> f32 { return exp(-max(sigmaT * d, 0.0)); }';

describe('hostile submissions end in an outcome', () => {
  it('refuses a binding of its own with the line and column, before compiling', async () => {
    const device = await nodeDevice();
    const source = [
      'fn transmittance(sigmaT: f32, d: f32) -> f32 {',
      '  leak[0] = 1u;',
      '  return 1.0;',
      '}',
      '  @group(0) @binding(2) var<storage, read_write> leak: array<u32>;',
    ].join('\n');
    const outcome = await gradeSubmission(device, SHADER_LIBRARY, 'beer-law', source, {
      which: 'public',
    });
    expect(outcome.status).toBe('rejected');
    if (outcome.status === 'rejected') {
      expect(outcome.message).toContain('line 5, column 3: `@group`');
      expect(outcome.message).toContain('line 5, column 13: `@binding`');
    }
  });

  it('maps a compile error of a BOM + CR LF file to the line and column the student sees', async () => {
    const device = await nodeDevice();
    const lines = [
      'fn transmittance(sigmaT: f32, d: f32) -> f32 {',
      '  var t = 1.0;',
      '  for (var i = 0; i < 3; i++) { t = t * undefinedName; }',
      '  return t;',
      '}',
    ];
    const outcome = await gradeSubmission(
      device,
      SHADER_LIBRARY,
      'beer-law',
      `\ufeff${lines.join('\r\n')}\r\n`,
      { which: 'public' },
    );
    expect(outcome.status).toBe('compile-error');
    if (outcome.status !== 'compile-error') return;
    const error = outcome.diagnostics.find((d) => d.severity === 'error');
    expect(error?.line).toBe(3);
    expect(error?.column).toBe((lines[2] ?? '').indexOf('undefinedName') + 1);
  });

  it('grades a correct solution saved with a BOM and CR LF like any other', async () => {
    const device = await nodeDevice();
    const outcome = await gradeSubmission(
      device,
      SHADER_LIBRARY,
      'beer-law',
      `\ufeff// Windows\r\n${CORRECT}\r\n`,
      { which: 'public', seed: 5 },
    );
    expect(outcome.status).toBe('graded');
    if (outcome.status === 'graded') expect(outcome.score).toBe(outcome.maxScore);
  });

  it('bounds an endless loop hidden behind a CR-ended comment', async () => {
    const device = await nodeDevice();
    const outcome = await gradeSubmission(
      device,
      SHADER_LIBRARY,
      'beer-law',
      'fn transmittance(sigmaT: f32, d: f32) -> f32 {\n  // hidden?\r  loop { }\n}\n',
      { which: 'public' },
    );
    expect(outcome.status).toBe('loop-budget');
  });

  it('turns workgroup memory past the device limit into an outcome, not a throw', async () => {
    const device = await nodeDevice();
    const outcome = await gradeSubmission(
      device,
      SHADER_LIBRARY,
      'beer-law',
      'var<workgroup> big: array<f32, 1000000>;\n' +
        'fn transmittance(sigmaT: f32, d: f32) -> f32 { big[0] = d; return exp(-max(sigmaT * big[0], 0.0)); }',
      { which: 'public' },
    );
    expect(['compile-error', 'rejected']).toContain(outcome.status);
  });
});

describe('grader-side failures are outcomes', () => {
  it('reports an unknown exercise as internal-error instead of throwing', async () => {
    const device = await nodeDevice();
    const outcome = await gradeSubmission(device, SHADER_LIBRARY, 'no-such-exercise', CORRECT, {
      which: 'public',
    });
    expect(outcome.status).toBe('internal-error');
    if (outcome.status === 'internal-error') expect(outcome.message).toContain('no-such-exercise');
  });

  it('turns a bind-group validation error of the dispatch into an outcome, not a thrown Error', async () => {
    // A reference with a binding of its own: the pipeline's 'auto' layout then wants a
    // binding the harness's bind group lacks, and the device refuses the dispatch.
    const device = await nodeDevice();
    const exercise = await loadFullExercise('beer-law');
    const outcome = await gradeReference(
      device,
      SHADER_LIBRARY,
      {
        ...exercise,
        reference:
          '@group(0) @binding(2) var<storage, read_write> extra: array<f32>;\n' +
          'fn transmittance(sigmaT: f32, d: f32) -> f32 { extra[0] = d; return exp(-sigmaT * d); }',
      },
      { which: 'public' },
    );
    expect(outcome.status).toBe('internal-error');
    if (outcome.status === 'internal-error') expect(outcome.message).toContain('validation');
  });

  it('turns an exception in a hidden check into internal-error without naming the check', async () => {
    const device = await nodeDevice();
    const exercise = await loadFullExercise('beer-law');
    const secret = 'Secret hidden case';
    const broken = {
      kind: 'cases',
      name: secret,
      points: 1,
      message: 'x',
      rtol: 0,
      atol: 0,
      get cases(): never {
        throw new Error(`broken check "${secret}"`);
      },
    } as unknown as CheckSpec;
    const definition: ExerciseDefinition = { ...exercise, hiddenChecks: [broken] };
    const outcome = await gradeSubmission(device, SHADER_LIBRARY, definition, CORRECT, {
      which: 'all',
    });
    expect(outcome.status).toBe('internal-error');
    if (outcome.status !== 'internal-error') return;
    expect(outcome.message).not.toContain(secret);
    expect(outcome.message).toContain('a hidden check');
  });
});
