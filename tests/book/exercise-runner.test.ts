// The exercise widget's guards around the grading core (src/widgets/exercise/runner.ts):
// a run that never answers is abandoned by the watchdog, a run can be cancelled, a
// lost device is reported, a grader failure is told apart from the student's
// mistakes, and after any of these the next run gets a fresh device. The device and
// the grading function are fakes here; the real ones run in tests/e2e/exercise.spec.ts.
import { describe, expect, it } from 'vitest';
import { ExerciseRunner, type GradeFunction } from '../../src/widgets/exercise/runner.ts';
import type { GradeOutcome } from '../../src/grading/types.ts';

interface FakeDevice {
  device: GPUDevice;
  destroyed: () => boolean;
  lose: (message: string) => void;
}

function fakeDevice(): FakeDevice {
  let destroyed = false;
  let resolveLost: (info: GPUDeviceLostInfo) => void = () => undefined;
  const lost = new Promise<GPUDeviceLostInfo>((resolve) => (resolveLost = resolve));
  const device = {
    lost,
    destroy: () => {
      destroyed = true;
      resolveLost({ reason: 'destroyed', message: '' } as GPUDeviceLostInfo);
    },
  } as unknown as GPUDevice;
  return {
    device,
    destroyed: () => destroyed,
    lose: (message) => resolveLost({ reason: 'unknown', message } as GPUDeviceLostInfo),
  };
}

const GRADED: GradeOutcome = { status: 'graded', checks: [], score: 0, maxScore: 0, seed: 1 };
const never: GradeFunction = () => new Promise<GradeOutcome>(() => undefined);

function setup(): { runner: ExerciseRunner; devices: FakeDevice[] } {
  const devices: FakeDevice[] = [];
  const runner = new ExerciseRunner(() => {
    const fake = fakeDevice();
    devices.push(fake);
    return Promise.resolve(fake.device);
  }, 20);
  return { runner, devices };
}

const options = (signal = new AbortController().signal) => ({
  timeoutMs: 30,
  signal,
  onProgress: () => undefined,
});

describe('exercise runner guards', () => {
  it('passes the outcome through and keeps the device for the next run', async () => {
    const { runner, devices } = setup();
    let seen: string | undefined;
    const grade: GradeFunction = (_device, source, gradeOptions) => {
      seen = `${source}|${gradeOptions.which}|${gradeOptions.timeoutMs}`;
      return Promise.resolve(GRADED);
    };
    expect(await runner.run(grade, 'src', options())).toEqual(GRADED);
    expect(seen).toBe('src|public|30');
    await runner.run(grade, 'src', options());
    expect(devices).toHaveLength(1);
  });

  it('abandons a run that never answers, drops its device, and starts fresh', async () => {
    const { runner, devices } = setup();
    const outcome = await runner.run(never, 'src', options());
    expect(outcome.status).toBe('timeout');
    expect(outcome.status === 'timeout' && outcome.message).toMatch(/no answer within/);
    expect(devices[0]?.destroyed()).toBe(true);
    await runner.run(() => Promise.resolve(GRADED), 'src', options());
    expect(devices).toHaveLength(2);
  });

  it('cancels on request and tells the core to stop', async () => {
    const { runner, devices } = setup();
    const controller = new AbortController();
    let coreSignal: AbortSignal | undefined;
    const grade: GradeFunction = (_device, _source, gradeOptions) => {
      coreSignal = gradeOptions.signal;
      return new Promise<GradeOutcome>(() => undefined);
    };
    const pending = runner.run(grade, 'src', { ...options(controller.signal), timeoutMs: 10_000 });
    controller.abort();
    expect((await pending).status).toBe('cancelled');
    expect(coreSignal?.aborted).toBe(true);
    expect(devices[0]?.destroyed()).toBe(true);
  });

  it('reports a lost device, and a grader failure as the grader’s', async () => {
    const { runner, devices } = setup();
    const lost = runner.run(never, 'src', { ...options(), timeoutMs: 10_000 });
    await Promise.resolve();
    await Promise.resolve();
    devices[0]?.lose('out of bounds');
    const outcome = await lost;
    expect(outcome.status).toBe('device-lost');
    expect(outcome.status === 'device-lost' && outcome.message).toContain('out of bounds');
    const failed = await runner.run(
      () => Promise.reject(new Error('broken reference')),
      'src',
      options(),
    );
    expect(failed).toEqual({ status: 'error', message: 'broken reference' });
    // Each guarded failure dropped its device: the lost one, then the grader's.
    expect(devices).toHaveLength(2);
    expect(devices[1]?.destroyed()).toBe(true);
  });
});
