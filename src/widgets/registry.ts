// Every widget of the book, built from the folders: each src/widgets/<name>/widget.ts
// exports its definition (base/definition.ts), and this glob finds them, so adding a
// widget is adding a folder. Vite and Vitest expand the glob; code that Node runs
// without Vite (the build's page generator, Playwright, the benchmarks) reads the
// same folders through catalog.ts, and tests/widgets/registry.test.ts checks that
// both list exactly the folders that have a widget.ts.
import { registryFrom, type WidgetDefinition } from './base/definition.ts';

export const WIDGETS: readonly WidgetDefinition[] = registryFrom(
  import.meta.glob<{ widget?: WidgetDefinition }>('./*/widget.ts', { eager: true }),
);

/** The definition of `sb-<name>`, if there is one. */
export function widgetNamed(name: string): WidgetDefinition | undefined {
  return WIDGETS.find((definition) => definition.entry.name === name);
}

/**
 * Loads a widget's code and defines `sb-<name>`. The element base is imported here,
 * lazily, so a page without widgets does not load it.
 */
export async function defineWidgetElement(definition: WidgetDefinition): Promise<void> {
  const [module, { defineFromModule }] = await Promise.all([
    definition.load(),
    import('./base/definedElement.ts'),
  ]);
  defineFromModule(definition, module);
}
