// The shader library's doc comments cite the project's numerical reference, a
// document for the library's developers that the book does not publish:
// "(physics.md §6.1)", "Hard cases (§9): …", "(§6.2, §9 row 21)". In the appendix a
// student would meet references to nothing, so each citation becomes a link to the
// chapter that teaches the cited topic, and a citation of a section that no chapter
// teaches (the table of hard cases, the notes on f32 arithmetic, the list of sources)
// is left out, with the parentheses or separators that held it. The comments keep
// their citations for the developers.

/** The numerical reference's top-level sections, and the chapter that teaches each. */
const CHAPTER_OF_SECTION: Readonly<Record<number, number>> = {
  1: 2, // extinction, transmittance, Beer–Lambert
  2: 3, // phase functions
  3: 5, // ray marching the emission–absorption integral
  4: 6, // unbiased transmittance estimators
  5: 9, // single scattering with shadow rays
  6: 11, // subsurface scattering (dipoles, Christensen–Burley)
  7: 11, // Monte Carlo benchmarks of a slab (the chapter's validation table)
  8: 11, // Jensen & Buhler's hierarchical translucent rendering
};

/**
 * One citation: an optional "physics.md", the section, and what of it is cited
 * (rows of the hard-case table, "table", "hazards", "benchmark B", …).
 */
const CITATION =
  /(?:physics\.md\s+)?§(\d+)(?:\.\d+)*(\s+(?:rows?\s+\d+(?:\s*[–-]\s*\d+)?(?:,\s*\d+(?=[),;]))*|table|hazards|conformance vector|benchmark\s+[A-Z]\b|test problem|prints))?/g;
const DROPPED = '\u0000';
/** "(row 10", "(rows 19–23": the start of a parenthesis citing rows of the hard-case table. */
const ROW_CITATION = /\(\s*rows?\s+\d+(?:\s*[–-]\s*\d+)?(?:,\s*\d+)*/;

export interface ChapterLink {
  number: number;
  /** Site path of the chapter page, e.g. `/chapters/11-subsurface-scattering.html`. */
  path: string;
}

/**
 * Markdown of a doc comment with every citation of the numerical reference replaced by
 * a link to its chapter, or removed. Text without citations comes back unchanged.
 */
export function replaceReferenceCitations(
  markdown: string,
  chapters: readonly ChapterLink[],
): string {
  if (!markdown.includes('§') && !ROW_CITATION.test(markdown)) return markdown;
  let text = markdown.replace(CITATION, (_all, section: string, qualifier?: string) => {
    const number = CHAPTER_OF_SECTION[Number(section)];
    const chapter = chapters.find((c) => c.number === number);
    // "§3 table", "§9 row 21": a part of the reference that no chapter holds as such.
    if (qualifier) return DROPPED;
    return chapter ? `[chapter ${chapter.number}](${chapter.path})` : DROPPED;
  });
  // Where a dropped citation stood, take out what only held it: "(§9)", "(§9 row 5: …",
  // ", §9 row 21)", "Hard case: §9 row 25, …".
  const d = DROPPED;
  text = text
    // A row of the hard-case table cited on its own at the start of a parenthesis,
    // "(row 10)", "(row 22; …)", "(row 12: …)".
    .replace(new RegExp(`${ROW_CITATION.source}\\s*\\)`, 'g'), `(${d})`)
    .replace(new RegExp(`${ROW_CITATION.source}\\s*[;:,]\\s*`, 'g'), '(')
    .replace(new RegExp(`\\s*\\(\\s*${d}(?:\\s*[,;]\\s*${d})*\\s*\\)`, 'g'), '')
    .replace(new RegExp(`\\(\\s*${d}\\s*[,;:]\\s*`, 'g'), '(')
    .replace(new RegExp(`\\s*[,;]\\s*${d}(?=\\s*[),;:.])`, 'g'), '')
    .replace(new RegExp(`${d}\\s*[,;:]\\s*`, 'g'), '')
    .replace(new RegExp(`\\s*${d}`, 'g'), '');
  // One chapter named twice in a row ("§6.1, §6.2", "physics.md §3; chapter 5") reads as once.
  return text
    .replace(
      /(\[chapter (\d+)\]\([^)]*\))(?:\s*[,;]\s*(?:\[chapter \2\]\([^)]*\)|chapter \2\b))+/g,
      '$1',
    )
    .replace(/\bchapter (\d+)\s*[,;]\s*\[chapter \1\]\([^)]*\)/g, 'chapter $1');
}
