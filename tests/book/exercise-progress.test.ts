// The exercise widget's saved progress (src/widgets/exercise/progress.ts): what a
// reload restores, and what an imported progress file must look like, with every
// problem reported in words.
import { describe, expect, it } from 'vitest';
import {
  PROGRESS_FORMAT,
  PROGRESS_VERSION,
  collectProgress,
  loadProgress,
  parseProgressFile,
  saveProgress,
  summarizeOutcome,
  type KeyValueStore,
} from '../../src/widgets/exercise/progress.ts';

function memoryStore(): KeyValueStore & { map: Map<string, string> } {
  const map = new Map<string, string>();
  return {
    map,
    getItem: (key) => map.get(key) ?? null,
    setItem: (key, value) => void map.set(key, value),
    get length() {
      return map.size;
    },
    key: (index) => [...map.keys()][index] ?? null,
  };
}

const AT = new Date('2026-11-23T12:00:00Z');

describe('exercise progress', () => {
  it('summarizes an outcome: public checks passed and points; failures score 0', () => {
    const graded = summarizeOutcome(
      {
        status: 'graded',
        seed: 7,
        score: 3,
        maxScore: 5,
        checks: [
          {
            name: 'a',
            visibility: 'public',
            verdict: 'pass',
            points: 3,
            maxPoints: 3,
            message: '',
          },
          {
            name: 'b',
            visibility: 'public',
            verdict: 'fail',
            points: 0,
            maxPoints: 2,
            message: '',
          },
        ],
      },
      AT,
    );
    expect(graded).toEqual({
      status: 'graded',
      score: 3,
      maxScore: 5,
      passed: 1,
      total: 2,
      at: '2026-11-23T12:00:00.000Z',
    });
    expect(summarizeOutcome({ status: 'loop-budget', message: 'x' }, AT)).toMatchObject({
      status: 'loop-budget',
      score: 0,
      total: 0,
    });
  });

  it('saves, reloads and exports every exercise; ignores other keys and corrupt entries', () => {
    const store = memoryStore();
    saveProgress(store, 'beer-law', { code: 'fn f() {}', hintsShown: 1, result: null });
    store.setItem('scatterbook:theme', 'dark');
    store.setItem('scatterbook:exercise:hg-eval', '{not json');
    expect(loadProgress(store, 'beer-law')?.code).toBe('fn f() {}');
    expect(loadProgress(store, 'hg-eval')).toBeNull();
    const file = collectProgress(store, AT);
    expect(file.format).toBe(PROGRESS_FORMAT);
    expect(Object.keys(file.exercises)).toEqual(['beer-law']);
    const parsed = parseProgressFile(JSON.stringify(file), ['beer-law', 'hg-eval']);
    expect(parsed).toMatchObject({ ok: true, unknownIds: [] });
  });

  it('rejects files that are not progress files, with clear reasons', () => {
    const ids = ['beer-law'];
    const bad = (text: string): string[] => {
      const parsed = parseProgressFile(text, ids);
      return parsed.ok ? [] : parsed.errors;
    };
    expect(bad('nope')[0]).toMatch(/not JSON/);
    expect(bad('[]')[0]).toMatch(/JSON object/);
    expect(bad('{"format":"other"}')[0]).toMatch(/not a Scatterbook progress file/);
    expect(bad(`{"format":"${PROGRESS_FORMAT}","version":99}`)[0]).toMatch(/version 99/);
    const entry = (value: unknown): string =>
      JSON.stringify({
        format: PROGRESS_FORMAT,
        version: PROGRESS_VERSION,
        exercises: { 'beer-law': value },
      });
    expect(bad(entry({ code: 3, hintsShown: -1, result: null }))).toEqual([
      'exercise “beer-law”: “code” must be text',
      'exercise “beer-law”: “hintsShown” must be a whole number ≥ 0',
    ]);
    expect(
      bad(
        entry({
          code: '',
          hintsShown: 0,
          result: { status: 'great', score: 1, maxScore: 1, passed: 1, total: 1, at: 'x' },
        }),
      ),
    ).toEqual([
      'exercise “beer-law”: “result.status” must be one of graded, compile-error, wrong-signature, loop-budget, rejected, timeout, device-lost, internal-error',
      'exercise “beer-law”: “result.at” must be a date',
    ]);
  });

  it('imports the exercises it knows and names the ones it skips', () => {
    const text = JSON.stringify({
      format: PROGRESS_FORMAT,
      version: PROGRESS_VERSION,
      exported: AT.toISOString(),
      exercises: {
        'beer-law': { code: 'x', hintsShown: 0, result: null },
        'future-exercise': { code: 'y', hintsShown: 0, result: null },
      },
    });
    const parsed = parseProgressFile(text, ['beer-law']);
    expect(parsed.ok && Object.keys(parsed.file.exercises)).toEqual(['beer-law']);
    expect(parsed.ok && parsed.unknownIds).toEqual(['future-exercise']);
  });
});
