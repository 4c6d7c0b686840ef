// Markdown → HTML for one chapter, with math typeset by KaTeX at build time
// (no math JavaScript at run time), numbered equation labels, heading anchors for
// the table of contents, quizzes, and no-JavaScript fallbacks inside widgets.
import { fileURLToPath } from 'node:url';
import katex from 'katex';
import MarkdownIt from 'markdown-it';
import anchor from 'markdown-it-anchor';
import { tex } from '@mdit/plugin-tex';
import { parseQuiz, renderQuiz, type AnswerKeyEntry } from './quiz.ts';
import { WIDGET_CATALOG } from '../../widgets/catalog.ts';
import { embedExercises } from './exercises.ts';
import { mathmlArityProblems, repairMathml } from './mathml.ts';
import { figuresAndListings } from './figures.ts';

export interface TocEntry {
  level: 2 | 3;
  id: string;
  text: string;
}

export interface EquationLabel {
  label: string;
  /** Printed number, e.g. "2.3". */
  number: string;
  /** Page the equation lives on, e.g. `/chapters/02-extinction-and-transmittance.html`. */
  page: string;
}

export interface RenderedChapter {
  html: string;
  toc: TocEntry[];
  equations: EquationLabel[];
  widgets: string[];
  /** The chapter's quizzes, for the answer key (build/quiz.ts). */
  quizzes: AnswerKeyEntry[];
}

export interface RenderEnv {
  /** Prefix of equation numbers: the chapter number, or a letter for an appendix. */
  chapterNumber: number | string;
  page: string;
  file: string;
  equations: EquationLabel[];
  quizCount: number;
  quizzes: AnswerKeyEntry[];
  /** Lines of the source file before the Markdown body, so errors can cite file lines. */
  lineOffset: number;
}

const LABEL = /\\label\{([^}]+)\}/g;
const LABEL_NAME = /^eq:[a-z0-9-]+$/;

export function slugify(text: string): string {
  return text
    .toLowerCase()
    .normalize('NFKD')
    .replace(/[\u0300-\u036f]/g, '')
    .replace(/<[^>]*>/g, '')
    .replace(/[^a-z0-9]+/g, '-')
    .replace(/^-+|-+$/g, '');
}

