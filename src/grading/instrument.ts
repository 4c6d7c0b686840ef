// Source handling of a student's WGSL before it reaches the GPU:
// - blanking comments (same length, newlines kept) so that scans see only code;
// - bounding every loop: each `loop`, `for` and `while` body gets an iteration counter
//   against a budget, so an endless loop ends and the kernel reports it instead of
//   hanging the GPU;
// - mapping the compiler's line/column back to the student's text, accounting for
//   the lines in front of it and the text inserted on a line by the instrumentation.
import type { ParamType } from './exercise.ts';

/** Names the instrumentation and the harness declare; a submission must not use the prefix. */
export const RESERVED_PREFIX = 'sbg_';
export const GUARD_COUNTER = 'sbg_iterations';
export const GUARD_FLAG = 'sbg_budgetExceeded';

/** The source with comments replaced by spaces (newlines kept), so offsets still match. */
export function blankComments(source: string): string {
  let out = '';
  let i = 0;
  let depth = 0;
  while (i < source.length) {
    const two = source.slice(i, i + 2);
    if (depth === 0 && two === '//') {
      while (i < source.length && source[i] !== '\n') {
        out += ' ';
        i++;
      }
    } else if (two === '/*') {
      // WGSL block comments nest.
      depth++;
      out += '  ';
      i += 2;
    } else if (depth > 0 && two === '*/') {
      depth--;
      out += '  ';
      i += 2;
    } else if (depth > 0) {
      out += source[i] === '\n' ? '\n' : ' ';
      i++;
    } else {
      out += source[i];
      i++;
    }
  }
  return out;
}

/** Text inserted by the instrumentation: at 1-based line, after 1-based column `column - 1`. */
export interface Insertion {
  line: number;
  column: number;
  length: number;
}

export interface Instrumented {
  source: string;
  insertions: Insertion[];
  loops: number;
}

function isIdentifierChar(c: string | undefined): boolean {
  return c !== undefined && /[A-Za-z0-9_]/.test(c);
}

/**
 * Inserts, right after the `{` that opens each loop body, a statement that counts
 * iterations in a per-thread private counter and breaks out once it passes the
 * budget, setting a flag the harness writes out. The counter is shared by all loops
 * of a thread, so nested loops are bounded by the same total, and once it has
 * tripped every enclosing loop breaks on its next iteration too. The insertion
 * stays on the line of the `{`, so line numbers do not change.
 */
export function instrumentLoops(source: string, budget: number): Instrumented {
  const code = blankComments(source);
  const functions = parseFunctions(source);
  // `return` of the zero value (`T()` is WGSL's zero-value constructor) rather than
  // `break`: a `loop` without `break` may legally end a function that returns a value,
  // and a `break` there would turn it into a "missing return" compile error.
  const guard = (open: number): string => {
    const enclosing = functions.filter((f) => f.start < open).pop();
    const exit = enclosing?.result ? `return ${enclosing.result}();` : 'return;';
    return (
      ` ${GUARD_COUNTER} += 1u; if (${GUARD_COUNTER} > ${budget}u) ` +
      `{ ${GUARD_FLAG} = 1u; ${exit} }`
    );
  };
  const opens: number[] = [];
  const keyword = /\b(loop|for|while)\b/g;
  let match: RegExpExecArray | null;
  while ((match = keyword.exec(code)) !== null) {
    const start = match.index;
    if (isIdentifierChar(code[start - 1])) continue;
    let i = start + match[0].length;
    let parens = 0;
    // The body's `{` is the first brace at parenthesis depth 0 (WGSL expressions in
    // a `for` header or `while` condition contain no braces).
    for (; i < code.length; i++) {
      const c = code[i];
      if (c === '(') parens++;
      else if (c === ')') parens--;
      else if (c === '{' && parens === 0) break;
      else if (c === ';' && parens === 0) break;
    }
    if (code[i] === '{') opens.push(i);
  }
  let out = '';
  let last = 0;
  const insertions: Insertion[] = [];
  for (const open of opens) {
    const text = guard(open);
    out += source.slice(last, open + 1) + text;
    last = open + 1;
    const before = source.slice(0, open + 1);
    const line = before.split('\n').length;
    const column = open + 1 - before.lastIndexOf('\n');
    insertions.push({ line, column, length: text.length });
  }
  out += source.slice(last);
  return { source: out, insertions, loops: opens.length };
}

/** The student's 1-based line/column for a compiler position in the instrumented text. */
export function mapPosition(
  line: number,
  column: number,
  linesBefore: number,
  insertions: readonly Insertion[],
): { line: number; column: number } {
  const studentLine = line - linesBefore;
  let studentColumn = column;
  for (const insertion of insertions) {
    if (insertion.line !== studentLine || insertion.column >= column) continue;
    // A position inside inserted text maps to the brace it follows.
    studentColumn -= Math.min(insertion.length, column - insertion.column);
  }
  return { line: studentLine, column: Math.max(1, studentColumn) };
}

/** Replaces `import …;` lines with blank lines (helpers are linked in front instead). */
export function blankImports(source: string): string {
  return source.replace(/^[ \t]*import[^;\n]*;?[ \t]*$/gm, '');
}

export interface ParsedFunction {
  /** Offset of the `fn` keyword. */
  start: number;
  name: string;
  params: { name: string; type: string }[];
  result: string | null;
}

/** Whitespace-normalised type text, e.g. `ptr<function,u32>` → `ptr<function, u32>`. */
export function normaliseType(type: string): string {
  return type
    .replace(/\s+/g, '')
    .replace(/,/g, ', ')
    .replace(/^vec([234])<f32>$/, 'vec$1f');
}

/** Every `fn` declaration of the (comment-blanked) source, with its parameter and result types. */
export function parseFunctions(source: string): ParsedFunction[] {
  const code = blankComments(source);
  const found: ParsedFunction[] = [];
  const header = /\bfn\s+([A-Za-z_][A-Za-z0-9_]*)\s*\(/g;
  let match: RegExpExecArray | null;
  while ((match = header.exec(code)) !== null) {
    let i = header.lastIndex;
    let depth = 1;
    const start = i;
    for (; i < code.length && depth > 0; i++) {
      if (code[i] === '(' || code[i] === '<') depth++;
      else if (code[i] === ')' || code[i] === '>') depth--;
    }
    const list = code.slice(start, i - 1);
    const params: { name: string; type: string }[] = [];
    let partDepth = 0;
    let part = '';
    const flush = (): void => {
      const text = part.trim();
      part = '';
      if (!text) return;
      const colon = text.indexOf(':');
      params.push(
        colon < 0
          ? { name: text, type: '' }
          : {
              name: text
                .slice(0, colon)
                .replace(/@\w+(\([^)]*\))?/g, '')
                .trim(),
              type: normaliseType(text.slice(colon + 1)),
            },
      );
    };
    for (const c of list) {
      if (c === '<' || c === '(') partDepth++;
      if (c === '>' || c === ')') partDepth--;
      if (c === ',' && partDepth === 0) flush();
      else part += c;
    }
    flush();
    const rest = code.slice(i);
    const arrow = /^\s*->\s*([^{]+)\{/.exec(rest);
    found.push({
      start: match.index,
      name: match[1] ?? '',
      params,
      result: arrow ? normaliseType(arrow[1] ?? '') : null,
    });
  }
  return found;
}

/** Canonical text of a grader parameter type, for comparison with normaliseType's. */
export function paramTypeText(type: ParamType): string {
  return normaliseType(type);
}
