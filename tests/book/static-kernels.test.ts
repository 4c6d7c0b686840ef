// The kernels linked at build time (src/book/build/staticKernels.ts): a real Vite build
// with the plugin writes every variant of kernelVariants.ts and the map the page reads;
// each file must be what the Node linker (tests, command line) produces for its variant,
// so the page and the tests run the same WGSL, and the offline precache must take them.
// The development server's middleware answers with the same code. The page's lookup
// (src/gpu/prelinked.ts): a listed variant is fetched, a missing one is linked in the page
// with a warning, a failed fetch names the file. No page module reaches the linker or the
// library source but through an import on demand (the exercise's first check, a missing
// variant): the same property as the built chunks', on the module graph, fast.
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { build, createServer } from 'vite';
import { getManifest } from 'workbox-build';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { kernelVariants, SCENE_WIDGETS } from '../../src/book/build/kernelVariants.ts';
import { PRECACHE_MAX_FILE_BYTES, PRECACHE_PATTERNS } from '../../src/book/build/pwa.ts';
import { STATIC_KERNELS_MODULE, staticKernels } from '../../src/book/build/staticKernels.ts';
import { linkLibraryKernel, variantKey, type LinkConditions } from '../../src/gpu/link.ts';
import { prelinkedKernels } from '../../src/gpu/prelinked.ts';
import { GENERAL_CONDITIONS } from '../../src/scene/plan.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));

describe('the build links every kernel variant into a static file', () => {
  const out = mkdtempSync(join(tmpdir(), 'static-kernels-'));
  let files: Record<string, string> = {};
  let variants: Awaited<ReturnType<typeof kernelVariants>> = [];

  beforeAll(async () => {
    await build({
      configFile: false,
      root: ROOT,
      logLevel: 'silent',
      publicDir: false,
      plugins: [staticKernels(ROOT)],
      build: {
        outDir: out,
        emptyOutDir: true,
        minify: false,
        rollupOptions: {
          input: { kernels: STATIC_KERNELS_MODULE },
          // An application build drops an entry's exports; here the map is the product.
          preserveEntrySignatures: 'exports-only',
          output: { entryFileNames: 'kernels.js' },
        },
      },
    });
    const module = (await import(pathToFileURL(join(out, 'kernels.js')).href)) as {
      KERNEL_FILES: Record<string, string>;
    };
    files = module.KERNEL_FILES;
    variants = await kernelVariants(ROOT, SHADER_LIBRARY);
  }, 120_000);

  afterAll(() => rmSync(out, { recursive: true, force: true }));

  it('maps every enumerated variant, and every kernel of shaders/kernels/, to a file', () => {
    expect(Object.keys(files).sort()).toEqual(variants.map((v) => v.key));
    const kernels = Object.keys(SHADER_LIBRARY).filter((p) => p.startsWith('kernels/'));
    for (const kernel of kernels)
      expect(
        variants.some((v) => v.kernel === kernel),
        kernel,
      ).toBe(true);
    // The kernel single-scatter times against, and the plan of its default scene.
    expect(files[variantKey('kernels/scene-render.wesl', GENERAL_CONDITIONS)]).toBeDefined();
  });

  it('each file is the Node linker’s WGSL for its variant, named by its content', async () => {
    for (const variant of variants) {
      const file = files[variant.key]!;
      expect(file, variant.key).toMatch(/^assets\/kernels\/[\w-]+-[0-9a-f]{10}\.wgsl$/);
      const built = readFileSync(join(out, file), 'utf8');
      const linked = await linkLibraryKernel(SHADER_LIBRARY, variant.kernel, variant.conditions);
      expect(built === linked, `${variant.key} (${file})`).toBe(true);
    }
  });

  it('writes no other kernel file, and the offline precache takes every one', async () => {
    const written = readdirSync(join(out, 'assets', 'kernels')).map((f) => `assets/kernels/${f}`);
    expect(written.sort()).toEqual([...new Set(Object.values(files))].sort());
    const { manifestEntries } = await getManifest({
      globDirectory: out,
      globPatterns: PRECACHE_PATTERNS,
      maximumFileSizeToCacheInBytes: PRECACHE_MAX_FILE_BYTES,
    });
    const precached = new Set(manifestEntries?.map((entry) => entry.url));
    for (const file of written) expect(precached.has(file), file).toBe(true);
  });
});

