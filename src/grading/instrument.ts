// Source handling of a student's WGSL before it reaches the GPU. Everything here is
// one pass (or a constant number of passes) over the text, so a hostile submission
// cannot make preprocessing slow: the grader must finish before any watchdog could
// help (this runs as synchronous JavaScript, in the page too).
// - a size cap, checked before any parsing;
// - normalisation: a UTF-8 byte-order mark is dropped and every WGSL line break
//   (LF, CR LF, CR, VT, FF, U+0085, U+2028, U+2029 — WGSL spec §3.1 "Blankspace
//   and line breaks") becomes LF. The compiler then sees the same lines as every scan
//   here, so a `//` comment cannot end for the compiler but not for the scans, and
//   line/column numbers stay the student's (a CR LF pair or any other break is still
//   one line end; columns before it do not move);
// - blanking comments (same length, newlines kept) so that scans see only code;
// - tokens (identifiers with WGSL's Unicode rules, numbers by WGSL's literal grammar,
//   single-character punctuation) that every later scan reads;
// - refusing declarations the grader's harness does not allow (resource bindings,
//   entry points, `enable`/`requires`/`diagnostic` directives, `override`) and the
//   reserved name prefix, with the line and column of each;
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

/**
 * The largest submission the grader reads, in bytes of UTF-8: 64 KiB, a hundred times
 * the size of any exercise's solution. Checked before any parsing.
 */
export const MAX_SUBMISSION_BYTES = 64 * 1024;

/**
 * The most tokens the graded code may reach once every call of the student's own
 * functions is inlined (what the GPU compilers do: SwiftShader's SPIR-V optimiser
 * inlines every call). Twice what 64 KiB of straight-line code can hold, so only a
 * call tree that multiplies code is refused: 40 lines of `fn e_k(x) { return
 * e_{k-1}(e_{k-1}(x)); }` inline to 2^40 calls and crashed the grader's compiler
 * (SIGSEGV after "ID overflow") or ran past its wall-clock limit.
 */
export const MAX_INLINED_TOKENS = 1 << 17;

/** What a submission may contain, in the words the page and the README use. */
export const SUBMISSION_RULES =
  `One WGSL file of at most ${MAX_SUBMISSION_BYTES / 1024} KiB: your function and whatever it ` +
  'needs (other functions, structs, module-scope const and var<private>), with no ' +
  'var<workgroup>, ' +
  'bindings (@group, @binding), entry points (@compute, @vertex, @fragment), ' +
  'enable/requires/diagnostic directives, override declarations or names starting with ' +
  `${RESERVED_PREFIX}, and no functions that call each other so often that, inlined, ` +
  `they exceed ${MAX_INLINED_TOKENS} tokens; the grader refuses those before compiling.`;

/** Bytes of `text` in UTF-8 (lone surrogates count 3, as TextEncoder writes U+FFFD). */
export function utf8Length(text: string): number {
  let bytes = 0;
  for (let i = 0; i < text.length; i++) {
    const c = text.charCodeAt(i);
    if (c < 0x80) bytes += 1;
    else if (c < 0x800) bytes += 2;
    else if (c >= 0xd800 && c <= 0xdbff && i + 1 < text.length) {
      const d = text.charCodeAt(i + 1);
      if (d >= 0xdc00 && d <= 0xdfff) {
        bytes += 4;
        i++;
      } else bytes += 3;
    } else bytes += 3;
  }
  return bytes;
}

/** The refusal message for a submission of `bytes` bytes over the cap, or null when it fits. */
export function sizeRefusal(bytes: number, maxBytes = MAX_SUBMISSION_BYTES): string | null {
  if (bytes <= maxBytes) return null;
  return (
    `Your submission is ${bytes} bytes; the grader accepts at most ${maxBytes} bytes ` +
    `(${maxBytes / 1024} KiB) of WGSL. Submit only your function and what it needs.`
  );
}

/**
 * Decodes a submitted file: UTF-16 when it starts with a UTF-16 byte-order mark (what
 * some Windows editors save as "Unicode"), UTF-8 otherwise (invalid bytes become
 * U+FFFD, which the compiler then reports as an invalid character at its position).
 */
