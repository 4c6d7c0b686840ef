import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    include: ['tests/{reference,shaders,stability,book,grading,naga}/**/*.test.ts'],
    pool: 'forks',
    setupFiles: ['tests/support/setupGpu.ts'],
    testTimeout: 30_000,
    reporters: ['default', 'json'],
    outputFile: { json: 'test-results/vitest.json' },
  },
});
