// Pseudo-code listings (src/book/listings/NAME.pseudo): the lecture's algorithms written
// the way a blackboard writes them, highlighted at build time and linked to the WGSL
// function of the shader library that implements each of them.
//
// A listing file starts with a header, `implements: module.function[, module.function]`,
// then a line `---`, then the pseudo-code. Highlighting uses CodeMirror's stream parser
// (@codemirror/language StreamLanguage) and @lezer/highlight's classHighlighter, the same
// libraries the exercise editor uses, with the small grammar below: keywords, ▷ comments,
// numbers, operators and procedure names. Nothing is interpreted; the grammar only colours.
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { StreamLanguage, type StringStream } from '@codemirror/language';
import { classHighlighter, highlightCode } from '@lezer/highlight';
import type { ShaderModuleDocs } from './shaderDocs.ts';

export interface ListingReference {
  module: string;
  name: string;
}

export interface ListingSource {
  name: string;
  /** The shader-library functions that implement the algorithm (appendix anchors). */
  implements: ListingReference[];
  /** The pseudo-code, one string per line, indentation kept. */
  code: string;
}

const KEYWORDS = new Set([
  'function',
  'procedure',
  'return',
  'for',
  'to',
  'do',
  'while',
  'loop',
  'if',
  'then',
  'else',
  'break',
  'and',
  'or',
  'not',
  'each',
  'in',
  'repeat',
  'until',
]);

/** Procedure names: a word followed by "(" (a call or a definition). */
const PROCEDURE = /^[A-Za-z_][A-Za-z0-9_]*(?=\()/;
// Latin and Greek letters, ℓ, and the marks that decorate them (σ̄, T̂, primes).
const WORD = /^[A-Za-z_\u0370-\u03ff\u2113](?:[\w\u0370-\u03ff\u2113′]|\p{M})*/u;
const NUMBER = /^\d+(\.\d+)?([eE][−-]?\d+)?/;
const OPERATOR = /^(←|≥|≤|≠|=|<|>|\+|−|-|·|×|\/|\*|\^)/;

const pseudocode = StreamLanguage.define<Record<string, never>>({
  name: 'pseudocode',
  startState: () => ({}),
  token(stream: StringStream): string | null {
    if (stream.eatSpace()) return null;
    if (stream.match('▷')) {
      stream.skipToEnd();
      return 'comment';
    }
    if (stream.match(PROCEDURE)) return 'def';
    const word = stream.match(WORD);
    if (word && typeof word !== 'boolean') {
      return KEYWORDS.has(word[0]) ? 'keyword' : 'variableName';
    }
    if (stream.match(NUMBER)) return 'number';
    if (stream.match(OPERATOR)) return 'operator';
    stream.next();
    return null;
  },
});

function escapeHtml(text: string): string {
  return text.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
}

/** The code as HTML: one block `<span class="line">` per line, tokens as `<span class="tok-…">`. */
export function highlightPseudocode(code: string): string {
  const tree = pseudocode.parser.parse(code);
  const lines: string[] = [''];
  highlightCode(
    code,
    tree,
    classHighlighter,
    (textPart, classes) => {
      // Monospace fonts rarely place combining marks (the bar of σ̄, the hat of T̂) over their
      // letter; such a letter is set in the math font instead (figures.css, .pc-accent).
      const escaped = escapeHtml(textPart).replace(
        /\P{M}\p{M}+/gu,
        (letter) => `<span class="pc-accent">${letter}</span>`,
      );
      lines[lines.length - 1] += classes ? `<span class="${classes}">${escaped}</span>` : escaped;
    },
    () => lines.push(''),
  );
  // Block lines, no newline between them: under pre-wrap a newline would be a blank line.
  // A line that is only a comment keeps it inline, so that it wraps in place (figures.css).
  return lines
    .map((line) => {
      const commentOnly = /^\s*<span class="tok-comment">[^]*<\/span>$/.test(line);
      return `<span class="line${commentOnly ? ' line-comment' : ''}">${line}</span>`;
    })
    .join('');
}

const HEADER = /^implements:\s*(.+)\n---\n/;

export function parseListing(name: string, text: string, file: string): ListingSource {
  const header = HEADER.exec(text);
  if (!header)
    throw new Error(`${file}: a listing starts with "implements: module.function" and "---"`);
  const implementsList = (header[1] ?? '').split(',').map((entry) => {
    const match = /^\s*([a-z0-9-]+)\.([A-Za-z_][A-Za-z0-9_]*)\s*$/.exec(entry);
    if (!match) throw new Error(`${file}: "${entry.trim()}" is not module.function`);
    return { module: match[1] ?? '', name: match[2] ?? '' };
  });
  const code = text.slice(header[0].length).replace(/\s+$/, '');
  if (code === '') throw new Error(`${file}: the listing has no code`);
  return { name, implements: implementsList, code };
}

export function loadListings(directory: string): Map<string, ListingSource> {
  const listings = new Map<string, ListingSource>();
  for (const file of readdirSync(directory)
    .filter((entry) => entry.endsWith('.pseudo'))
    .sort()) {
    const name = file.replace(/\.pseudo$/, '');
    listings.set(name, parseListing(name, readFileSync(join(directory, file), 'utf8'), file));
  }
  return listings;
}

/** The appendix anchor of a library function (appendix.ts: `${module}-${function}`). */
export function appendixAnchor(reference: ListingReference): string {
  return `${reference.module}-${reference.name}`;
}

/** Throws unless every function a listing cites is a documented function of the library. */
export function checkListingReferences(
  listings: Map<string, ListingSource>,
  modules: readonly ShaderModuleDocs[],
): void {
  for (const listing of listings.values()) {
    for (const reference of listing.implements) {
      const module = modules.find((candidate) => candidate.name === reference.module);
      const found = module?.declarations.some(
        (declaration) => declaration.kind === 'fn' && declaration.name === reference.name,
      );
      if (!found) {
        throw new Error(
          `listing ${listing.name}: shaders/${reference.module}.wesl has no function ${reference.name}`,
        );
      }
    }
  }
}