describe('the development server', () => {
  it('links a variant on request, the same WGSL, under the same keys', async () => {
    const server = await createServer({
      configFile: false,
      root: ROOT,
      logLevel: 'silent',
      plugins: [staticKernels(ROOT)],
      server: { port: 0, strictPort: false, host: '127.0.0.1', ws: false },
    });
    try {
      await server.listen();
      const base = server.resolvedUrls?.local[0];
      expect(base).toBeDefined();
      const { KERNEL_FILES } = (await server.ssrLoadModule(STATIC_KERNELS_MODULE)) as {
        KERNEL_FILES: Record<string, string>;
      };
      const variants = await kernelVariants(ROOT, SHADER_LIBRARY);
      expect(Object.keys(KERNEL_FILES).sort()).toEqual(variants.map((v) => v.key));
      const scene = variants.find((v) => v.key.includes('?'))!;
      for (const variant of [variants[0]!, scene]) {
        const response = await fetch(new URL(KERNEL_FILES[variant.key]!, base));
        expect(response.status, variant.key).toBe(200);
        expect(await response.text()).toBe(
          await linkLibraryKernel(SHADER_LIBRARY, variant.kernel, variant.conditions),
        );
      }
    } finally {
      await server.close();
    }
  }, 60_000);
});

describe('the page’s lookup of a variant (prelinked.ts)', () => {
  const setup = (files: Record<string, string>, fetchText: (file: string) => Promise<string>) => {
    const calls = { fetched: [] as string[], linked: [] as string[], warnings: [] as string[] };
    const kernels = prelinkedKernels({
      files: () => Promise.resolve(files),
      fetchText: (file) => {
        calls.fetched.push(file);
        return fetchText(file);
      },
      linkFromSource: (kernel: string, conditions: LinkConditions) => {
        calls.linked.push(variantKey(kernel, conditions));
        return linkLibraryKernel(SHADER_LIBRARY, kernel, conditions);
      },
      warn: (message) => calls.warnings.push(message),
    });
    return { kernels, calls };
  };

  it('fetches a listed variant once, whatever the order or false entries of its conditions', async () => {
    const key = variantKey('kernels/scene-render.wesl', { media: true, emission: true });
    const { kernels, calls } = setup({ [key]: 'assets/kernels/x.wgsl' }, () =>
      Promise.resolve('// code'),
    );
    const a = await kernels.prelinked('kernels/scene-render.wesl', { media: true, emission: true });
    const b = await kernels.prelinked('kernels/scene-render.wesl', {
      emission: true,
      gridMedia: false,
      media: true,
    });
    expect([a, b]).toEqual(['// code', '// code']);
    expect(calls).toEqual({ fetched: ['assets/kernels/x.wgsl'], linked: [], warnings: [] });
  });

  it('links a variant the build lacks in the page, with a warning naming it', async () => {
    const { kernels, calls } = setup({}, () => Promise.reject(new Error('not reached')));
    const conditions = { media: true, lightPoint: true };
    const code = await kernels.prelinked('kernels/scene-render.wesl', conditions);
    expect(code).toBe(
      await linkLibraryKernel(SHADER_LIBRARY, 'kernels/scene-render.wesl', conditions),
    );
    await kernels.prelinked('kernels/scene-render.wesl', conditions);
    const key = 'kernels/scene-render.wesl?lightPoint,media';
    expect(calls.linked).toEqual([key]);
    expect(calls.fetched).toEqual([]);
    expect(calls.warnings).toHaveLength(1);
    expect(calls.warnings[0]).toContain(key);
  });

  it('a file that cannot be fetched is an error naming it, and is tried again next time', async () => {
    let fail = true;
    const { kernels, calls } = setup({ 'kernels/beer-law.wesl': 'assets/kernels/b.wgsl' }, () =>
      fail ? Promise.reject(new Error('HTTP 404')) : Promise.resolve('// beer'),
    );
    await expect(kernels.prelinked('kernels/beer-law.wesl', {})).rejects.toThrow(
      /kernels\/beer-law\.wesl from assets\/kernels\/b\.wgsl: Error: HTTP 404/,
    );
    fail = false;
    expect(await kernels.prelinked('kernels/beer-law.wesl', {})).toBe('// beer');
    expect(calls.fetched).toEqual(['assets/kernels/b.wgsl', 'assets/kernels/b.wgsl']);
    expect(calls.linked).toEqual([]);
  });
});

