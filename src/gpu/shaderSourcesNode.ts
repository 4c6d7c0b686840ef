// The shader library read from disk, for Node (tests, CLI, benchmarks).
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join, relative } from 'node:path';
import type { ShaderLibrary } from './link.ts';

export function loadShaderLibrary(directory: string): ShaderLibrary {
  const library: Record<string, string> = {};
  const visit = (folder: string): void => {
    for (const name of readdirSync(folder)) {
      const path = join(folder, name);
      if (statSync(path).isDirectory()) visit(path);
      else if (name.endsWith('.wesl'))
        library[relative(directory, path).split('\\').join('/')] = readFileSync(path, 'utf8');
    }
  };
  visit(directory);
  return library;
}
