// HTML templates of the book's pages: the home page with the list of chapters,
// and a chapter page with its table of contents and previous/next links.
// Pages are complete without JavaScript; the script only adds widgets, quiz
// checking and the theme switch.
import type { ChapterSource } from './chapters.ts';
import type { TocEntry } from './markdown.ts';

export const SITE_TITLE = 'Scatterbook';
export const SITE_SUBTITLE = 'Light in participating media — an interactive textbook';

export function chapterPath(chapter: Pick<ChapterSource, 'slug'>): string {
  return `/chapters/${chapter.slug}.html`;
}

function escapeHtml(text: string): string {
  return text
    .replace(/&/g, '&amp;')
    .replace(/</g, '&lt;')
    .replace(/>/g, '&gt;')
    .replace(/"/g, '&quot;');
}

/**
 * Keeps the MathML (KaTeX's accessible copy of each formula) out of layout until the
 * HTML parser is done: Firefox lays a long page out while it is still arriving, and
 * an <msub> or <mfrac> cut off at the end of a network chunk has too few children
 * for that moment, which it logs as "Invalid markup: Incorrect number of children".
 * book.css hides `.sb-parsing .katex-mathml math`; DOMContentLoaded shows it. Without
 * JavaScript the class is never set and the MathML is there from the start.
 */
const PARSING_SCRIPT =
  '<script>document.documentElement.classList.add("sb-parsing");' +
  'document.addEventListener("DOMContentLoaded",function(){' +
  'document.documentElement.classList.remove("sb-parsing")})</script>';

export function shell(title: string, description: string, body: string, htmlClass = ''): string {
  return `<!doctype html>
<html lang="en"${htmlClass ? ` class="${htmlClass}"` : ''}>
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="description" content="${escapeHtml(description)}">
<title>${escapeHtml(title)}</title>
<link rel="icon" href="/favicon.svg" type="image/svg+xml">
<link rel="stylesheet" href="/src/book/styles/book.css">
${PARSING_SCRIPT}
<script type="module" src="/src/book/main.ts"></script>
</head>
<body>
<a class="skip-link" href="#content">Skip to content</a>
<header class="site-header">
  <a class="site-title" href="/index.html">${SITE_TITLE}</a>
  <span class="site-subtitle">${SITE_SUBTITLE}</span>
  <button type="button" class="theme-toggle" hidden aria-label="Switch between light and dark theme">Theme</button>
</header>
${body}
<footer class="site-footer">
  <p>${SITE_TITLE}: every figure is computed live from one WGSL shader library whose float64 TypeScript twin the tests hold it against.</p>
</footer>
</body>
</html>
`;
}

export function renderHomePage(
  chapters: readonly ChapterSource[],
  appendices: readonly (PageLink & { summary: string })[] = [],
): string {
  const items = chapters
    .map(
      (chapter) =>
        `<li><a href="${chapterPath(chapter)}"><span class="chapter-number">${chapter.number}</span>` +
        `<span class="chapter-title">${escapeHtml(chapter.title)}</span></a>` +
        `<p>${escapeHtml(chapter.summary)}</p></li>`,
    )
    .join('\n');
  const body = `<main id="content" class="home">
<h1>${SITE_TITLE}</h1>
<p class="lede">How light is absorbed, scattered and emitted in fog, smoke, milk, skin and CT volumes —
with live figures that show what accuracy costs in time.</p>
<p><a class="deck-link" href="/deck.html">Open the lecture demo deck</a>: every figure in lecture order, one per slide.</p>
<h2>Chapters</h2>
<ol class="chapter-list">
${items}
</ol>
${
  appendices.length
    ? `<h2>Appendices</h2>
<ul class="chapter-list appendix-list">
${appendices
  .map(
    (a, index) =>
      `<li><a href="${a.path}"><span class="chapter-number">${String.fromCharCode(65 + index)}</span><span class="chapter-title">${escapeHtml(a.title)}</span></a><p>${escapeHtml(a.summary)}</p></li>`,
  )
  .join('\n')}
</ul>`
    : ''
}
</main>`;
  return shell(`${SITE_TITLE} — ${SITE_SUBTITLE}`, SITE_SUBTITLE, body);
}

function renderToc(toc: readonly TocEntry[]): string {
  if (toc.length === 0) return '';
  const items = toc
    .map(
      (entry) =>
        `<li class="toc-level-${entry.level}"><a href="#${entry.id}">${escapeHtml(entry.text)}</a></li>`,
    )
    .join('');
  return `<nav class="toc" aria-label="On this page"><p class="toc-title">On this page</p><ol>${items}</ol></nav>`;
}

export interface PageLink {
  path: string;
  /** E.g. "2. Extinction and transmittance". */
  title: string;
}

export function chapterLink(chapter: ChapterSource): PageLink {
  return { path: chapterPath(chapter), title: `${chapter.number}. ${chapter.title}` };
}

function pagerLink(link: PageLink | undefined, rel: 'prev' | 'next'): string {
  if (!link) return '<span></span>';
  const label = rel === 'prev' ? 'Previous' : 'Next';
  return (
    `<a class="pager-${rel}" rel="${rel}" href="${link.path}">` +
    `<span class="pager-label">${label}</span>` +
    `<span class="pager-title">${escapeHtml(link.title)}</span></a>`
  );
}

export interface ArticlePage {
  /** Small line above the title, e.g. "Chapter 2" or "Appendix". */
  kicker: string;
  title: string;
  summary: string;
  html: string;
  toc: readonly TocEntry[];
  previous?: PageLink;
  next?: PageLink;
}

export function renderArticlePage(page: ArticlePage): string {
  const body = `<div class="chapter-layout">
${renderToc(page.toc)}
<main id="content" class="chapter">
<article>
<header class="chapter-header">
<p class="chapter-kicker">${escapeHtml(page.kicker)}</p>
<h1>${escapeHtml(page.title)}</h1>
<p class="chapter-summary">${escapeHtml(page.summary)}</p>
</header>
${page.html}
</article>
<nav class="pager" aria-label="Chapters">${pagerLink(page.previous, 'prev')}${pagerLink(page.next, 'next')}</nav>
</main>
</div>`;
  return shell(`${page.title} — ${SITE_TITLE}`, page.summary, body);
}
