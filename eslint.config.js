// Lint rules: typescript-eslint's type-aware recommended set, plus the project's
// rules from STYLE.md (no console.log or debugger left in shipped code).
import js from '@eslint/js';
import tseslint from 'typescript-eslint';
import globals from 'globals';

export default tseslint.config(
  {
    ignores: [
      'node_modules',
      'dist',
      'test-results',
      'playwright-report',
      'bench/results',
      '.cache',
    ],
  },
  js.configs.recommended,
  ...tseslint.configs.recommended,
  {
    languageOptions: { globals: { ...globals.browser } },
  },
  {
    files: [
      'scripts/**',
      'tests/**',
      'bench/**',
      '*.config.{js,ts}',
      'src/cli/**',
      'src/book/build/**',
    ],
    languageOptions: { globals: { ...globals.node } },
  },
  {
    rules: {
      'no-console': ['error', { allow: ['warn', 'error'] }],
      'no-debugger': 'error',
      '@typescript-eslint/no-unused-vars': ['error', { argsIgnorePattern: '^_' }],
    },
  },
  {
    // Shipped code takes 2D contexts through context2d (src/widgets/base/canvas2d.ts):
    // rasterised on the CPU, not in the GPU process beside WebGPU (issue 23).
    files: ['src/**'],
    ignores: ['src/cli/**', 'src/book/build/**'],
    rules: {
      'no-restricted-syntax': [
        'error',
        {
          selector: "CallExpression[callee.property.name='getContext'][arguments.0.value='2d']",
          message:
            'Take a 2D context with context2d() from src/widgets/base/canvas2d.ts (CPU-rasterised).',
        },
      ],
    },
  },
  {
    // Command-line entry points, benchmarks and build scripts print to the terminal.
    files: ['src/cli/**', 'bench/**', 'scripts/**', 'src/book/build/**'],
    rules: { 'no-console': 'off' },
  },
);