export function decodeSubmission(bytes: Uint8Array): string {
  if (bytes[0] === 0xff && bytes[1] === 0xfe) return new TextDecoder('utf-16le').decode(bytes);
  if (bytes[0] === 0xfe && bytes[1] === 0xff) return new TextDecoder('utf-16be').decode(bytes);
  return new TextDecoder('utf-8').decode(bytes);
}

/** WGSL line breaks other than LF (CR LF is handled as a pair first). */
const LINE_BREAKS = /\r\n|[\r\v\f\u0085\u2028\u2029]/g;

/**
 * The source the compiler and every scan see: no byte-order mark, every WGSL line
 * break as LF. Line and column numbers are those of the student's editor.
 */
export function normalizeSource(source: string): string {
  const text = source.charCodeAt(0) === 0xfeff ? source.slice(1) : source;
  return text.replace(LINE_BREAKS, '\n');
}

/** The source with comments replaced by spaces (newlines kept), so offsets still match. */
export function blankComments(source: string): string {
  // Chunks of unchanged text are copied whole; only comment text is rewritten.
  const out: string[] = [];
  let i = 0;
  let copied = 0;
  const n = source.length;
  const blank = (from: number, to: number): void => {
    out.push(source.slice(copied, from));
    out.push(source.slice(from, to).replace(/[^\n]/g, ' '));
    copied = to;
  };
  while (i < n) {
    const c = source.charCodeAt(i);
    if (c !== 0x2f /* / */ || i + 1 >= n) {
      i++;
      continue;
    }
    const next = source.charCodeAt(i + 1);
    if (next === 0x2f) {
      // Line comment: to the line end (every break is LF after normalizeSource; the
      // other WGSL breaks are honoured too for text that was not normalised).
      let j = i + 2;
      while (j < n && !isLineBreak(source.charCodeAt(j))) j++;
      blank(i, j);
      i = j;
    } else if (next === 0x2a /* * */) {
      // Block comments nest (WGSL §3.2).
      let depth = 1;
      let j = i + 2;
      while (j < n && depth > 0) {
        const a = source.charCodeAt(j);
        const b = j + 1 < n ? source.charCodeAt(j + 1) : 0;
        if (a === 0x2f && b === 0x2a) {
          depth++;
          j += 2;
        } else if (a === 0x2a && b === 0x2f) {
          depth--;
          j += 2;
        } else j++;
      }
      blank(i, j);
      i = j;
    } else i++;
  }
  out.push(source.slice(copied));
  return out.join('');
}

function isLineBreak(c: number): boolean {
  return (
    c === 0x0a ||
    c === 0x0b ||
    c === 0x0c ||
    c === 0x0d ||
    c === 0x85 ||
    c === 0x2028 ||
    c === 0x2029
  );
}

/** A token of comment-blanked WGSL: an identifier (or keyword), or one punctuation character. */
export interface Token {
  kind: 'ident' | 'punct';
  text: string;
  start: number;
}

// WGSL identifiers (§3.5): XID_Start XID_Continue*, or `_` followed by XID_Continue+.
const IDENTIFIER = /(?:[\p{XID_Start}]|_(?=[\p{XID_Continue}]))[\p{XID_Continue}]*/uy;
// WGSL literals (§3.4), so that the letters of `1u`, `0x1p4f` or `1e-3h` are not read as
// identifiers and the identifier after a literal starts where the compiler's does.
const NUMBERS = [
  /0[xX][0-9a-fA-F]*\.[0-9a-fA-F]+(?:[pP][+-]?[0-9]+[fh]?)?/y,
  /0[xX][0-9a-fA-F]+\.[0-9a-fA-F]*(?:[pP][+-]?[0-9]+[fh]?)?/y,
  /0[xX][0-9a-fA-F]+[pP][+-]?[0-9]+[fh]?/y,
  /0[xX][0-9a-fA-F]+[iu]?/y,
  /[0-9]*\.[0-9]+(?:[eE][+-]?[0-9]+)?[fh]?/y,
  /[0-9]+\.[0-9]*(?:[eE][+-]?[0-9]+)?[fh]?/y,
  /[0-9]+[eE][+-]?[0-9]+[fh]?/y,
  /[0-9]+[iufh]?/y,
];
// Blankspace (§3.1): space, tab, the line breaks, LRM and RLM.
const BLANK = /[ \t\n\v\f\r\u0085\u200e\u200f\u2028\u2029]+/y;

