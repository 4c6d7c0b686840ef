// The lecture deck's slides are data checked against the widget catalog and the
// chapters: a slide with an unknown widget or an invalid attribute fails the build,
// every slide has speaker notes and every note names a slide, and an equation slide
// shows the chapter's own equation (up to how it is laid out on the slide).
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import {
  DECK,
  deckFrom,
  renderDeckPage,
  slideKey,
  validateDeck,
  type DeckContext,
  type DeckSlide,
} from '../../src/book/build/deck.ts';
import { EQUATION_SLIDES, equationLayoutFree } from '../../src/book/deck/equationSlides.ts';
import { SPEAKER_NOTES } from '../../src/book/deck/notes.ts';
import { slugify } from '../../src/book/build/markdown.ts';
import { WIDGET_DEFINITIONS } from '../../src/widgets/catalog.ts';

const CHAPTERS = join(import.meta.dirname, '../../chapters');

const slide = (overrides: Partial<Extract<DeckSlide, { kind: 'widget' }>>): DeckSlide => ({
  kind: 'widget',
  title: 'T',
  widget: 'beer-law',
  attributes: {},
  caption: 'C',
  chapter: '02-extinction-and-transmittance',
  ...overrides,
});

/** Every display equation of the chapters, by label: its TeX and its chapter slug. */
function chapterEquations(): Map<string, { tex: string; chapter: string }> {
  const equations = new Map<string, { tex: string; chapter: string }>();
  for (const file of readdirSync(CHAPTERS).filter((name) => name.endsWith('.md'))) {
    const text = readFileSync(join(CHAPTERS, file), 'utf8');
    for (const [, tex = ''] of text.matchAll(/\$\$([\s\S]*?)\$\$/g)) {
      const label = /\\label\{([^}]+)\}/.exec(tex)?.[1];
      if (label) equations.set(label, { tex, chapter: file.replace(/\.md$/, '') });
    }
  }
  return equations;
}

/** A context with every chapter equation numbered in order, as the build numbers them. */
function context(): DeckContext {
  const numbered = new Map<string, { label: string; number: string; page: string }>();
  for (const [label, { chapter }] of chapterEquations()) {
    numbered.set(label, {
      label,
      number: `${Number(chapter.slice(0, 2))}.x`,
      page: `/chapters/${chapter}.html`,
    });
  }
  return { chapterTitles: new Map(), equations: numbered };
}

describe('lecture deck', () => {
  it('the shipped deck is valid', () => {
    expect(() => validateDeck(DECK)).not.toThrow();
    expect(DECK.filter((s) => s.kind === 'widget').length).toBeGreaterThan(0);
  });

  it('rejects unknown widgets, out-of-range values and unknown attributes', () => {
    expect(() => validateDeck([slide({ widget: 'nope' })])).toThrow(
      /slide 1: unknown widget "nope"/,
    );
    expect(() => validateDeck([slide({ attributes: { thickness: '99' } })])).toThrow(
      /slide 1: .*clamped/,
    );
    expect(() => validateDeck([slide({ attributes: { colour: 'red' } })])).toThrow(
      /unknown attributes colour/,
    );
  });

  it('has equation slides for the RTE, the VRE, delta and ratio tracking and the dipole', () => {
    const labels = DECK.flatMap((s) =>
      s.kind === 'equation' ? s.equations.map((e) => e.label) : [],
    );
    for (const label of [
      'eq:rte',
      'eq:vre',
      'eq:delta-estimator',
      'eq:ratio-tracking',
      'eq:dipole-profile',
    ])
      expect(labels).toContain(label);
  });

  it('places each equation slide right before the widget slide it names', () => {
    for (const spec of EQUATION_SLIDES) {
      const at = DECK.findIndex((s) => s.kind === 'equation' && s.title === spec.title);
      const following = DECK.slice(at + 1).find((s) => s.kind === 'widget');
      expect(following && slideKey(following), spec.title).toBe(spec.before);
    }
    expect(() =>
      deckFrom(WIDGET_DEFINITIONS, [{ ...EQUATION_SLIDES[0]!, before: 'beer-law/No such slide' }]),
    ).toThrow(/no slide "beer-law\/No such slide"/);
  });

  it('shows each equation as the chapter writes it, only laid out in lines', () => {
    const chapters = chapterEquations();
    for (const spec of EQUATION_SLIDES) {
      for (const equation of spec.equations) {
        const source = chapters.get(equation.label);
        expect(source, `${spec.title}: ${equation.label} is in a chapter`).toBeDefined();
        expect(source?.chapter).toBe(spec.chapter);
        expect(equationLayoutFree(equation.tex), `${spec.title}: ${equation.label}`).toBe(
          equationLayoutFree(source?.tex ?? ''),
        );
      }
    }
  });

  it('takes out layout only: a changed symbol still differs', () => {
    const chapter = String.raw`a = b \;+\; \left[ c \right]`;
    expect(
      equationLayoutFree(
        String.raw`\begin{aligned} a ={}& b \\[0.4em] &+ \Bigl[ c \Bigr] \end{aligned}`,
      ),
    ).toBe(equationLayoutFree(chapter));
    expect(equationLayoutFree(String.raw`a = \underbrace{b}_{\text{note}} + [c]`)).toBe(
      equationLayoutFree(chapter),
    );
    expect(equationLayoutFree(String.raw`a = b - [c]`)).not.toBe(equationLayoutFree(chapter));
  });

  it('links each equation slide to a section its chapter has', () => {
    for (const spec of EQUATION_SLIDES) {
      const text = readFileSync(join(CHAPTERS, `${spec.chapter}.md`), 'utf8');
      const headings = [...text.matchAll(/^#{2,3} (.+)$/gm)].map((m) => slugify(m[1] ?? ''));
      expect(headings, spec.title).toContain(slugify(spec.section));
    }
  });

  it('has speaker notes for every slide, and every note names a slide', () => {
    const keys = DECK.map(slideKey);
    expect(keys.filter((key) => !SPEAKER_NOTES[key])).toEqual([]);
    expect(Object.keys(SPEAKER_NOTES).filter((key) => !keys.includes(key))).toEqual([]);
  });

  it('renders one section per slide, only the first visible, notes hidden, each widget with its own id', () => {
    const html = renderDeckPage(DECK, context());
    expect(html.match(/<section class="deck-slide/g)).toHaveLength(DECK.length);
    expect(html.match(/<section [^>]* hidden>/g)).toHaveLength(DECK.length - 1);
    expect(html.match(/<aside class="deck-notes"[^>]* hidden>/g)).toHaveLength(DECK.length);
    const first = DECK.findIndex((s) => s.kind === 'widget') + 1;
    expect(html).toContain(`id="slide-${first}-widget"`);
    expect(html).toContain('<math');
    expect(html).toContain('href="/chapters/04-the-volume-rendering-equation.html#eq:rte"');
    expect(html).toContain(
      'href="/chapters/04-the-volume-rendering-equation.html#the-radiative-transfer-equation"',
    );
  });

  it('refuses a slide without notes and an equation the book does not have', () => {
    expect(() => renderDeckPage(DECK, { ...context(), notes: {} })).toThrow(/no speaker notes/);
    expect(() => renderDeckPage(DECK, { ...context(), equations: new Map() })).toThrow(
      /no equation labelled/,
    );
  });
});
