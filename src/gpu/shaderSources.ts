// The shader library as bundled by Vite for the browser: every `shaders/**/*.wesl`
// as text, keyed by its path under `shaders/`.
import type { ShaderLibrary } from './link.ts';

const modules = import.meta.glob('../../shaders/**/*.wesl', {
  query: '?raw',
  import: 'default',
  eager: true,
}) as Record<string, string>;

export const SHADER_LIBRARY: ShaderLibrary = Object.fromEntries(
  Object.entries(modules).map(([path, source]) => [path.replace(/^.*\/shaders\//, ''), source]),
);
