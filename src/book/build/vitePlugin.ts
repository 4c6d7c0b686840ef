// Vite plugin: regenerates the book's HTML pages before a build or dev server
// starts, declares them as the multi-page inputs, and rebuilds them (with a full
// reload) whenever a chapter changes.
import { join, resolve } from 'node:path';
import type { Plugin } from 'vite';
import { writeBook } from './generate.ts';

export function scatterbookChapters(root: string): Plugin {
  return {
    name: 'scatterbook-chapters',
    config() {
      const files = writeBook(root);
      const input = Object.fromEntries(
        files.map((file) => [file.replace(/\.html$/, '').replace(/\//g, '-'), resolve(root, file)]),
      );
      return { build: { rollupOptions: { input } } };
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
        try {
          writeBook(root);
          server.ws.send({ type: 'full-reload' });
        } catch (error) {
          server.config.logger.error(String(error));
        }
      });
    },
  };
}
