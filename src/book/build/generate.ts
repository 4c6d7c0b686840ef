// Builds every page of the book from chapters/*.md and writes them next to their
// sources (index.html at the root, chapters/NN-slug.html), where Vite picks them
// up as the inputs of a multi-page site. The generated HTML is not committed.
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { loadChapters, type ChapterSource } from './chapters.ts';
import {
  createMarkdown,
  createRenderEnv,
  renderChapterBody,
  resolveEquationReferences,
  type EquationLabel,
  type RenderedChapter,
} from './markdown.ts';
import {
  chapterLink,
  chapterPath,
  renderArticlePage,
  renderHomePage,
  SITE_TITLE,
  type PageLink,
} from './pages.ts';
import { APPENDIX_FILE, APPENDIX_SUMMARY, APPENDIX_TITLE, renderAppendix } from './appendix.ts';
import { loadShaderDocs } from './shaderDocs.ts';
import { DECK, renderDeckPage, validateDeck } from './deck.ts';
import { hostStyleSheet } from '../../widgets/base/definition.ts';
import { WIDGET_DEFINITIONS } from '../../widgets/catalog.ts';
import { markRoot, relativizeLinks } from './links.ts';
import { collectFigureLabels, resolveFigureReferences, type FigureLabel } from './figures.ts';
import { renderAnswerKey, sealQuizzes } from './quiz.ts';
import {
  EMBED_INDEX_FILE,
  EMBED_INDEX_SUMMARY,
  EMBED_INDEX_TITLE,
  planEmbeds,
  renderEmbedIndex,
  renderEmbedPage,
} from './embeds.ts';

const ANSWERS_FILE = 'appendix/answers.html';
const ANSWERS_TITLE = 'Answers to the questions';
const ANSWERS_SUMMARY =
  'Every question of the chapters with its answer, and why each other option is wrong.';

export interface BookPage {
  /** Path relative to the project root, e.g. `chapters/02-extinction-and-transmittance.html`. */
  file: string;
  html: string;
  chapter?: ChapterSource;
  widgets: string[];
}

export interface Book {
  chapters: ChapterSource[];
  pages: BookPage[];
  equations: Map<string, EquationLabel>;
}

