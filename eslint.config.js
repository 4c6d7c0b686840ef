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
    // Command-line entry points, benchmarks and build scripts print to the terminal.
    files: ['src/cli/**', 'bench/**', 'scripts/**', 'src/book/build/**'],
    rules: { 'no-console': 'off' },
  },
);
