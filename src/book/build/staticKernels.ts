// Vite plugin: the kernels the pages run, linked at build time into static WGSL files.
// Every variant of kernelVariants.ts is linked with the same call the tests and the
// command line use (src/gpu/link.ts, the library read from disk) and written to
// `assets/kernels/NAME-HASH.wgsl`, named by a hash of its content, so a changed kernel
// gets a new name and the offline precache (pwa.ts, which takes every .wgsl) holds
// every one. The virtual module `virtual:static-kernels` maps each variant's key to its
// file under the site root; the page fetches it (src/gpu/staticKernels.ts) and ships
// neither the linker nor the library source.
//
// In development (`npm start`) the map points at this plugin's middleware, which links
// a variant from the current shaders on request; the page takes the same path.
import { createHash } from 'node:crypto';
import { join, posix } from 'node:path';
import type { Plugin, ResolvedConfig } from 'vite';
import { linkLibraryKernel, type LinkConditions, type ShaderLibrary } from '../../gpu/link.ts';
import { loadShaderLibrary } from '../../gpu/shaderSourcesNode.ts';
import { kernelVariants, type KernelVariant } from './kernelVariants.ts';

export const STATIC_KERNELS_MODULE = 'virtual:static-kernels';
const RESOLVED_MODULE = `\0${STATIC_KERNELS_MODULE}`;
/** Where the development server answers with a freshly linked variant. */
const DEV_PREFIX = '@static-kernels/';

export interface LinkedVariant extends KernelVariant {
  code: string;
  /** Path under the site root, e.g. `assets/kernels/scene-render-0123456789.wgsl`. */
  file: string;
}

/** `assets/kernels/beer-law-<10 hex of SHA-256>.wgsl` for the kernel `kernels/beer-law.wesl`. */
export function staticFileName(kernel: string, code: string, assetsDir = 'assets'): string {
  const name = posix.basename(kernel, '.wesl');
  const hash = createHash('sha256').update(code).digest('hex').slice(0, 10);
  return posix.join(assetsDir, 'kernels', `${name}-${hash}.wgsl`);
}

/** Links every variant (variants with the same code share one file). */
export async function linkStaticKernels(
  root: string,
  assetsDir = 'assets',
  library: ShaderLibrary = loadShaderLibrary(join(root, 'shaders')),
): Promise<LinkedVariant[]> {
  const variants = await kernelVariants(root, library);
  return Promise.all(
    variants.map(async (variant) => {
      const code = await linkLibraryKernel(library, variant.kernel, variant.conditions);
      return { ...variant, code, file: staticFileName(variant.kernel, code, assetsDir) };
    }),
  );
}

/** The source of `virtual:static-kernels`: variant key → file under the site root. */
export function manifestModule(files: Readonly<Record<string, string>>): string {
  return `export const KERNEL_FILES = ${JSON.stringify(files, null, 2)};\n`;
}

/** The development server's address of a variant: `@static-kernels/NAME.wgsl?if=a,b`. */
export function devFileName(variant: KernelVariant): string {
  const on = Object.keys(variant.conditions).filter((name) => variant.conditions[name]);
  const query = on.length > 0 ? `?if=${on.sort().join(',')}` : '';
  return `${DEV_PREFIX}${posix.basename(variant.kernel, '.wesl')}.wgsl${query}`;
}

/** The variant a development address names, or null when it names none. */
export function parseDevUrl(url: string): { kernel: string; conditions: LinkConditions } | null {
  const at = url.indexOf(`/${DEV_PREFIX}`);
  if (at < 0) return null;
  const { pathname, searchParams } = new URL(url.slice(at), 'http://localhost');
  const name = /^\/@static-kernels\/([\w.-]+)\.wgsl$/.exec(pathname)?.[1];
  if (!name) return null;
  const on = (searchParams.get('if') ?? '').split(',').filter((c) => c !== '');
  return {
    kernel: `kernels/${name}.wesl`,
    conditions: Object.fromEntries(on.map((c) => [c, true])),
  };
}

export function staticKernels(root: string): Plugin {
  let config: ResolvedConfig | null = null;
  let linking: Promise<LinkedVariant[]> | null = null;
  let devFiles: Promise<Record<string, string>> | null = null;
  const shaders = join(root, 'shaders');
  return {
    name: 'scatterbook-static-kernels',
    configResolved(resolved) {
      config = resolved;
    },
    resolveId(id) {
      return id === STATIC_KERNELS_MODULE ? RESOLVED_MODULE : undefined;
    },
    async buildStart() {
      if (config?.command !== 'build') return;
      linking ??= linkStaticKernels(root, config.build.assetsDir);
      const emitted = new Set<string>();
      for (const variant of await linking) {
        if (emitted.has(variant.file)) continue;
        emitted.add(variant.file);
        this.emitFile({ type: 'asset', fileName: variant.file, source: variant.code });
      }
    },
    async load(id) {
      if (id !== RESOLVED_MODULE) return undefined;
      if (config?.command === 'build') {
        linking ??= linkStaticKernels(root, config.build.assetsDir);
        return manifestModule(Object.fromEntries((await linking).map((v) => [v.key, v.file])));
      }
      devFiles ??= kernelVariants(root, loadShaderLibrary(shaders)).then((variants) =>
        Object.fromEntries(variants.map((v) => [v.key, devFileName(v)])),
      );
      return manifestModule(await devFiles);
    },
    configureServer(server) {
      server.middlewares.use((request, response, next) => {
        const variant = parseDevUrl(request.url ?? '');
        if (!variant) return next();
        // Read the shaders on every request: an edited kernel is linked afresh.
        linkLibraryKernel(loadShaderLibrary(shaders), variant.kernel, variant.conditions).then(
          (code) => {
            response.setHeader('Content-Type', 'text/plain; charset=utf-8');
            response.setHeader('Cache-Control', 'no-store');
            response.end(code);
          },
          (error: unknown) => {
            response.statusCode = 500;
            response.end(`could not link ${variant.kernel}: ${String(error)}`);
          },
        );
      });
      // A shader edit reloads the page (the shaders are no longer modules Vite watches),
      // and a new kernel or a changed @if set enters the map.
      server.watcher.add(shaders);
      server.watcher.on('all', (_event, file) => {
        if (!file.startsWith(shaders) || !file.endsWith('.wesl')) return;
        devFiles = null;
        const module = server.moduleGraph.getModuleById(RESOLVED_MODULE);
        if (module) server.moduleGraph.invalidateModule(module);
        server.ws.send({ type: 'full-reload' });
      });
    },
  };
}