function escapeHtml(text: string): string {
  return text
    .replace(/&/g, '&amp;')
    .replace(/</g, '&lt;')
    .replace(/>/g, '&gt;')
    .replace(/"/g, '&quot;');
}

function renderMath(content: string, displayMode: boolean, env: RenderEnv): string {
  const labels = [...content.matchAll(LABEL)].map((m) => m[1] ?? '');
  const body = content.replace(LABEL, '');
  let html: string;
  try {
    html = katex.renderToString(body, { displayMode, throwOnError: true, output: 'htmlAndMathml' });
  } catch (error) {
    throw new Error(`${env.file}: KaTeX cannot typeset "${content.trim()}": ${String(error)}`);
  }
  // KaTeX leaves an operator name in a script as two loose children (mathml.ts);
  // anything still malformed is refused here rather than logged by Firefox.
  html = repairMathml(html);
  const problem = mathmlArityProblems(html)[0];
  if (problem) {
    throw new Error(
      `${env.file}: KaTeX made invalid MathML for "${content.trim()}": <${problem.element}> ` +
        `has ${problem.children} children, MathML requires ${problem.expected}`,
    );
  }
  if (!displayMode) {
    if (labels.length) throw new Error(`${env.file}: \\label is only allowed in display math`);
    return html;
  }
  if (labels.length > 1) throw new Error(`${env.file}: one \\label per display equation`);
  const label = labels[0];
  if (label === undefined) return `<div class="equation">${html}</div>`;
  if (!LABEL_NAME.test(label)) {
    throw new Error(`${env.file}: equation label "${label}" must look like eq:lowercase-words`);
  }
  const number = `${env.chapterNumber}.${env.equations.length + 1}`;
  env.equations.push({ label, number, page: env.page });
  return (
    `<div class="equation" id="${label}">${html}` +
    `<a class="equation-number" href="#${label}" aria-label="Equation ${number}">(${number})</a></div>`
  );
}

/** The text a widget shows where it cannot run (no JavaScript, or before it loads). */
function widgetFallback(name: string): string {
  const entry = WIDGET_CATALOG[name];
  const title = entry ? entry.title : name;
  return (
    `<p class="widget-fallback">Interactive figure “${escapeHtml(title)}”: ` +
    `it needs JavaScript (and draws with WebGPU where the browser has it).</p>`
  );
}

export function createMarkdown(): MarkdownIt {
  const md = new MarkdownIt({ html: true, typographer: true, linkify: false });
  md.use(tex, {
    delimiters: 'dollars',
    render: (content: string, displayMode: boolean, env: unknown) =>
      renderMath(content, displayMode, env as RenderEnv),
  });
  md.use(anchor, { slugify, level: [2, 3], tabIndex: false });
  md.use(figuresAndListings);

  // A table scrolls inside its own box when a narrow screen cannot fit it (book.css
  // lays tables out compactly first); the page itself never scrolls sideways.
  md.renderer.rules.table_open = (tokens, index, options, _env, self) =>
    `<div class="table-scroll">${self.renderToken(tokens, index, options)}`;
  md.renderer.rules.table_close = (tokens, index, options, _env, self) =>
    `${self.renderToken(tokens, index, options)}</div>\n`;

  const defaultFence = md.renderer.rules.fence;
  md.renderer.rules.fence = (tokens, index, options, env, self) => {
    const token = tokens[index];
    if (token && token.info.trim() === 'quiz') {
      const renderEnv = env as RenderEnv;
      // token.map[0] is the fence's 0-based line; its body starts one line below.
      const firstLine = renderEnv.lineOffset + (token.map?.[0] ?? 0) + 2;
      return renderQuiz(md, parseQuiz(token.content, renderEnv.file, firstLine), renderEnv);
    }
    return defaultFence ? defaultFence(tokens, index, options, env, self) : '';
  };

  // Figure captions sit inside raw HTML blocks, which Markdown leaves alone; typeset
  // their inline Markdown and math too.
  const defaultHtmlBlock = md.renderer.rules.html_block;
  md.renderer.rules.html_block = (tokens, index, options, env, self) => {
    const html = defaultHtmlBlock ? defaultHtmlBlock(tokens, index, options, env, self) : '';
    return html.replace(
      /<figcaption>([\s\S]*?)<\/figcaption>/g,
      (_all, caption: string) => `<figcaption>${md.renderInline(caption.trim(), env)}</figcaption>`,
    );
  };
  return md;
}

export function createRenderEnv(
  chapterNumber: number | string,
  page: string,
  file: string,
): RenderEnv {
  return { chapterNumber, page, file, equations: [], quizCount: 0, quizzes: [], lineOffset: 0 };
}

/** Renders one chapter body. Equation references are resolved later, across chapters. */
export function renderChapterBody(
  md: MarkdownIt,
  body: string,
  chapterNumber: number,
  page: string,
  file: string,
  exercisesDir = fileURLToPath(new URL('../../../exercises', import.meta.url)),
  lineOffset = 0,
): RenderedChapter {
  const env = createRenderEnv(chapterNumber, page, file);
  env.lineOffset = lineOffset;
  const tokens = md.parse(body, env);
  const toc: TocEntry[] = [];
  tokens.forEach((token, index) => {
    if (token.type !== 'heading_open') return;
    const level = Number(token.tag.slice(1));
    if (level !== 2 && level !== 3) return;
    const inline = tokens[index + 1];
    toc.push({ level, id: token.attrGet('id') ?? '', text: inline?.content ?? '' });
  });
  let html = md.renderer.render(tokens, md.options, env);

  const widgets: string[] = [];
  // Exercises first: their statement goes inside the element (see exercises.ts).
  const exercises = embedExercises(md, html, env, exercisesDir);
  html = exercises.html;
  if (exercises.ids.length > 0) widgets.push('exercise');
  html = html.replace(/<(sb-[a-z0-9-]+)([^>]*)>\s*<\/\1>/g, (_all, tag: string, attrs: string) => {
    const name = tag.slice(3);
    if (!WIDGET_CATALOG[name]) {
      throw new Error(
        `${file}: unknown widget <${tag}>; known: ${Object.keys(WIDGET_CATALOG).join(', ')}`,
      );
    }
    widgets.push(name);
    return `<${tag}${attrs}>${widgetFallback(name)}</${tag}>`;
  });
  return { html, toc, equations: env.equations, widgets, quizzes: env.quizzes };
}

/**
 * Replaces each empty link to an equation, `[](#eq:NAME)`, with its number and a
 * link to its page. An unknown label is an error: a chapter may not cite an
 * equation that does not exist.
 */
export function resolveEquationReferences(
  html: string,
  labels: Map<string, EquationLabel>,
  currentPage: string,
  file: string,
): string {
  return html.replace(/<a href="#(eq:[^"]+)"><\/a>/g, (_all, label: string) => {
    const target = labels.get(label);
    if (!target) throw new Error(`${file}: reference to unknown equation label "${label}"`);
    const href = target.page === currentPage ? `#${label}` : `${target.page}#${label}`;
    return `<a class="eqref" href="${href}">(${target.number})</a>`;
  });
}
