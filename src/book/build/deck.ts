// The lecture deck: every widget slide in lecture order, with the book's key
// equations between them (src/book/deck/equationSlides.ts) and speaker notes for
// every slide (src/book/deck/notes.ts). Each slide is a deep link
// (`deck.html#slide=3`). Widget slides are data in each widget's definition
// (src/widgets/<name>/widget.ts); this module orders them, checks them and renders
// the page; src/book/deck.ts runs it.
import katex from 'katex';
import type { WidgetDefinition } from '../../widgets/base/definition.ts';
import { WIDGET_CATALOG, WIDGET_DEFINITIONS } from '../../widgets/catalog.ts';
import { parseParameters } from '../../widgets/parameters.ts';
import {
  EQUATION_SLIDES,
  type EquationSlideSpec,
  type SlideEquation,
  type SlideKey,
} from '../deck/equationSlides.ts';
import { SPEAKER_NOTES } from '../deck/notes.ts';
import { createMarkdown, createRenderEnv, slugify, type EquationLabel } from './markdown.ts';
import { mathmlArityProblems, repairMathml } from './mathml.ts';
import { shell, SITE_TITLE } from './pages.ts';

export interface WidgetSlide {
  kind: 'widget';
  title: string;
  /** Widget name without the `sb-` prefix. */
  widget: string;
  attributes: Readonly<Record<string, string>>;
  caption: string;
  /** Chapter slug the slide belongs to, for the "read more" link. */
  chapter: string;
}

export interface EquationSlide extends Omit<EquationSlideSpec, 'before'> {
  kind: 'equation';
}

export type DeckSlide = WidgetSlide | EquationSlide;

/** The name notes and equation slides use for a slide (see equationSlides.ts). */
export function slideKey(slide: DeckSlide): SlideKey {
  return slide.kind === 'widget' ? `${slide.widget}/${slide.title}` : `equation/${slide.title}`;
}

/**
 * The slides of every widget definition (src/widgets/<name>/widget.ts), in lecture
 * order: by chapter (slugs start with the chapter number), then by each widget's
 * deckOrder within its chapter, then in the order the widget lists its slides.
 */
export function widgetSlidesFrom(definitions: readonly WidgetDefinition[]): WidgetSlide[] {
  const slides = definitions.flatMap((definition) =>
    (definition.slides ?? []).map((slide, index) => ({
      slide: { kind: 'widget' as const, ...slide, widget: definition.entry.name },
      order: definition.deckOrder ?? 0,
      index,
    })),
  );
  slides.sort(
    (a, b) =>
      a.slide.chapter.localeCompare(b.slide.chapter, 'en') ||
      a.order - b.order ||
      a.slide.widget.localeCompare(b.slide.widget, 'en') ||
      a.index - b.index,
  );
  return slides.map(({ slide }) => slide);
}

/**
 * The whole deck: the widget slides with each equation slide placed before the widget
 * slide it names. An equation slide that names no slide fails the build.
 */
export function deckFrom(
  definitions: readonly WidgetDefinition[],
  equationSlides: readonly EquationSlideSpec[] = EQUATION_SLIDES,
): DeckSlide[] {
  const widgetSlides = widgetSlidesFrom(definitions);
  const keys = new Set(widgetSlides.map(slideKey));
  for (const spec of equationSlides) {
    if (!keys.has(spec.before))
      throw new Error(`equation slide "${spec.title}": no slide "${spec.before}" to precede`);
  }
  return widgetSlides.flatMap((slide) => [
    ...equationSlides
      .filter((spec) => spec.before === slideKey(slide))
      .map(({ before: _before, ...spec }): EquationSlide => ({ kind: 'equation', ...spec })),
    slide,
  ]);
}

export const DECK: readonly DeckSlide[] = deckFrom(WIDGET_DEFINITIONS);

/** Checks every widget slide against the widget catalog; a bad slide fails the build. */
export function validateDeck(slides: readonly DeckSlide[] = DECK): void {
  slides.forEach((slide, index) => {
    if (slide.kind !== 'widget') return;
    const entry = WIDGET_CATALOG[slide.widget];
    if (!entry) throw new Error(`deck slide ${index + 1}: unknown widget "${slide.widget}"`);
    const parsed = parseParameters(entry.parameters, (name) => slide.attributes[name]);
    if (parsed.warnings.length)
      throw new Error(`deck slide ${index + 1}: ${parsed.warnings.join('; ')}`);
    const unknown = Object.keys(slide.attributes).filter(
      (name) => !entry.parameters.some((p) => p.name === name || p.aliases?.includes(name)),
    );
    if (unknown.length)
      throw new Error(`deck slide ${index + 1}: unknown attributes ${unknown.join(', ')}`);
  });
}

export const DECK_PATH = '/deck.html';

/** What the deck page needs from the rest of the book. */
export interface DeckContext {
  /** Chapter slug → title. */
  chapterTitles: ReadonlyMap<string, string>;
  /** Equation label → its number and page (from the chapters). */
  equations: ReadonlyMap<string, EquationLabel>;
  /** Chapter slug → the ids of its section headings; checked when given. */
  sections?: ReadonlyMap<string, ReadonlySet<string>>;
  notes?: Readonly<Record<SlideKey, string>>;
}

