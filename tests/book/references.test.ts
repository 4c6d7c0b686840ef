// What a student reads refers only to what a student can see: no "§" (the book's
// sections are not numbered; the developers' numerical reference, physics.md, is not
// published) and no repository paths (src/…, scripts/…, public/…, shaders/….wesl) in
// the text of the built pages. The shader-library appendix documents the library's
// code and may name its source files, but cites chapters, not physics.md.
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { buildBook } from '../../src/book/build/generate.ts';
import { replaceReferenceCitations } from '../../src/book/build/citations.ts';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));
const book = buildBook(ROOT);

/** The text of a page as read: no markup, scripts, styles or MathML (its TeX annotations hold `\S`-like source). */
function readableText(html: string): string {
  return html
    .replace(/<(script|style|math)\b[\s\S]*?<\/\1>/gi, ' ')
    .replace(/<[^>]+>/g, ' ')
    .replace(/&amp;/g, '&')
    .replace(/&lt;/g, '<')
    .replace(/&gt;/g, '>')
    .replace(/\s+/g, ' ');
}

const SECTION_SIGN = /.{0,50}§.{0,40}/g;
const PHYSICS_REFERENCE = /.{0,50}(?:physics\.md|physics reference|\(rows? \d+\b).{0,40}/gi;
/** A path into the repository, or a file of it named by its source extension. */
const REPOSITORY_PATH =
  /.{0,50}(?:\b(?:src|scripts|tests|public|shaders|exercises|bench|chapters)\/[\w.-]+|\b[\w-]+\.(?:wesl|ts|mjs|md)\b).{0,40}/g;

const CHAPTERS = [
  { number: 3, path: '/chapters/03-x.html' },
  { number: 5, path: '/chapters/05-y.html' },
  { number: 11, path: '/chapters/11-z.html' },
];

describe('citations of the numerical reference in doc comments', () => {
  it('become links to the chapter that teaches the section', () => {
    expect(replaceReferenceCitations('HG (physics.md §2.2), μ clamped', CHAPTERS)).toBe(
      'HG ([chapter 3](/chapters/03-x.html)), μ clamped',
    );
    expect(replaceReferenceCitations('the form of §2.4, with ξ', CHAPTERS)).toBe(
      'the form of [chapter 3](/chapters/03-x.html), with ξ',
    );
  });

  it('name one chapter once', () => {
    expect(replaceReferenceCitations('boundary (physics.md §6.1, §6.2, §7): Snell', CHAPTERS)).toBe(
      'boundary ([chapter 11](/chapters/11-z.html)): Snell',
    );
    expect(replaceReferenceCitations('integral (physics.md §3; chapter 5):', CHAPTERS)).toBe(
      'integral ([chapter 5](/chapters/05-y.html)):',
    );
  });

  it('are left out, with what held them, where no chapter teaches the section', () => {
    expect(replaceReferenceCitations('gives exactly 1 (§9 row 21); α', CHAPTERS)).toBe(
      'gives exactly 1; α',
    );
    expect(replaceReferenceCitations('Hard cases (§9): g = 0', CHAPTERS)).toBe('Hard cases: g = 0');
    expect(replaceReferenceCitations('Hard case: §9 row 25, 3 − 8', CHAPTERS)).toBe(
      'Hard case: 3 − 8',
    );
    expect(replaceReferenceCitations('finite (§9 row 19: no guard needed)', CHAPTERS)).toBe(
      'finite (no guard needed)',
    );
    expect(replaceReferenceCitations('gives 4.17 (§6.2, §9 row 21).', CHAPTERS)).toBe(
      'gives 4.17 ([chapter 11](/chapters/11-z.html)).',
    );
    expect(replaceReferenceCitations('Values (§6.3 table): 5.434', CHAPTERS)).toBe('Values: 5.434');
    // Rows of the hard-case table cited without the section.
    expect(replaceReferenceCitations('gives T = 0 exactly (row 10); σt', CHAPTERS)).toBe(
      'gives T = 0 exactly; σt',
    );
    expect(
      replaceReferenceCitations('not the exact 0 (row 22; the better dipole gives 0)', CHAPTERS),
    ).toBe('not the exact 0 (the better dipole gives 0)');
    expect(replaceReferenceCitations('Row 0 is the top row (row 0 of the image).', CHAPTERS)).toBe(
      'Row 0 is the top row (row 0 of the image).',
    );
  });

  it('leave text without citations unchanged', () => {
    const text = 'Skimmilk R: 0.814946; Ketchup B: 0.001830 (Jensen et al. 2001).';
    expect(replaceReferenceCitations(text, CHAPTERS)).toBe(text);
  });
});

describe('references in the built pages', () => {
  it('the scans find what they look for', () => {
    expect('see the chapter’s §2.5 here'.match(SECTION_SIGN)).not.toBeNull();
    expect('Physics reference §5 writes'.match(PHYSICS_REFERENCE)).not.toBeNull();
    expect('The scene public/scenes/white-furnace.json is'.match(REPOSITORY_PATH)).not.toBeNull();
    expect('computed by phantom.ts when'.match(REPOSITORY_PATH)).not.toBeNull();
    expect(readableText('<p>a<math><annotation>\\S x</annotation></math> b</p>')).toBe(' a b ');
  });

  for (const page of book.pages) {
    const appendix = page.file.startsWith('appendix/');
    it(`${page.file}: no § or physics.md${appendix ? '' : ', no repository paths'}`, () => {
      const text = readableText(page.html);
      expect(text.match(SECTION_SIGN) ?? []).toEqual([]);
      expect(text.match(PHYSICS_REFERENCE) ?? []).toEqual([]);
      if (!appendix) expect(text.match(REPOSITORY_PATH) ?? []).toEqual([]);
    });
  }
});
