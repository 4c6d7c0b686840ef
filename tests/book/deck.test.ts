// The demo deck's slides are data checked against the widget catalog: a slide
// with an unknown widget or an invalid attribute fails the build.
import { describe, expect, it } from 'vitest';
import { DECK, validateDeck, type DeckSlide } from '../../src/book/build/deck.ts';
import { renderDeckPage } from '../../src/book/build/pages.ts';

const slide = (overrides: Partial<DeckSlide>): DeckSlide => ({
  title: 'T',
  widget: 'beer-law',
  attributes: {},
  caption: 'C',
  chapter: '02-extinction-and-transmittance',
  ...overrides,
});

describe('demo deck', () => {
  it('the shipped deck is valid', () => {
    expect(() => validateDeck(DECK)).not.toThrow();
    expect(DECK.length).toBeGreaterThan(0);
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

  it('renders one section per slide, only the first visible, each widget with its own id', () => {
    const html = renderDeckPage(DECK, new Map());
    expect(html.match(/<section class="deck-slide"/g)).toHaveLength(DECK.length);
    expect(html.match(/ hidden>/g)).toHaveLength(DECK.length - 1);
    expect(html).toContain('id="slide-1-widget"');
  });
});
