// The compute queue and cache (src/workers/compute.ts) on its in-page path (Node has no
// Worker): results cached by arguments, one run per parameter set, abandoned queued
// jobs dropped, failures not cached. The job table is mocked; the widgets' own jobs.ts
// are tested with their twins.
import { beforeEach, describe, expect, it, vi } from 'vitest';

const calls: string[] = [];
let release: (() => void) | null = null;

vi.mock('../../src/workers/jobs.ts', () => ({
  runJob: async (widget: string, name: string, args: readonly unknown[]) => {
    calls.push(`${widget}/${name}:${JSON.stringify(args)}`);
    if (name === 'fail') throw new Error('no such medium');
    if (name === 'slow') await new Promise<void>((resolve) => (release = resolve));
    return { sum: (args as number[]).reduce((a, b) => a + b, 0), data: new Float64Array([1, 2]) };
  },
}));

const { workerJobs, cacheKey } = await import('../../src/workers/compute.ts');

type Jobs = {
  add: (...values: number[]) => { sum: number; data: Float64Array };
  slow: (value: number) => { sum: number };
  fail: () => never;
};

beforeEach(() => {
  calls.length = 0;
  release = null;
});

describe('workerJobs (in-page fallback)', () => {
  it('computes once per argument list and serves the cache afterwards', async () => {
    const jobs = workerJobs<Jobs>('test-widget');
    const [a, b] = await Promise.all([jobs.run('add', [1, 2]), jobs.run('add', [1, 2])]);
    expect(a.sum).toBe(3);
    expect(b).toBe(a);
    expect(await jobs.run('add', [1, 2])).toBe(a);
    expect(jobs.cached('add', [1, 2])).toBe(a);
    expect(jobs.cached('add', [2, 1])).toBeUndefined();
    expect(calls).toEqual(['test-widget/add:[1,2]']);
  });

  it('drops a queued job whose callers all aborted, and rejects them with AbortError', async () => {
    const jobs = workerJobs<Jobs>('test-widget');
    const running = jobs.run('slow', [1]);
    await vi.waitFor(() => expect(release).not.toBeNull());
    const aborter = new AbortController();
    const stale = jobs.run('add', [5, 5], { signal: aborter.signal });
    aborter.abort();
    await expect(stale).rejects.toMatchObject({ name: 'AbortError' });
    const wanted = jobs.run('add', [7, 7]);
    release!();
    await running;
    expect((await wanted).sum).toBe(14);
    expect(calls).toEqual(['test-widget/slow:[1]', 'test-widget/add:[7,7]']);
  });

  it('does not cache a failure', async () => {
    const jobs = workerJobs<Jobs>('test-widget');
    await expect(jobs.run('fail', [])).rejects.toThrow('no such medium');
    await expect(jobs.run('fail', [])).rejects.toThrow('no such medium');
    expect(calls).toHaveLength(2);
  });

  it('evicts the least recently used results beyond its size', async () => {
    const jobs = workerJobs<Jobs>('test-widget', 2);
    await jobs.run('add', [1]);
    await jobs.run('add', [2]);
    await jobs.run('add', [1]); // touch [1]: [2] is now the oldest
    await jobs.run('add', [3]);
    expect(jobs.cached('add', [1])).toBeDefined();
    expect(jobs.cached('add', [2])).toBeUndefined();
  });

  it('keys typed arrays by their values', () => {
    expect(cacheKey('f', [new Float32Array([1, 2])])).toBe(cacheKey('f', [[1, 2]]));
    expect(cacheKey('f', [{ a: 1 }])).not.toBe(cacheKey('g', [{ a: 1 }]));
  });
});