describe('what the page loads', () => {
  // The files a relative glob such as ./*/widget.ts matches (* stands within one segment).
  const expandGlob = (folder: string, pattern: string): string[] =>
    pattern
      .split('/')
      .reduce(
        (paths, segment) =>
          segment.includes('*')
            ? paths.flatMap((path) => {
                const escaped = segment.replace(/[.+?^$(){}|[\]\\]/g, '\\$&');
                const match = new RegExp('^' + escaped.replace(/\*/g, '[^/]*') + '$');
                return existsSync(path) && statSync(path).isDirectory()
                  ? readdirSync(path)
                      .filter((name) => match.test(name))
                      .map((name) => join(path, name))
                  : [];
              })
            : paths.map((path) => resolve(path, segment)),
        [folder],
      )
      .filter((path) => existsSync(path));

  /** What a module imports (`import type` left out), static, dynamic and by import.meta.glob. */
  const importsOf = (file: string): { target: string; dynamic: boolean }[] => {
    const source = readFileSync(file, 'utf8');
    const pattern =
      /\b(?:import|export)\s+(type\s+)?(?:[\w*{}\s,$]+?\s+from\s+)?['"]([^'"]+)['"]|\bimport\(\s*['"]([^'"]+)['"]\s*\)/g;
    const imports = [...source.matchAll(pattern)]
      .filter((match) => !match[1])
      .map((match) => ({ target: match[2] ?? match[3]!, dynamic: match[3] !== undefined }));
    for (const match of source.matchAll(/\bimport\.meta\.glob(?:<[^(]*>)?\(\s*['"]([^'"]+)['"]/g))
      for (const path of expandGlob(dirname(file), match[1]!))
        imports.push({ target: `./${relative(dirname(file), path)}`, dynamic: false });
    return imports;
  };

  it('no module the book or an embed loads reaches the linker or the library source until needed', () => {
    const sources = join(ROOT, 'src', 'gpu', 'shaderSources.ts');
    // The places that import them on demand (dynamic imports): linking from source
    // (link.ts), a variant the build lacks (staticKernels.ts) and an exercise's first
    // check (exerciseSource.ts: the grader links the student's code).
    const onDemand = new Set([
      join(ROOT, 'src', 'gpu', 'link.ts'),
      join(ROOT, 'src', 'gpu', 'staticKernels.ts'),
      join(ROOT, 'src', 'widgets', 'exercise', 'exerciseSource.ts'),
    ]);
    const seen = new Map<string, string | null>();
    const queue: [string, string | null][] = [
      [join(ROOT, 'src', 'book', 'main.ts'), null],
      [join(ROOT, 'src', 'book', 'embed.ts'), null],
    ];
    const problems: string[] = [];
    const chain = (file: string | null): string =>
      file ? `${chain(seen.get(file) ?? null)} → ${relative(ROOT, file)}` : '';
    while (queue.length > 0) {
      const [file, from] = queue.shift()!;
      if (seen.has(file) || !file.endsWith('.ts')) continue;
      seen.set(file, from);
      if (file === sources) {
        problems.push(`the library source: ${chain(file)}`);
        continue;
      }
      for (const { target, dynamic } of importsOf(file)) {
        if (dynamic && onDemand.has(file)) continue;
        if (target === 'wesl') problems.push(`the linker: ${chain(file)} → wesl`);
        else if (target.startsWith('.')) queue.push([resolve(dirname(file), target), file]);
      }
    }
    expect(seen.size).toBeGreaterThan(50);
    expect(problems).toEqual([]);
  });

  it('every widget folder that plans scenes is among the scene widgets', () => {
    const folders = readdirSync(join(ROOT, 'src', 'widgets'), { withFileTypes: true })
      .filter((entry) => entry.isDirectory())
      .map((entry) => entry.name);
    const planning = folders.filter((folder) =>
      readdirSync(join(ROOT, 'src', 'widgets', folder))
        .filter((file) => file.endsWith('.ts'))
        .some((file) =>
          /from '\.\.\/\.\.\/scene\/plan\.ts'/.test(
            readFileSync(join(ROOT, 'src', 'widgets', folder, file), 'utf8'),
          ),
        ),
    );
    expect(planning.length).toBeGreaterThan(0);
    expect(SCENE_WIDGETS.map((w) => w.entry.name).sort()).toEqual(planning.sort());
  });
});
