// The widget registry is built from the folders, twice: by import.meta.glob for the
// browser (src/widgets/registry.ts) and with fs for Node without Vite
// (src/widgets/catalog.ts). Both must list exactly the folders that have a widget.ts,
// and each definition must be well-formed for the deck, the embeds and the page loader.
import { existsSync, readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { WIDGETS } from '../../src/widgets/registry.ts';
import { WIDGET_CATALOG, WIDGET_DEFINITIONS, WIDGET_FOLDERS } from '../../src/widgets/catalog.ts';
import {
  folderOf,
  hostStyleSheet,
  registryFrom,
  tagName,
} from '../../src/widgets/base/definition.ts';
import { DECK, deckFrom } from '../../src/book/build/deck.ts';

const WIDGETS_DIR = join(import.meta.dirname, '../../src/widgets');
const foldersWithDefinition = readdirSync(WIDGETS_DIR, { withFileTypes: true })
  .filter((item) => item.isDirectory() && existsSync(join(WIDGETS_DIR, item.name, 'widget.ts')))
  .map((item) => item.name)
  .sort();

describe('widget registry', () => {
  it('every widget folder has a widget.ts', () => {
    const folders = readdirSync(WIDGETS_DIR, { withFileTypes: true })
      .filter((item) => item.isDirectory() && item.name !== 'base')
      .map((item) => item.name)
      .sort();
    expect(foldersWithDefinition).toEqual(folders);
  });

  it('the glob registry and the fs registry list exactly those folders', () => {
    expect(WIDGETS.map((definition) => definition.entry.name)).toEqual(foldersWithDefinition);
    expect(WIDGET_DEFINITIONS.map((definition) => definition.entry.name)).toEqual(
      foldersWithDefinition,
    );
    expect(WIDGET_FOLDERS).toEqual(foldersWithDefinition);
    expect(Object.keys(WIDGET_CATALOG).sort()).toEqual(foldersWithDefinition);
  });

  it('refuses a definition named unlike its folder, or a module without one', () => {
    const beer = WIDGETS.find((definition) => definition.entry.name === 'beer-law');
    expect(beer).toBeDefined();
    if (!beer) return;
    expect(() => registryFrom({ './vre-ray/widget.ts': { widget: beer } })).toThrow(/folder/);
    expect(() => registryFrom({ './beer-law/widget.ts': {} })).toThrow(/does not export/);
    expect(folderOf('./beer-law/widget.ts')).toBe('beer-law');
    expect(() => folderOf('./beer-law/view.ts')).toThrow();
  });

  it('gives each widget its element name and host rule', () => {
    for (const definition of WIDGETS) {
      expect(tagName(definition)).toBe(`sb-${definition.entry.name}`);
    }
    const css = hostStyleSheet(WIDGETS);
    for (const definition of WIDGETS) {
      expect(css).toContain(`${tagName(definition)} {\n  display: block;\n}`);
    }
  });

  it('derives the deck: by chapter, then deckOrder, then the widget’s own slide order', () => {
    expect(DECK).toEqual(deckFrom(WIDGETS));
    const chapters = DECK.map((slide) => slide.chapter);
    expect(chapters).toEqual([...chapters].sort());
    // Chapter 3 shows the phase function before the sky and the sky before Mie, chapter 10 the path tracer
    // before photon mapping, chapter 11 the dipole before the translucent sphere.
    const order = (chapter: string): string[] => [
      ...new Set(
        DECK.filter((slide) => slide.chapter.startsWith(chapter)).flatMap((s) =>
          s.kind === 'widget' ? [s.widget] : [],
        ),
      ),
    ];
    expect(order('03')).toEqual(['hg-lobe', 'rayleigh-sky', 'mie-lobe']);
    expect(order('10')).toEqual(['volume-path-tracer', 'photon-map']);
    expect(order('11')).toEqual(['dipole-profile', 'translucent-render']);
  });

  it('keeps widget.ts free of view code: only load() imports it', () => {
    // Node imports every widget.ts (catalog.ts); a static import of the view, the
    // element or a backend would pull the DOM and GPU code into the build.
    for (const name of foldersWithDefinition) {
      const source = readFileSync(join(WIDGETS_DIR, name, 'widget.ts'), 'utf8');
      const staticImports = [...source.matchAll(/^import\s[^;]*?from\s+'([^']+)'/gms)].map(
        (match) => match[1] ?? '',
      );
      const viewCode = staticImports.filter((path) =>
        /(element|view|gpuBackend|cpuBackend|widgetElement|definedElement)\.ts$/.test(path),
      );
      expect(viewCode, `${name}/widget.ts`).toEqual([]);
    }
  });
});