/** The longest match of the sticky regexes at `at`, or 0. */
function longest(regexes: readonly RegExp[], text: string, at: number): number {
  let best = 0;
  for (const regex of regexes) {
    regex.lastIndex = at;
    const match = regex.exec(text);
    if (match && match[0].length > best) best = match[0].length;
  }
  return best;
}

/** Tokens of comment-blanked code, in one pass. */
export function tokenize(code: string): Token[] {
  const tokens: Token[] = [];
  let i = 0;
  const n = code.length;
  while (i < n) {
    BLANK.lastIndex = i;
    if (BLANK.exec(code)) {
      i = BLANK.lastIndex;
      continue;
    }
    const c = code.charCodeAt(i);
    const digit = c >= 0x30 && c <= 0x39;
    if (digit || (c === 0x2e && /[0-9]/.test(code[i + 1] ?? ''))) {
      i += Math.max(1, longest(NUMBERS, code, i));
      continue;
    }
    IDENTIFIER.lastIndex = i;
    const ident = IDENTIFIER.exec(code);
    if (ident) {
      tokens.push({ kind: 'ident', text: ident[0], start: i });
      i += ident[0].length;
      continue;
    }
    // One UTF-16 code unit (a lone surrogate or any symbol): the compiler reports it.
    const width = c >= 0xd800 && c <= 0xdbff ? 2 : 1;
    tokens.push({ kind: 'punct', text: code.slice(i, i + width), start: i });
    i += width;
  }
  return tokens;
}

/** 1-based line and column of offsets in a text, in one pass to build. */
export class LineIndex {
  private readonly starts: number[] = [0];

  constructor(text: string) {
    for (let i = text.indexOf('\n'); i >= 0; i = text.indexOf('\n', i + 1)) this.starts.push(i + 1);
  }

  get lineCount(): number {
    return this.starts.length;
  }

  position(offset: number): { line: number; column: number } {
    let lo = 0;
    let hi = this.starts.length - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if ((this.starts[mid] ?? 0) <= offset) lo = mid;
      else hi = mid - 1;
    }
    return { line: lo + 1, column: offset - (this.starts[lo] ?? 0) + 1 };
  }
}

/** One declaration the grader refuses, at the student's line and column. */
export interface Refusal {
  line: number;
  column: number;
  what: string;
}

const ATTRIBUTE_REFUSALS: Record<string, string> = {
  group:
    '`@group` declares a GPU resource; the grader owns every binding, so your code ' +
    'can use only its parameters, the provided helpers and module-scope `const` or `var<private>`',
  binding:
    '`@binding` declares a GPU resource; the grader owns every binding, so your code ' +
    'can use only its parameters, the provided helpers and module-scope `const` or `var<private>`',
  compute: '`@compute` declares an entry point; the grader calls your function from its own',
  vertex: '`@vertex` declares an entry point; the grader calls your function from its own',
  fragment: '`@fragment` declares an entry point; the grader calls your function from its own',
};

const KEYWORD_REFUSALS: Record<string, string> = {
  enable:
    '`enable` directives are not allowed: the grader links code in front of yours and ' +
    'runs on devices without optional features; plain WGSL only',
  requires:
    '`requires` directives are not allowed: the grader links code in front of yours; plain WGSL only',
  diagnostic:
    '`diagnostic` directives are not allowed (the grader links code in front of yours); ' +
    'an `@diagnostic(…)` attribute on your function is fine',
  override:
    '`override` declarations are not allowed: the grader sets no pipeline constants; use `const`',
};

/**
 * Every refused declaration of the tokens: resource bindings (`@group`, `@binding`),
 * entry points (`@compute`, `@vertex`, `@fragment`), directives (`enable`, `requires`,
 * `diagnostic` other than as an attribute), `override`, and identifiers with the
 * reserved prefix.
 */
