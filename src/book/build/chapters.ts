// Loads the Markdown chapters: `chapters/NN-slug.md`, each with YAML front matter
// (title, summary). The two-digit prefix is the chapter number.
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { parse as parseYaml } from 'yaml';

export interface ChapterSource {
  /** 1-based chapter number from the file name. */
  number: number;
  /** File name without extension, e.g. `02-extinction-and-transmittance`; also the page name. */
  slug: string;
  title: string;
  summary: string;
  /** Markdown body without the front matter. */
  body: string;
  /** Lines of the file before the body (the front matter), so errors can cite file lines. */
  bodyOffset?: number;
  file: string;
}

const FILE_PATTERN = /^(\d{2})-[a-z0-9-]+\.md$/;
const FRONT_MATTER = /^---\n([\s\S]*?)\n---\n/;

export function parseChapter(file: string, text: string): ChapterSource {
  const name = file.split('/').pop() ?? file;
  const match = FILE_PATTERN.exec(name);
  if (!match) {
    throw new Error(`${file}: chapter files are named NN-slug.md (lowercase slug), got "${name}"`);
  }
  const front = FRONT_MATTER.exec(text);
  if (!front) {
    throw new Error(`${file}: missing YAML front matter (--- title: … summary: … ---)`);
  }
  const meta = parseYaml(front[1] ?? '') as Record<string, unknown> | null;
  const title = meta?.['title'];
  const summary = meta?.['summary'];
  if (typeof title !== 'string' || title.trim() === '') {
    throw new Error(`${file}: front matter needs a "title" string`);
  }
  if (typeof summary !== 'string' || summary.trim() === '') {
    throw new Error(`${file}: front matter needs a "summary" string`);
  }
  return {
    number: Number(match[1]),
    slug: name.replace(/\.md$/, ''),
    title: title.trim(),
    summary: summary.trim(),
    body: text.slice(front[0].length),
    bodyOffset: front[0].split('\n').length - 1,
    file,
  };
}

export function loadChapters(directory: string): ChapterSource[] {
  const files = readdirSync(directory)
    .filter((name) => name.endsWith('.md'))
    .sort();
  const chapters = files.map((name) =>
    parseChapter(join(directory, name), readFileSync(join(directory, name), 'utf8')),
  );
  const seen = new Map<number, string>();
  for (const chapter of chapters) {
    const other = seen.get(chapter.number);
    if (other)
      throw new Error(`chapters ${other} and ${chapter.slug} share number ${chapter.number}`);
    seen.set(chapter.number, chapter.slug);
  }
  return chapters;
}
