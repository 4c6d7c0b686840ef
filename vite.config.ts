import { defineConfig } from 'vite';
import { VitePWA } from 'vite-plugin-pwa';
import { scatterbookChapters } from './src/book/build/vitePlugin.ts';
import { offlineReading } from './src/book/build/pwa.ts';
import { staticKernels } from './src/book/build/staticKernels.ts';

const root = import.meta.dirname;

export default defineConfig({
  root,
  publicDir: 'public',
  plugins: [scatterbookChapters(root), staticKernels(root), VitePWA(offlineReading())],
  server: { port: 5173, strictPort: false, host: 'localhost' },
  preview: { port: 4173, host: 'localhost' },
  build: { outDir: 'dist', emptyOutDir: true, target: 'es2022' },
  worker: { format: 'es' },
});
