// Links a kernel against the shared WGSL library with WESL (imports and @if
// conditions). The same function runs in the browser (sources bundled by Vite,
// see shaderSources.ts) and in Node (sources read from disk, see
// shaderSourcesNode.ts), so tests link exactly what the widgets link.
import { link } from 'wesl';

/** Library modules keyed by their path under `shaders/`, e.g. `transmittance.wesl`. */
export type ShaderLibrary = Readonly<Record<string, string>>;

export type LinkConditions = Readonly<Record<string, boolean>>;

const cache = new Map<string, Promise<string>>();

/**
 * Returns plain WGSL for `rootSource` (a kernel that imports `package::module::fn`),
 * with every referenced library function and nothing else. Results are cached by
 * source and conditions.
 */
export function linkKernel(
  library: ShaderLibrary,
  rootSource: string,
  conditions: LinkConditions = {},
): Promise<string> {
  const key = `${JSON.stringify(conditions)}\n${rootSource}`;
  let linked = cache.get(key);
  if (!linked) {
    const weslSrc: Record<string, string> = { './__root__.wesl': rootSource };
    for (const [path, source] of Object.entries(library)) weslSrc[`./${path}`] = source;
    linked = link({
      weslSrc,
      rootModuleName: './__root__.wesl',
      conditions: { ...conditions },
      keepComments: false,
    }).then((result) => result.dest);
    cache.set(key, linked);
    linked.catch(() => cache.delete(key));
  }
  return linked;
}

/** Loads a kernel from `shaders/kernels/NAME.wesl` in the library and links it. */
export function linkLibraryKernel(
  library: ShaderLibrary,
  kernelPath: string,
  conditions: LinkConditions = {},
): Promise<string> {
  const source = library[kernelPath];
  if (source === undefined) {
    return Promise.reject(new Error(`no shader module "${kernelPath}" in the library`));
  }
  return linkKernel(library, source, conditions);
}
