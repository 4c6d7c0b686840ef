// A student's progress on the exercises: the code and the last public-check result of
// each exercise, kept in localStorage (so a reload restores it) and exported or
// imported as one JSON file (so it moves between browsers). Pure data and
// validation, no DOM: an imported file is checked field by field and every problem
// is reported in words, because a student cannot debug a silently ignored file.
import type { GradeOutcome } from '../../grading/types.ts';

/** Format marker and version of an exported progress file. */
export const PROGRESS_FORMAT = 'scatterbook-exercise-progress';
export const PROGRESS_VERSION = 1;

const STORAGE_PREFIX = 'scatterbook:exercise:';

/** The summary of the last run kept next to the code (the full outcome is not stored). */
export interface StoredResult {
  /** GradeOutcome status, e.g. 'graded' or 'compile-error'. */
  status: GradeOutcome['status'];
  score: number;
  maxScore: number;
  /** Public checks passed / run (0 / 0 when grading could not happen). */
  passed: number;
  total: number;
  /** ISO time of the run. */
  at: string;
}

export interface ExerciseProgress {
  code: string;
  /** Hints revealed so far. */
  hintsShown: number;
  result: StoredResult | null;
}

export interface ProgressFile {
  format: typeof PROGRESS_FORMAT;
  version: number;
  exported: string;
  exercises: Record<string, ExerciseProgress>;
}

/** Reduces a grading outcome to what is worth keeping across reloads. */
export function summarizeOutcome(outcome: GradeOutcome, at: Date): StoredResult {
  if (outcome.status !== 'graded') {
    return {
      status: outcome.status,
      score: 0,
      maxScore: 0,
      passed: 0,
      total: 0,
      at: at.toISOString(),
    };
  }
  return {
    status: 'graded',
    score: outcome.score,
    maxScore: outcome.maxScore,
    passed: outcome.checks.filter((check) => check.verdict === 'pass').length,
    total: outcome.checks.length,
    at: at.toISOString(),
  };
}

const STATUSES: readonly string[] = [
  'graded',
  'compile-error',
  'wrong-signature',
  'loop-budget',
  'rejected',
  'timeout',
  'device-lost',
  'internal-error',
];

function isRecord(value: unknown): value is Record<string, unknown> {
  return typeof value === 'object' && value !== null && !Array.isArray(value);
}

function isCount(value: unknown): value is number {
  return typeof value === 'number' && Number.isFinite(value) && value >= 0;
}

/** Checks one exercise's entry; returns the problems found (empty when valid). */
function checkEntry(id: string, value: unknown): string[] {
  if (!isRecord(value)) return [`exercise “${id}”: expected an object with code and result`];
  const problems: string[] = [];
  if (typeof value['code'] !== 'string') problems.push(`exercise “${id}”: “code” must be text`);
  else if (value['code'].length > 200_000)
    problems.push(`exercise “${id}”: “code” is longer than 200 000 characters`);
  if (!Number.isInteger(value['hintsShown']) || !isCount(value['hintsShown']))
    problems.push(`exercise “${id}”: “hintsShown” must be a whole number ≥ 0`);
  const result = value['result'];
  if (result !== null) {
    if (!isRecord(result)) {
      problems.push(`exercise “${id}”: “result” must be null or an object`);
    } else {
      if (typeof result['status'] !== 'string' || !STATUSES.includes(result['status']))
        problems.push(`exercise “${id}”: “result.status” must be one of ${STATUSES.join(', ')}`);
      for (const key of ['score', 'maxScore', 'passed', 'total'])
        if (!isCount(result[key]))
          problems.push(`exercise “${id}”: “result.${key}” must be a number ≥ 0`);
      if (typeof result['at'] !== 'string' || Number.isNaN(Date.parse(result['at'])))
        problems.push(`exercise “${id}”: “result.at” must be a date`);
    }
  }
  return problems;
}

export type ParsedProgress =
  { ok: true; file: ProgressFile; unknownIds: string[] } | { ok: false; errors: string[] };

/**
 * Parses an exported progress file. `knownIds` are the exercises this book has:
 * entries for others are kept out and named, so a file from a newer book imports
 * what it can and says what it skipped.
 */
export function parseProgressFile(text: string, knownIds: readonly string[]): ParsedProgress {
  let data: unknown;
  try {
    data = JSON.parse(text);
  } catch (error) {
    return {
      ok: false,
      errors: [`The file is not JSON: ${error instanceof Error ? error.message : String(error)}`],
    };
  }
  if (!isRecord(data)) return { ok: false, errors: ['The file does not hold a JSON object.'] };
  if (data['format'] !== PROGRESS_FORMAT)
    return {
      ok: false,
      errors: [`This is not a Scatterbook progress file (“format” is not “${PROGRESS_FORMAT}”).`],
    };
  if (data['version'] !== PROGRESS_VERSION)
    return {
      ok: false,
      errors: [
        `The file has version ${JSON.stringify(data['version'])}; this book reads version ${PROGRESS_VERSION}.`,
      ],
    };
  const exercises = data['exercises'];
  if (!isRecord(exercises))
    return { ok: false, errors: ['“exercises” must be an object keyed by exercise id.'] };
  const errors: string[] = [];
  const accepted: Record<string, ExerciseProgress> = {};
  const unknownIds: string[] = [];
  for (const [id, entry] of Object.entries(exercises)) {
    if (!knownIds.includes(id)) {
      unknownIds.push(id);
      continue;
    }
    const problems = checkEntry(id, entry);
    if (problems.length > 0) errors.push(...problems);
    else accepted[id] = entry as ExerciseProgress;
  }
  if (errors.length > 0) return { ok: false, errors };
  const exported = typeof data['exported'] === 'string' ? data['exported'] : '';
  return {
    ok: true,
    file: { format: PROGRESS_FORMAT, version: PROGRESS_VERSION, exported, exercises: accepted },
    unknownIds,
  };
}

/** The minimal storage interface (localStorage, or a Map in tests). */
export interface KeyValueStore {
  getItem(key: string): string | null;
  setItem(key: string, value: string): void;
  readonly length: number;
  key(index: number): string | null;
}

/** Reads one exercise's stored progress; null when none or unreadable. */
export function loadProgress(store: KeyValueStore, id: string): ExerciseProgress | null {
  const raw = store.getItem(STORAGE_PREFIX + id);
  if (raw === null) return null;
  try {
    const value: unknown = JSON.parse(raw);
    return checkEntry(id, value).length === 0 ? (value as ExerciseProgress) : null;
  } catch {
    return null;
  }
}

export function saveProgress(store: KeyValueStore, id: string, progress: ExerciseProgress): void {
  store.setItem(STORAGE_PREFIX + id, JSON.stringify(progress));
}

/** Every exercise's stored progress, as an export file. */
export function collectProgress(store: KeyValueStore, now: Date): ProgressFile {
  const exercises: Record<string, ExerciseProgress> = {};
  for (let i = 0; i < store.length; i++) {
    const key = store.key(i);
    if (!key?.startsWith(STORAGE_PREFIX)) continue;
    const id = key.slice(STORAGE_PREFIX.length);
    const progress = loadProgress(store, id);
    if (progress) exercises[id] = progress;
  }
  return {
    format: PROGRESS_FORMAT,
    version: PROGRESS_VERSION,
    exported: now.toISOString(),
    exercises,
  };
}
