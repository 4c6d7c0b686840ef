// The widget registry for Node without Vite's import.meta.glob (the build's page
// generator, Playwright specs, the benchmarks): the folders of src/widgets that have
// a widget.ts, read with fs, each definition imported. The browser uses registry.ts,
// built from the same folders by a glob; tests/widgets/registry.test.ts checks that
// the two agree. Every widget.ts is DOM-free data plus a lazy load(), so importing
// them here loads no view code.
import { existsSync, readdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { registryFrom, type WidgetDefinition } from './base/definition.ts';
import type { WidgetEntry } from './parameters.ts';

const WIDGETS_FOLDER = dirname(fileURLToPath(import.meta.url));

/** Folders of src/widgets with a widget.ts, sorted. */
export const WIDGET_FOLDERS: readonly string[] = readdirSync(WIDGETS_FOLDER, {
  withFileTypes: true,
})
  .filter((item) => item.isDirectory() && existsSync(join(WIDGETS_FOLDER, item.name, 'widget.ts')))
  .map((item) => item.name)
  .sort();

export const WIDGET_DEFINITIONS: readonly WidgetDefinition[] = registryFrom(
  Object.fromEntries(
    await Promise.all(
      WIDGET_FOLDERS.map(
        async (name) =>
          [
            `./${name}/widget.ts`,
            (await import(`./${name}/widget.ts`)) as { widget?: WidgetDefinition },
          ] as const,
      ),
    ),
  ),
);

/** Each widget's schema by name (derived from the definitions). */
export const WIDGET_CATALOG: Readonly<Record<string, WidgetEntry>> = Object.fromEntries(
  WIDGET_DEFINITIONS.map((definition) => [definition.entry.name, definition.entry]),
);
