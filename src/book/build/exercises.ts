// Exercises embedded in a chapter: `<sb-exercise exercise="ID"></sb-exercise>` on a
// line of its own. At build time the statement (exercises/ID/statement.md) is
// rendered with the chapter's own Markdown + KaTeX pipeline and put inside the
// element, followed by the starter code, so the exercise reads without JavaScript;
// the element (src/widgets/exercise/view.ts) keeps the statement and replaces
// the starter listing with the editor.
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import type MarkdownIt from 'markdown-it';
import type { RenderEnv } from './markdown.ts';

// Markdown keeps a line holding one custom element inside a paragraph; the block
// content (statement, code) may not sit in a <p>, so the wrapper goes with the tag.
const EXERCISE_TAG =
  /<p>\s*<sb-exercise([^>]*)>\s*<\/sb-exercise>\s*<\/p>|<sb-exercise([^>]*)>\s*<\/sb-exercise>/g;
const EXERCISE_ID = /^[a-z0-9]+(?:-[a-z0-9]+)*$/;

function escapeHtml(text: string): string {
  return text.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
}

/**
 * Statement headings sit under the chapter's "## Exercise" section: `#` becomes
 * h3, `##` h4, and so on, so the page keeps one h1 and a correct outline.
 */
function demoteHeadings(html: string): string {
  return html.replace(
    /<(\/?)h([1-6])\b/g,
    (_all, slash: string, level: string) => `<${slash}h${Math.min(6, Number(level) + 2)}`,
  );
}

/**
 * Replaces each empty `<sb-exercise exercise="ID">` in a rendered chapter with the
 * element holding its statement and starter code. A missing or malformed id, or a
 * missing statement or starter file, fails the build with the chapter's name.
 */
export function embedExercises(
  md: MarkdownIt,
  html: string,
  env: RenderEnv,
  exercisesDir: string,
): { html: string; ids: string[] } {
  const ids: string[] = [];
  const out = html.replace(EXERCISE_TAG, (_all, inParagraph?: string, bare?: string) => {
    const attrs = inParagraph ?? bare ?? '';
    const id = /\bexercise="([^"]*)"/.exec(attrs)?.[1] ?? '';
    if (!EXERCISE_ID.test(id)) {
      throw new Error(
        `${env.file}: <sb-exercise> needs exercise="id" (lowercase-words), got "${id}"`,
      );
    }
    const folder = join(exercisesDir, id);
    const statementFile = join(folder, 'statement.md');
    const starterFile = join(folder, 'starter.wgsl');
    for (const file of [statementFile, starterFile]) {
      if (!existsSync(file)) throw new Error(`${env.file}: exercise "${id}" has no ${file}`);
    }
    ids.push(id);
    const statement = demoteHeadings(md.render(readFileSync(statementFile, 'utf8'), env));
    const starter = readFileSync(starterFile, 'utf8');
    return (
      `<sb-exercise${attrs}>` +
      `<div class="sb-exercise-statement">${statement}</div>` +
      `<details class="sb-exercise-starter"><summary>Starter code (WGSL)</summary>` +
      `<pre><code class="language-wgsl">${escapeHtml(starter)}</code></pre></details>` +
      `<p class="widget-fallback">Write your solution in the editor: it needs JavaScript, ` +
      `and running the checks needs WebGPU.</p>` +
      `</sb-exercise>`
    );
  });
  return { html: out, ids };
}