export function buildBook(root: string): Book {
  const chapters = loadChapters(join(root, 'chapters'));
  const md = createMarkdown();
  const rendered = new Map<string, RenderedChapter>();
  const equations = new Map<string, EquationLabel>();
  const figures = new Map<string, FigureLabel>();
  for (const chapter of chapters) {
    const result = renderChapterBody(
      md,
      chapter.body,
      chapter.number,
      chapterPath(chapter),
      chapter.file,
      join(root, 'exercises'),
      chapter.bodyOffset ?? 0,
    );
    for (const equation of result.equations) {
      const existing = equations.get(equation.label);
      if (existing) {
        throw new Error(
          `${chapter.file}: equation label "${equation.label}" is also defined on ${existing.page}`,
        );
      }
      equations.set(equation.label, equation);
    }
    for (const figure of collectFigureLabels(result.html, chapterPath(chapter))) {
      const existing = figures.get(figure.label);
      if (existing) {
        throw new Error(`${chapter.file}: "${figure.label}" is also placed on ${existing.page}`);
      }
      figures.set(figure.label, figure);
    }
    rendered.set(chapter.slug, result);
  }
  const appendixLink: PageLink = { path: `/${APPENDIX_FILE}`, title: APPENDIX_TITLE };
  const embedIndexLink: PageLink = { path: `/${EMBED_INDEX_FILE}`, title: EMBED_INDEX_TITLE };
  const answersLink: PageLink = { path: `/${ANSWERS_FILE}`, title: ANSWERS_TITLE };
  const pages: BookPage[] = [
    {
      file: 'index.html',
      html: renderHomePage(chapters, [
        { ...appendixLink, summary: APPENDIX_SUMMARY },
        { ...embedIndexLink, summary: EMBED_INDEX_SUMMARY },
        { ...answersLink, summary: ANSWERS_SUMMARY },
      ]),
      widgets: [],
    },
  ];
  chapters.forEach((chapter, index) => {
    const result = rendered.get(chapter.slug);
    if (!result) return;
    const html = resolveFigureReferences(
      resolveEquationReferences(result.html, equations, chapterPath(chapter), chapter.file),
      figures,
      chapterPath(chapter),
      chapter.file,
    );
    const previous = chapters[index - 1];
    const next = chapters[index + 1];
    pages.push({
      file: `chapters/${chapter.slug}.html`,
      html: renderArticlePage({
        kicker: `Chapter ${chapter.number}`,
        title: chapter.title,
        summary: chapter.summary,
        html,
        toc: result.toc,
        previous: previous ? chapterLink(previous) : undefined,
        next: next ? chapterLink(next) : appendixLink,
      }),
      chapter,
      widgets: result.widgets,
    });
  });
  const last = chapters[chapters.length - 1];
  const appendix = renderAppendix(
    md,
    loadShaderDocs(join(root, 'shaders')),
    createRenderEnv('A', appendixLink.path, 'shaders/*.wesl'),
    chapters.map((chapter) => ({ number: chapter.number, path: chapterPath(chapter) })),
  );
  pages.push({
    file: APPENDIX_FILE,
    html: renderArticlePage({
      kicker: 'Appendix',
      title: APPENDIX_TITLE,
      summary: APPENDIX_SUMMARY,
      html: resolveEquationReferences(
        appendix.html,
        equations,
        appendixLink.path,
        'shaders/*.wesl',
      ),
      toc: appendix.toc,
      previous: last ? chapterLink(last) : undefined,
    }),
    widgets: [],
  });
  validateDeck(DECK);
  pages.push({
    file: 'deck.html',
    html: renderDeckPage(DECK, {
      chapterTitles: new Map(chapters.map((chapter) => [chapter.slug, chapter.title])),
      equations,
      sections: new Map(
        [...rendered].map(([slug, result]) => [slug, new Set(result.toc.map((entry) => entry.id))]),
      ),
    }),
    widgets: [...new Set(DECK.flatMap((slide) => (slide.kind === 'widget' ? [slide.widget] : [])))],
  });
  // One embed page per catalog widget (embeds.ts), then the appendix that lists them.
  const embeds = planEmbeds(
    pages.flatMap((page) => (page.chapter ? [{ chapter: page.chapter, html: page.html }] : [])),
  );
  for (const embed of embeds)
    pages.push({
      file: embed.file,
      html: renderEmbedPage(embed, SITE_TITLE),
      widgets: [embed.widget],
    });
  pages.push({
    file: EMBED_INDEX_FILE,
    html: renderArticlePage({
      kicker: 'Appendix',
      title: EMBED_INDEX_TITLE,
      summary: EMBED_INDEX_SUMMARY,
      html: renderEmbedIndex(embeds),
      toc: [
        { level: 2, id: 'embed-how', text: 'How to embed a figure' },
        { level: 2, id: 'embed-list', text: 'The figures' },
      ],
      previous: appendixLink,
      next: answersLink,
    }),
    widgets: [],
  });
  // The answer key: where a reader without JavaScript finds the answers (build/quiz.ts).
  pages.push({
    file: ANSWERS_FILE,
    html: renderArticlePage({
      kicker: 'Appendix',
      title: ANSWERS_TITLE,
      summary: ANSWERS_SUMMARY,
      html: resolveEquationReferences(
        renderAnswerKey(
          chapters.map((chapter) => ({
            title: chapter.title,
            number: chapter.number,
            page: chapterPath(chapter),
            quizzes: rendered.get(chapter.slug)?.quizzes ?? [],
          })),
        ),
        equations,
        answersLink.path,
        'chapters/*.md (quizzes)',
      ),
      toc: chapters
        .filter((chapter) => (rendered.get(chapter.slug)?.quizzes.length ?? 0) > 0)
        .map((chapter) => ({
          level: 2 as const,
          id: `answers-chapter-${chapter.number}`,
          text: `Chapter ${chapter.number}`,
        })),
      previous: embedIndexLink,
    }),
    widgets: [],
  });
  // Every page's links to other pages become relative to it (links.ts), so the site
  // works under any base path.
  // Quiz feedback is encoded last, once its equation references and links are final.
  for (const page of pages)
    page.html = sealQuizzes(markRoot(relativizeLinks(page.html, page.file), page.file), page.file);
  return { chapters, pages, equations };
}

/** Builds the book and writes its pages; returns the page files, for Vite's inputs. */
export function writeBook(root: string): string[] {
  const book = buildBook(root);
  for (const page of book.pages) {
    const path = join(root, page.file);
    mkdirSync(join(path, '..'), { recursive: true });
    writeFileSync(path, page.html);
  }
  return book.pages.map((page) => page.file);
}

/** The host element rules of every widget (served as a virtual style sheet by vitePlugin.ts). */
export function widgetHostStyles(): string {
  return hostStyleSheet(WIDGET_DEFINITIONS);
}