function escapeHtml(text: string): string {
  return text
    .replace(/&/g, '&amp;')
    .replace(/</g, '&lt;')
    .replace(/>/g, '&gt;')
    .replace(/"/g, '&quot;');
}

function escapeAttribute(text: string): string {
  return text.replace(/&/g, '&amp;').replace(/"/g, '&quot;');
}

/** One display equation, typeset by KaTeX as the chapters are (markdown.ts), MathML repaired. */
function typesetEquation(equation: SlideEquation, context: DeckContext, where: string): string {
  const target = context.equations.get(equation.label);
  if (!target) throw new Error(`${where}: no equation labelled "${equation.label}" in the book`);
  let html: string;
  try {
    html = katex.renderToString(equation.tex, {
      displayMode: true,
      throwOnError: true,
      output: 'htmlAndMathml',
    });
  } catch (error) {
    throw new Error(`${where}: KaTeX cannot typeset ${equation.label}: ${String(error)}`);
  }
  html = repairMathml(html);
  const problem = mathmlArityProblems(html)[0];
  if (problem)
    throw new Error(`${where}: invalid MathML in ${equation.label} (<${problem.element}>)`);
  return (
    `<div class="deck-equation">${html}` +
    `<a class="equation-number" href="${target.page}#${equation.label}" ` +
    `aria-label="Equation ${target.number} in the book">(${target.number})</a></div>`
  );
}

/** Renders one slide's inner parts: the figure or the equations, the caption, the link. */
function slideBody(
  slide: DeckSlide,
  number: number,
  context: DeckContext,
  inline: (text: string) => string,
): { figure: string; caption: string } {
  const chapterTitle = context.chapterTitles.get(slide.chapter) ?? slide.chapter;
  if (slide.kind === 'widget') {
    const attributes = Object.entries(slide.attributes)
      .map(([name, value]) => ` ${name}="${escapeAttribute(value)}"`)
      .join('');
    return {
      figure:
        `<div class="deck-figure"><sb-${slide.widget} id="slide-${number}-widget"${attributes}>` +
        `<p class="widget-fallback">This slide's figure needs JavaScript.</p></sb-${slide.widget}></div>`,
      caption: `${escapeHtml(slide.caption)} <a href="/chapters/${slide.chapter}.html">Read: ${escapeHtml(chapterTitle)}</a>`,
    };
  }
  const where = `deck slide ${number} (${slide.title})`;
  const section = slugify(slide.section);
  const sections = context.sections?.get(slide.chapter);
  if (sections && !sections.has(section))
    throw new Error(`${where}: chapter ${slide.chapter} has no section "${slide.section}"`);
  return {
    figure:
      `<div class="deck-equations"><div class="deck-equations-inner">` +
      `${slide.equations.map((eq) => typesetEquation(eq, context, where)).join('')}</div></div>`,
    caption:
      `${inline(slide.caption)} <a href="/chapters/${slide.chapter}.html#${section}">` +
      `Read: ${escapeHtml(chapterTitle)} · ${escapeHtml(slide.section)}</a>`,
  };
}

/** The deck page: one slide visible at a time (src/book/deck.ts moves between them). */
export function renderDeckPage(slides: readonly DeckSlide[], context: DeckContext): string {
  const md = createMarkdown();
  const env = createRenderEnv('deck', DECK_PATH, 'src/book/deck');
  const inline = (text: string): string => md.renderInline(text, env);
  const notes = context.notes ?? SPEAKER_NOTES;
  const sections = slides
    .map((slide, index) => {
      const number = index + 1;
      const key = slideKey(slide);
      const note = notes[key];
      if (note === undefined)
        throw new Error(`deck slide ${number}: no speaker notes for "${key}"`);
      const { figure, caption } = slideBody(slide, number, context, inline);
      return `<section class="deck-slide deck-slide--${slide.kind}" id="slide-${number}" aria-labelledby="slide-${number}-title" data-slide-key="${escapeAttribute(key)}"${index === 0 ? '' : ' hidden'}>
<h2 class="deck-title" id="slide-${number}-title"><span class="deck-number">${number}</span> ${escapeHtml(slide.title)}</h2>
${figure}
<p class="deck-caption">${caption}</p>
<aside class="deck-notes" id="slide-${number}-notes" aria-label="Speaker notes, slide ${number}" hidden><p>${inline(note)}</p></aside>
</section>`;
    })
    .join('\n');
  const body = `<main id="content" class="deck" data-slides="${slides.length}">
<h1 class="sr-only">Lecture demo deck</h1>
<p class="sr-only deck-announcement" role="status" aria-live="polite" aria-atomic="true"></p>
<div class="deck-slides">
${sections}
</div>
<nav class="deck-nav" aria-label="Slides">
<button type="button" class="button deck-previous" aria-label="Previous slide" aria-keyshortcuts="ArrowLeft PageUp">← Previous</button>
<p class="deck-position"><label for="deck-jump">Slide</label> <input id="deck-jump" class="deck-jump" type="number" inputmode="numeric" min="1" max="${slides.length}" value="1"> of <span class="deck-count">${slides.length}</span></p>
<button type="button" class="button deck-next" aria-label="Next slide" aria-keyshortcuts="ArrowRight PageDown Space">Next →</button>
<span class="deck-tools">
<button type="button" class="button deck-notes-toggle" aria-expanded="false" aria-controls="slide-1-notes" aria-keyshortcuts="N">Notes</button>
<button type="button" class="button deck-present" aria-pressed="false" aria-keyshortcuts="P">Present</button>
</span>
</nav>
<p class="deck-help">← → Page Up/Down Space: slides · Home/End · N: speaker notes · P: present · inside a figure, F presents it and 1–9 recall presets · <a href="/deck.html?notes">presenter window</a></p>
</main>`;
  return shell(
    `Lecture demo deck — ${SITE_TITLE}`,
    'Every widget in lecture order as slides, with the key equations and speaker notes.',
    body,
    'deck-page',
  );
}
