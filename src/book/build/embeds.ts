// Embeddable figures: `embed/<widget>.html` for every widget in the catalog, the
// widget alone on a page without the site's chrome, for a lecturer's own slides or
// course page (issue 18, item 3). The page holds the widget as its chapter shows
// it: every instance of the widget in its first chapter, with the chapter's
// attributes and ids (`hg-lobe-1`, `hg-lobe-2`, …), so that a deep link copied in
// the chapter (`#hg-lobe-2.g=0.3&v=1`) opens the same figure in the same state once
// its path is changed to the embed. src/book/embed.ts picks the instance the hash
// names and loads the widget. Every link on these pages is relative, so the pages
// work under any base path.
import { WIDGET_CATALOG } from '../../widgets/catalog.ts';
import type { ChapterSource } from './chapters.ts';

/** Folder of the embed pages, relative to the book's root. */
export const EMBED_DIR = 'embed';
export const EMBED_INDEX_FILE = `${EMBED_DIR}/index.html`;
export const EMBED_INDEX_TITLE = 'Appendix: embedding the figures';
export const EMBED_INDEX_SUMMARY =
  'Every interactive figure as a page of its own, to put in slides or a course page with an iframe.';

export function embedFile(widget: string): string {
  return `${EMBED_DIR}/${widget}.html`;
}

/** One occurrence of a widget on a chapter page, as the chapter build rendered it. */
export interface WidgetInstance {
  /** The id the widget gets on its chapter page: `<name>-<n>`, n counting from 1 in page order. */
  id: string;
  /** The element's attributes, as written in the chapter (leading space included). */
  attributes: string;
  /** What the build put inside the element (fallback text, an exercise's statement). */
  content: string;
}

export interface EmbedPage {
  widget: string;
  file: string;
  /** The chapter the "Open in the book" link goes to. */
  chapter: ChapterSource;
  instances: WidgetInstance[];
}

function escapeHtml(text: string): string {
  return text
    .replace(/&/g, '&amp;')
    .replace(/</g, '&lt;')
    .replace(/>/g, '&gt;')
    .replace(/"/g, '&quot;');
}

/**
 * The instances of one widget in a rendered page, in page order, numbered as
 * WidgetElement numbers them (`<name>-<n>`; an explicit id attribute wins).
 */
export function widgetInstances(html: string, widget: string): WidgetInstance[] {
  const tag = `sb-${widget}`;
  const pattern = new RegExp(`<${tag}(\\s[^>]*)?>([\\s\\S]*?)</${tag}>`, 'g');
  return [...html.matchAll(pattern)].map((match, index) => {
    const attributes = match[1] ?? '';
    const explicitId = /\sid="([^"]*)"/.exec(attributes)?.[1];
    return {
      id: explicitId ?? `${widget}-${index + 1}`,
      attributes,
      content: match[2] ?? '',
    };
  });
}

/**
 * One embed page per catalog widget, from the chapters that show it (the first
 * chapter in reading order). A widget that no chapter shows has nothing to link
 * back to; that fails the build, as an unknown widget in a chapter does.
 */
export function planEmbeds(
  chapters: readonly { chapter: ChapterSource; html: string }[],
): EmbedPage[] {
  return Object.keys(WIDGET_CATALOG).map((widget) => {
    for (const { chapter, html } of chapters) {
      const instances = widgetInstances(html, widget);
      if (instances.length > 0) return { widget, file: embedFile(widget), chapter, instances };
    }
    throw new Error(
      `widget "${widget}" is in the catalog but in no chapter: its embed page would have no chapter to link to`,
    );
  });
}

/** Relative path from an embed page to a chapter page (both one folder below the root). */
function chapterHref(chapter: ChapterSource): string {
  return `../chapters/${chapter.slug}.html`;
}

function chapterLabel(chapter: ChapterSource): string {
  return `${chapter.number}. ${chapter.title}`;
}

/**
 * The embed page: no header, footer or theme button; the theme follows the
 * reader's system or the `theme=light|dark` hash key. The first instance is in the
 * page (it is what shows without JavaScript); the others wait in templates.
 */
export function renderEmbedPage(page: EmbedPage, siteTitle: string): string {
  const entry = WIDGET_CATALOG[page.widget];
  const title = entry?.title ?? page.widget;
  const tag = `sb-${page.widget}`;
  const element = (instance: WidgetInstance): string =>
    `<${tag} id="${escapeHtml(instance.id)}"${instance.attributes.replace(/\sid="[^"]*"/, '')}>${instance.content}</${tag}>`;
  const [first, ...others] = page.instances;
  const templates = page.instances
    .map(
      (instance) =>
        `<template class="embed-instance" data-instance="${escapeHtml(instance.id)}">${element(instance)}</template>`,
    )
    .join('\n');
  return `<!doctype html>
<html lang="en" class="sb-embed">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="description" content="${escapeHtml(entry?.description ?? title)}">
<title>${escapeHtml(title)} — ${escapeHtml(siteTitle)}</title>
<link rel="icon" href="../favicon.svg" type="image/svg+xml">
<link rel="stylesheet" href="../src/book/styles/book.css">
<link rel="stylesheet" href="../src/book/styles/embed.css">
<script type="module" src="../src/book/embed.ts"></script>
</head>
<body class="embed" data-widget="${escapeHtml(page.widget)}">
<main id="content" class="embed-main">
${first ? element(first) : ''}
</main>
${others.length > 0 ? templates : ''}
<p class="embed-source"><a class="embed-chapter-link" href="${chapterHref(page.chapter)}" target="_blank" rel="noopener">Open in the book: ${escapeHtml(chapterLabel(page.chapter))}</a></p>
</body>
</html>
`;
}

/**
 * The body of the appendix page that lists the embeds: one line per widget with
 * its embed page and its chapter, and how to put one in another page. Links are
 * relative to `embed/index.html`.
 */
export function renderEmbedIndex(pages: readonly EmbedPage[]): string {
  const rows = pages
    .map((page) => {
      const entry = WIDGET_CATALOG[page.widget];
      return (
        `<li><a href="${page.widget}.html"><code>embed/${page.widget}.html</code></a> — ` +
        `${escapeHtml(entry?.title ?? page.widget)} ` +
        `(<a href="${chapterHref(page.chapter)}">${escapeHtml(chapterLabel(page.chapter))}</a>)</li>`
      );
    })
    .join('\n');
  return `<p>Each figure of the book also exists as a page of its own that shows only the figure, sized to the frame it sits in, for a lecturer's slides or a course page. Press <kbd>F</kbd> inside it for presentation mode and the number keys for its presets, as in the chapters.</p>
<h2 id="embed-how">How to embed a figure</h2>
<p>Set the figure up in its chapter, open <strong>Copy</strong> above it and choose <strong>Copy embed code</strong>: that copies an <code>&lt;iframe&gt;</code> which opens the embed page in the same state. A link copied from a chapter also opens in an embed page once its path is changed from <code>chapters/…</code> to <code>embed/&lt;widget&gt;.html</code>: the state after <code>#</code> has the same format. Add <code>theme=dark</code> or <code>theme=light</code> to the part after <code>#</code> to fix the theme; otherwise it follows the reader's system.</p>
<h2 id="embed-list">The figures</h2>
<ul class="embed-list">
${rows}
</ul>`;
}
