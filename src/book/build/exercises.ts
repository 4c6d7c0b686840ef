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

/**
 * Said before the statement, in the page as built: which browsers run an exercise's
 * checks (WebGPU), so that a student knows before writing code. The exercise element
 * replaces it, once it runs, with the same list and whether this browser can
 * (src/widgets/exercise/view.ts, buildGradingNote and checkGpu). Versions as in
 * README "Browser support": WebGPU shipped in Chrome/Edge 113, Safari 26, Firefox 141 (Windows).
 */
export const EXERCISE_BROWSERS =
  '<strong>Browsers.</strong> The checks of this exercise run on your GPU through WebGPU: ' +
  'Chrome or Edge (113 or later), Safari 26 or later, Firefox 141 or later on Windows ' +
  '(elsewhere once WebGPU is enabled). In other browsers you can write, save and download ' +
  'your solution, but the checks cannot run.';

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
      `<p class="sb-exercise-browsers">${EXERCISE_BROWSERS}</p>` +
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
