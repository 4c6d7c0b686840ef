// For Vitest (vitest.config.ts): widget modules under test take their kernels from
// `replacement` (tests/support/staticKernels.ts, the library on disk) instead of
// src/gpu/staticKernels.ts, which fetches the build's static WGSL files from a page.
// Kept apart from staticKernels.ts so that loading the test config does not load the
// widgets and the planner.
import { dirname, join, resolve } from 'node:path';
import type { Plugin } from 'vite';

export function staticKernelsFromSource(root: string, replacement: string): Plugin {
  const browserModule = join(root, 'src', 'gpu', 'staticKernels.ts');
  return {
    name: 'scatterbook-static-kernels-from-source',
    enforce: 'pre',
    resolveId(source, importer) {
      if (!importer || !source.startsWith('.') || !source.endsWith('/staticKernels.ts'))
        return undefined;
      return resolve(dirname(importer), source) === browserModule ? replacement : undefined;
    },
  };
}
