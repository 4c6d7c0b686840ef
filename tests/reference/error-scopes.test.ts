// withErrorScopes (src/gpu/errors.ts) with a fake device whose error scopes behave as
// WebGPU's do: a stack, an error caught by the innermost scope of its filter, and each
// pop answered asynchronously. Guarded calls made side by side (two renderers created
// with Promise.all) must each get their own errors, and the three pops of one call must
// go out together (one round trip to the GPU process, not three).
import { describe, expect, it } from 'vitest';
import { GpuError, withErrorScopes } from '../../src/gpu/errors.ts';

interface Scope {
  filter: GPUErrorFilter;
  error: GPUError | null;
}

/** The parts of GPUDevice that withErrorScopes uses, as a WebGPU implementation keeps them. */
class FakeDevice {
  readonly stack: Scope[] = [];
  /** Pops asked for and not yet answered, at the moment of each pop. */
  inFlight = 0;
  largestInFlight = 0;

  pushErrorScope(filter: GPUErrorFilter): void {
    this.stack.push({ filter, error: null });
  }

  popErrorScope(): Promise<GPUError | null> {
    const scope = this.stack.pop();
    if (!scope) return Promise.reject(new DOMException('no scope', 'OperationError'));
    this.inFlight += 1;
    this.largestInFlight = Math.max(this.largestInFlight, this.inFlight);
    // Answered a few ticks later, as the GPU process does.
    return new Promise((resolve) =>
      setTimeout(() => {
        this.inFlight -= 1;
        resolve(scope.error);
      }, 1),
    );
  }

  /** An error raised by a call in the body: caught by the innermost scope of its filter. */
  raise(filter: GPUErrorFilter, message: string): void {
    const scope = this.stack.findLast((s) => s.filter === filter);
    if (scope && !scope.error) scope.error = { message } as GPUError;
  }
}

const asDevice = (fake: FakeDevice): GPUDevice => fake as unknown as GPUDevice;

describe('withErrorScopes', () => {
  it('returns the body’s value and leaves the scope stack balanced', async () => {
    const fake = new FakeDevice();
    await expect(withErrorScopes(asDevice(fake), 'ok', () => 42)).resolves.toBe(42);
    expect(fake.stack).toHaveLength(0);
  });

  it('throws the body’s error with its kind', async () => {
    const fake = new FakeDevice();
    const failing = withErrorScopes(asDevice(fake), 'upload', () =>
      fake.raise('out-of-memory', 'no room'),
    );
    await expect(failing).rejects.toThrow(GpuError);
    await expect(failing).rejects.toMatchObject({ kind: 'out-of-memory', detail: 'no room' });
    expect(fake.stack).toHaveLength(0);
  });

  it('keeps the errors of calls made side by side apart, whatever their kind', async () => {
    for (const kind of ['validation', 'out-of-memory', 'internal'] as const) {
      const fake = new FakeDevice();
      const device = asDevice(fake);
      // A starts, then B starts while A's pops are unanswered; only B's body fails.
      const a = withErrorScopes(device, 'A', () => 'a');
      const b = withErrorScopes(device, 'B', () => fake.raise(kind, `B's ${kind}`));
      const c = withErrorScopes(device, 'C', () => 'c');
      await expect(a).resolves.toBe('a');
      await expect(b).rejects.toMatchObject({ what: 'B', kind, detail: `B's ${kind}` });
      await expect(c).resolves.toBe('c');
      expect(fake.stack).toHaveLength(0);
    }
  });

  it('asks for the three pops together, before awaiting any', async () => {
    const fake = new FakeDevice();
    await withErrorScopes(asDevice(fake), 'one', () => undefined);
    expect(fake.largestInFlight).toBe(3);
  });
});