export function findRefusals(tokens: readonly Token[], lines: LineIndex): Refusal[] {
  const found: Refusal[] = [];
  const at = (token: Token, what: string): void => {
    found.push({ ...lines.position(token.start), what });
  };
  for (let k = 0; k < tokens.length; k++) {
    const token = tokens[k] as Token;
    if (token.kind !== 'ident') {
      // Characters the compiler reports without a position (e.g. NUL), or that mark a
      // file that was not UTF-8: say where they are.
      const c = token.text.charCodeAt(0);
      if ((c < 0x20 && c !== 0) || c === 0x7f) {
        const code = `U+${c.toString(16).toUpperCase().padStart(4, '0')}`;
        at(token, `a control character (${code}) that WGSL does not allow`);
      } else if (c === 0xfffd) {
        at(token, 'a byte sequence that is not UTF-8 (shown as U+FFFD); save the file as UTF-8');
      }
      continue;
    }
    const afterAt = tokens[k - 1]?.text === '@';
    if (
      token.text === 'workgroup' &&
      tokens[k - 1]?.text === '<' &&
      tokens[k - 2]?.text === 'var'
    ) {
      // Workgroup memory is shared by the grader's calls in one workgroup: a result could
      // then depend on other calls (other cases' arguments, other samples) and on their
      // order, so grading would neither test the function alone nor be reproducible.
      at(
        token,
        "`var<workgroup>` memory is shared between the grader's calls of your function, so " +
          'results would depend on other calls; use `var` inside your function or `var<private>`',
      );
    } else if (token.text.startsWith(RESERVED_PREFIX)) {
      at(
        token,
        `\`${token.text}\`: names starting with "${RESERVED_PREFIX}" are reserved for the grader; please rename it`,
      );
    } else if (afterAt) {
      const why = ATTRIBUTE_REFUSALS[token.text];
      if (why) at(tokens[k - 1] as Token, why);
    } else {
      const why = KEYWORD_REFUSALS[token.text];
      if (why) at(token, why);
    }
  }
  return found;
}

