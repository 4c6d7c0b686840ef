import { fileURLToPath } from 'node:url';
import { defineConfig } from 'vitest/config';
import { staticKernelsFromSource } from './src/book/build/staticKernelsFromSource.ts';

const root = import.meta.dirname;

export default defineConfig({
  // Widget modules under test link from the library on disk (the page fetches the
  // build's static WGSL; tests/book/static-kernels.test.ts holds the two equal).
  plugins: [
    staticKernelsFromSource(
      root,
      fileURLToPath(new URL('tests/support/staticKernels.ts', import.meta.url)),
    ),
  ],
  test: {
    include: ['tests/{reference,shaders,stability,book,grading,naga,widgets,bench}/**/*.test.ts'],
    pool: 'forks',
    setupFiles: ['tests/support/setupGpu.ts'],
    testTimeout: 30_000,
    reporters: ['default', 'json'],
    outputFile: { json: 'test-results/vitest.json' },
  },
});
