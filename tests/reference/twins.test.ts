// DESIGN.md contract 1: every function of shaders/M.wesl has a float64 twin of
// the same name in src/reference/M.ts.
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { loadShaderDocs } from '../../src/book/build/shaderDocs.ts';

const SHADERS = fileURLToPath(new URL('../../shaders', import.meta.url));
const twins = import.meta.glob('../../src/reference/*.ts');

describe('every library function has a float64 twin', () => {
  for (const module of loadShaderDocs(SHADERS)) {
    it(`${module.name}: src/reference/${module.name}.ts exports each fn of shaders/${module.name}.wesl`, async () => {
      const load = twins[`../../src/reference/${module.name}.ts`];
      expect(load, `src/reference/${module.name}.ts exists`).toBeDefined();
      const twin = (await load?.()) as Record<string, unknown>;
      const missing = module.declarations
        .filter((d) => d.kind === 'fn')
        .map((d) => d.name)
        .filter((name) => typeof twin[name] !== 'function');
      expect(missing).toEqual([]);
    });
  }
});