/** The message of a refused submission: the first few refusals with their positions. */
export function refusalMessage(refusals: readonly Refusal[]): string {
  const shown = refusals.slice(0, 5).map((r) => `line ${r.line}, column ${r.column}: ${r.what}.`);
  const more = refusals.length > shown.length ? [`(${refusals.length - shown.length} more)`] : [];
  return ['The grader refused your submission before compiling it:', ...shown, ...more].join('\n');
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

/**
 * Offsets of the `{` that opens each loop body, in one pass over the tokens: a loop
 * keyword waits for the first `{` at its own parenthesis depth (WGSL expressions in a
 * `for` header or `while` condition contain no braces); a `;` at that depth (no body)
 * or a `)` that closes past it drops it.
 */
function loopBodies(tokens: readonly Token[]): number[] {
  const opens: number[] = [];
  const pending: number[] = []; // parenthesis depth of each waiting keyword
  let depth = 0;
  for (const token of tokens) {
    if (token.kind === 'ident') {
      if (token.text === 'loop' || token.text === 'for' || token.text === 'while')
        pending.push(depth);
      continue;
    }
    switch (token.text) {
      case '(':
        depth++;
        break;
      case ')':
        depth--;
        while (pending.length > 0 && (pending[pending.length - 1] as number) > depth) pending.pop();
        break;
      case ';':
        while (pending.length > 0 && pending[pending.length - 1] === depth) pending.pop();
        break;
      case '{':
        if (pending.length > 0 && pending[pending.length - 1] === depth) {
          opens.push(token.start);
          while (pending.length > 0 && pending[pending.length - 1] === depth) pending.pop();
        }
        break;
    }
  }
  return opens;
}

/**
 * Inserts, right after the `{` that opens each loop body, a statement that counts
 * iterations in a per-thread private counter and breaks out once it passes the
 * budget, setting a flag the harness writes out. The counter is shared by all loops
 * of a thread, so nested loops are bounded by the same total, and once it has
 * tripped every enclosing loop breaks on its next iteration too. The insertion
 * stays on the line of the `{`, so line numbers do not change. `source` should be
 * normalised (normalizeSource); `tokens` may be passed when already computed.
 */
export function instrumentLoops(
  source: string,
  budget: number,
  scanned?: { code: string; tokens: readonly Token[] },
): Instrumented {
  const code = scanned?.code ?? blankComments(source);
  const tokens = scanned?.tokens ?? tokenize(code);
  const functions = parseFunctionTokens(code, tokens);
  const opens = loopBodies(tokens);
  // `return` of the zero value (`T()` is WGSL's zero-value constructor) rather than
  // `break`: a `loop` without `break` may legally end a function that returns a value,
  // and a `break` there would turn it into a "missing return" compile error.
  const guard = (result: string | null): string => {
    const exit = result ? `return ${result}();` : 'return;';
    return (
      ` ${GUARD_COUNTER} += 1u; if (${GUARD_COUNTER} > ${budget}u) ` +
      `{ ${GUARD_FLAG} = 1u; ${exit} }`
    );
  };
  const lines = new LineIndex(source);
  const out: string[] = [];
  const insertions: Insertion[] = [];
  let last = 0;
  let f = -1; // the last function starting before the current brace (both lists are sorted)
  for (const open of opens) {
    while (f + 1 < functions.length && (functions[f + 1] as ParsedFunction).start < open) f++;
    const text = guard(functions[f]?.result ?? null);
    out.push(source.slice(last, open + 1), text);
    last = open + 1;
    const { line, column } = lines.position(open);
    insertions.push({ line, column: column + 1, length: text.length });
  }
  out.push(source.slice(last));
  return { source: out.join(''), insertions, loops: opens.length };
}

/**
 * Maps compiler positions in the instrumented text (with `linesBefore` lines in front)
 * back to the student's; null for positions outside the student's `studentLines` lines.
 */
export function positionMapper(
  linesBefore: number,
  studentLines: number,
  insertions: readonly Insertion[],
): (line: number, column: number) => { line: number; column: number } | null {
  const byLine = new Map<number, Insertion[]>();
  for (const insertion of insertions) {
    const list = byLine.get(insertion.line);
    if (list) list.push(insertion);
    else byLine.set(insertion.line, [insertion]);
  }
  return (line, column) => {
    if (line <= linesBefore || line > linesBefore + studentLines) return null;
    return mapPosition(line, column, linesBefore, byLine.get(line - linesBefore) ?? []);
  };
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

const WORD_CHARACTER = /^[\p{XID_Continue}]/u;
const BLANKS_TO_END = /^[ \t]*$/;

/**
 * `import …;` lines (WESL; found in code, not comments) replaced by spaces of the
 * same length: the helpers are linked in front instead, and offsets do not move.
 */
export function blankImports(source: string, code: string = blankComments(source)): string {
  const out: string[] = [];
  let copied = 0;
  // A line is an import line when it starts with `import` as a whole word (a line
  // starting with an identifier such as `importance` is code) and has no `;` or one
  // `;` followed only by blanks. Read line by line with indexOf, not one multiline
  // regex: `[^;\n]*;?[ \t]*$` backtracks quadratically on `import`, 60,000 blanks
  // and `;x` (24 s).
  const n = code.length;
  for (let start = 0; start <= n;) {
    let end = code.indexOf('\n', start);
    if (end < 0) end = n;
    let word = start;
    while (word < end && (code[word] === ' ' || code[word] === '\t')) word++;
    const after = word + 'import'.length;
    if (
      after <= end &&
      code.startsWith('import', word) &&
      !WORD_CHARACTER.test(String.fromCodePoint(code.codePointAt(after) ?? 0x20))
    ) {
      // The rest of this line only (an indexOf past the line end would rescan).
      const rest = code.slice(after, end);
      const semi = rest.indexOf(';');
      if (semi < 0 || BLANKS_TO_END.test(rest.slice(semi + 1))) {
        out.push(source.slice(copied, start), ' '.repeat(end - start));
        copied = end;
      }
    }
    start = end + 1;
  }
  out.push(source.slice(copied));
  return out.join('');
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

function parseParam(text: string): { name: string; type: string } {
  const colon = text.indexOf(':');
  if (colon < 0) return { name: text.trim(), type: '' };
  return {
    // Attribute arguments first, with `[^()]*` so a failed match stops at the next
    // parenthesis: `@\s*\w+\s*(\([^)]*\))?` rescanned to the end of the text for every
    // unclosed `@a(` (quadratic, 4 s for 60 KB), then the attribute names.
    name: text
      .slice(0, colon)
      .replace(/\([^()]*\)/g, '')
      .replace(/@\s*\w+/g, '')
      .trim(),
    type: normaliseType(text.slice(colon + 1)),
  };
}

/**
 * Every `fn` declaration of the tokens with its parameter and result types, in one
 * pass: each header is read once, and the search for the next `fn` resumes after it.
 */
function parseFunctionTokens(code: string, tokens: readonly Token[]): ParsedFunction[] {
  const found: ParsedFunction[] = [];
  let k = 0;
  while (k < tokens.length) {
    const token = tokens[k] as Token;
    const name = tokens[k + 1];
    if (
      token.kind !== 'ident' ||
      token.text !== 'fn' ||
      name?.kind !== 'ident' ||
      tokens[k + 2]?.text !== '('
    ) {
      k++;
      continue;
    }
    // Parameters: to the `)` that closes the list (template brackets count as depth),
    // split at commas of depth 1.
    const params: { name: string; type: string }[] = [];
    let depth = 1;
    let j = k + 3;
    let partStart = (tokens[k + 2] as Token).start + 1;
    let close = code.length;
    for (; j < tokens.length; j++) {
      const t = tokens[j] as Token;
      if (t.text === '(' || t.text === '<') depth++;
      else if (t.text === ')' || t.text === '>') depth--;
      if (depth === 0) {
        close = t.start;
        j++;
        break;
      }
      if (t.text === ',' && depth === 1) {
        params.push(parseParam(code.slice(partStart, t.start)));
        partStart = t.start + 1;
      }
    }
    const last = code.slice(partStart, close);
    if (last.trim()) params.push(parseParam(last));
    // Result: `-> type` up to the body's `{`.
    let result: string | null = null;
    if (tokens[j]?.text === '-' && tokens[j + 1]?.text === '>') {
      const from = (tokens[j + 1] as Token).start + 1;
      let m = j + 2;
      while (m < tokens.length && tokens[m]?.text !== '{' && tokens[m]?.text !== ';') m++;
      if (tokens[m]?.text === '{') result = normaliseType(code.slice(from, tokens[m]?.start));
      j = m;
    }
    found.push({ start: token.start, name: name.text, params, result });
    k = Math.max(j, k + 1);
  }
  return found;
}

/** Every `fn` declaration of the source, with its parameter and result types (comments ignored). */
export function parseFunctions(source: string): ParsedFunction[] {
  const code = blankComments(normalizeSource(source));
  return parseFunctionTokens(code, tokenize(code));
}

/** Canonical text of a grader parameter type, for comparison with normaliseType's. */
export function paramTypeText(type: ParamType): string {
  return normaliseType(type);
}

/**
 * The largest inlined size of any function, in tokens: its own body's tokens plus,
 * for every call of another function of the submission, that function's inlined size.
 * Linear in the tokens: one pass assigns tokens and calls to function bodies, then a
 * memoised, iterative walk of the call graph (a cycle, which WGSL forbids and the
 * compiler reports, adds nothing). Sums saturate at Infinity, never overflow.
 */
export function inlinedSize(tokens: readonly Token[]): { name: string; tokens: number } | null {
  // Function names and where each body opens: `fn name ( … ) [-> type] {`.
  const index = new Map<string, number>();
  const names: string[] = [];
  const own: number[] = [];
  const calls: string[][] = [];
  let current = -1;
  let depth = 0;
  let pendingName: string | null = null;
  for (let k = 0; k < tokens.length; k++) {
    const token = tokens[k] as Token;
    if (
      depth === 0 &&
      token.kind === 'ident' &&
      token.text === 'fn' &&
      tokens[k + 1]?.kind === 'ident'
    ) {
      pendingName = (tokens[k + 1] as Token).text;
    }
    if (token.text === '{') {
      if (depth === 0 && pendingName !== null) {
        current = names.length;
        if (!index.has(pendingName)) index.set(pendingName, current);
        names.push(pendingName);
        own.push(0);
        calls.push([]);
        pendingName = null;
      }
      depth++;
    } else if (token.text === '}') {
      depth = Math.max(0, depth - 1);
      if (depth === 0) current = -1;
    } else if (token.text === ';' && depth === 0) pendingName = null;
    if (current >= 0) {
      own[current] = (own[current] as number) + 1;
      if (token.kind === 'ident' && tokens[k + 1]?.text === '(')
        (calls[current] as string[]).push(token.text);
    }
  }
  if (names.length === 0) return null;
  const size = new Array<number>(names.length).fill(-1); // -1 unvisited, -2 on the stack
  const stack: { f: number; next: number; total: number }[] = [];
  for (let root = 0; root < names.length; root++) {
    if (size[root] !== -1) continue;
    size[root] = -2;
    stack.push({ f: root, next: 0, total: own[root] as number });
    while (stack.length > 0) {
      const top = stack[stack.length - 1] as { f: number; next: number; total: number };
      const list = calls[top.f] as string[];
      if (top.next < list.length) {
        const callee = index.get(list[top.next++] as string);
        if (callee === undefined) continue;
        const known = size[callee] as number;
        if (known >= 0) top.total += known;
        else if (known === -1) {
          size[callee] = -2;
          stack.push({ f: callee, next: 0, total: own[callee] as number });
          // The callee's size is added when it is finished (below).
          top.next--;
        }
        continue;
      }
      size[top.f] = top.total;
      stack.pop();
    }
  }
  let best = 0;
  for (let f = 1; f < names.length; f++) if ((size[f] as number) > (size[best] as number)) best = f;
  return { name: names[best] as string, tokens: size[best] as number };
}

/** A submission ready to compile, or the reason it is refused. */
export type PreparedSource =
  | {
      ok: true;
      /** Normalised source with import lines blanked: what is compiled (after instrumentation). */
      text: string;
      instrumented: Instrumented;
      functions: ParsedFunction[];
      /** Lines of `text` (the student's lines). */
      lineCount: number;
    }
  | { ok: false; message: string };

/**
 * Everything done to a submission before the compiler sees it, in linear time: the
 * size cap (before any parsing), normalisation, import blanking, refusals and loop
 * instrumentation. The scans and the compiler read the same text.
 */
export function prepareSource(
  source: string,
  budget: number,
  maxBytes = MAX_SUBMISSION_BYTES,
): PreparedSource {
  const tooLarge = sizeRefusal(utf8Length(source), maxBytes);
  if (tooLarge) return { ok: false, message: tooLarge };
  const normalized = normalizeSource(source);
  const text = blankImports(normalized);
  const code = blankComments(text);
  const tokens = tokenize(code);
  const lines = new LineIndex(text);
  const refusals = findRefusals(tokens, lines);
  // NUL anywhere, comments included: Dawn refuses the whole module without a position.
  for (let at = text.indexOf('\0'); at >= 0; at = text.indexOf('\0', at + 1)) {
    refusals.push({
      ...lines.position(at),
      what: 'a NUL character (U+0000), which WGSL does not allow',
    });
  }
  refusals.sort((a, b) => a.line - b.line || a.column - b.column);
  if (refusals.length > 0) return { ok: false, message: refusalMessage(refusals) };
  const inlined = inlinedSize(tokens);
  if (inlined && inlined.tokens > MAX_INLINED_TOKENS) {
    const amount = Number.isFinite(inlined.tokens)
      ? `about ${inlined.tokens.toPrecision(2)}`
      : 'more than 10^308';
    return {
      ok: false,
      message:
        'The grader refused your submission before compiling it: the GPU compiler inlines ' +
        `every function call, and with its calls \`${inlined.name}\` inlines to ${amount} ` +
        `tokens (at most ${MAX_INLINED_TOKENS} are accepted). Call fewer functions per ` +
        'function, or use a loop instead of repeated calls.',
    };
  }
  return {
    ok: true,
    text,
    instrumented: instrumentLoops(text, budget, { code, tokens }),
    functions: parseFunctionTokens(code, tokens),
    lineCount: lines.lineCount,
  };
}
