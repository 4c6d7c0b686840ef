// The demo deck: every widget in lecture order as full-screen slides, each a
// deep link (`deck.html#slide=3`), with a one-line caption. Slides are data in
// each widget's definition (src/widgets/<name>/widget.ts); this module orders them.
import type { WidgetDefinition } from '../../widgets/base/definition.ts';
import { WIDGET_CATALOG, WIDGET_DEFINITIONS } from '../../widgets/catalog.ts';
import { parseParameters } from '../../widgets/parameters.ts';

export interface DeckSlide {
  title: string;
  /** Widget name without the `sb-` prefix. */
  widget: string;
  attributes: Readonly<Record<string, string>>;
  caption: string;
  /** Chapter slug the slide belongs to, for the "read more" link. */
  chapter: string;
}

/**
 * The slides of every widget definition (src/widgets/<name>/widget.ts), in lecture
 * order: by chapter (slugs start with the chapter number), then by each widget's
 * deckOrder within its chapter, then in the order the widget lists its slides.
 */
export function deckFrom(definitions: readonly WidgetDefinition[]): DeckSlide[] {
  const slides = definitions.flatMap((definition) =>
    (definition.slides ?? []).map((slide, index) => ({
      slide: { ...slide, widget: definition.entry.name },
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

export const DECK: readonly DeckSlide[] = deckFrom(WIDGET_DEFINITIONS);

/** Checks every slide against the widget catalog; a bad slide fails the build. */
export function validateDeck(slides: readonly DeckSlide[] = DECK): void {
  slides.forEach((slide, index) => {
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
