// Vite plugin: regenerates the book's HTML pages before a build or dev server
// starts, declares them as the multi-page inputs, and rebuilds them (with a full
// reload) whenever a chapter changes. It also serves the widgets' host style sheet
// (each widget's hostStyle, from its definition) as a virtual module.
//
// The page generator reads the widget registry, which imports every
// src/widgets/<name>/widget.ts found in the folders. Vite bundles this config for
// Node without import.meta.glob and without a TypeScript loader for such computed
// imports, so the generator is loaded through Vite's module runner (runnerImport),
// where both work.
import { join, resolve } from 'node:path';
import { runnerImport, type Plugin } from 'vite';
import type * as Generator from './generate.ts';

/** `import 'virtual:scatterbook/widget-hosts.css'`: `sb-<name> { display: block; }` per widget. */
export const WIDGET_HOSTS_CSS = 'virtual:scatterbook/widget-hosts.css';
const RESOLVED_WIDGET_HOSTS_CSS = `\0${WIDGET_HOSTS_CSS}`;

async function loadGenerator(root: string): Promise<typeof Generator> {
  const { module } = await runnerImport<typeof Generator>(
    resolve(root, 'src/book/build/generate.ts'),
    { root, configFile: false, logLevel: 'warn' },
  );
  return module;
}

export function scatterbookChapters(root: string): Plugin {
  let generator: Promise<typeof Generator> | null = null;
  const load = (): Promise<typeof Generator> => (generator ??= loadGenerator(root));
  return {
    name: 'scatterbook-chapters',
    async config() {
      const files = (await load()).writeBook(root);
      const input = Object.fromEntries(
        files.map((file) => [file.replace(/\.html$/, '').replace(/\//g, '-'), resolve(root, file)]),
      );
      return { build: { rollupOptions: { input } } };
    },
    resolveId(id) {
      return id === WIDGET_HOSTS_CSS ? RESOLVED_WIDGET_HOSTS_CSS : undefined;
    },
    async load(id) {
      return id === RESOLVED_WIDGET_HOSTS_CSS ? (await load()).widgetHostStyles() : undefined;
    },
    configureServer(server) {
      const chapters = join(root, 'chapters');
      // Exercise statements and starters are rendered into the chapters too.
      const exercises = join(root, 'exercises');
      server.watcher.add([chapters, exercises]);
      server.watcher.on('change', (file) => {
        const statement =
          file.startsWith(exercises) && (file.endsWith('.md') || file.endsWith('.wgsl'));
        if (!statement && (!file.startsWith(chapters) || !file.endsWith('.md'))) return;
        void load()
          .then((loaded) => {
            loaded.writeBook(root);
            server.ws.send({ type: 'full-reload' });
          })
          .catch((error: unknown) => server.config.logger.error(String(error)));
      });
    },
  };
}
