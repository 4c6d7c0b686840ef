// Printing and saving benchmark tables.
import { mkdirSync, writeFileSync } from 'node:fs';

export interface BenchTable {
  title: string;
  notes: string[];
  rows: Record<string, string | number | null>[];
}

export function median(values: readonly number[]): number {
  const sorted = [...values].sort((a, b) => a - b);
  const middle = Math.floor(sorted.length / 2);
  return sorted.length % 2
    ? (sorted[middle] ?? NaN)
    : ((sorted[middle - 1] ?? NaN) + (sorted[middle] ?? NaN)) / 2;
}

function format(value: string | number | null): string {
  if (value === null) return '—';
  if (typeof value === 'string') return value;
  if (!Number.isFinite(value)) return value > 0 ? '∞' : String(value);
  if (value === 0) return '0';
  const magnitude = Math.abs(value);
  return magnitude >= 1e5 || magnitude < 1e-3
    ? value.toExponential(3)
    : String(Number(value.toPrecision(5)));
}

/** Prints a table as Markdown (readable in a terminal and pasteable into a note). */
export function printTable(table: BenchTable): void {
  console.log(`\n## ${table.title}\n`);
  for (const note of table.notes) console.log(`- ${note}`);
  const columns = [...new Set(table.rows.flatMap((row) => Object.keys(row)))];
  console.log(`\n| ${columns.join(' | ')} |`);
  console.log(`| ${columns.map(() => '---').join(' | ')} |`);
  for (const row of table.rows)
    console.log(`| ${columns.map((c) => format(row[c] ?? null)).join(' | ')} |`);
}

export function saveTables(
  path: string,
  tables: readonly BenchTable[],
  meta: Record<string, unknown>,
): void {
  mkdirSync(new URL('.', `file://${path}`).pathname, { recursive: true });
  writeFileSync(
    path,
    `${JSON.stringify({ ...meta, tables }, (_k, v) => (v === Infinity ? 'Infinity' : v), 2)}\n`,
  );
}
