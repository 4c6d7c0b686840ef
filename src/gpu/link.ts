// Links a kernel against the shared WGSL library with WESL (imports and @if
// conditions). In Node (tests, CLI, benchmarks) the library is read from disk
// (shaderSourcesNode.ts) and every kernel is linked here. The book's pages do not
// link library kernels: the build links every variant they use into static WGSL files
// (src/book/build/staticKernels.ts) and the page fetches them (staticKernels.ts), so
// they pass a PrelinkedKernels instead of the library source. The linker itself is
// imported on first use, so a page that only fetches static kernels never loads it;
// the exercise editor (student code) and a variant missing from the build do.

/** Library modules keyed by their path under `shaders/`, e.g. `transmittance.wesl`. */
export type ShaderLibrary = Readonly<Record<string, string>>;

export type LinkConditions = Readonly<Record<string, boolean>>;

/** Library kernels linked ahead of time (the build's static WGSL), keyed by variantKey. */
export interface PrelinkedKernels {
  readonly prelinked: (kernelPath: string, conditions: LinkConditions) => Promise<string>;
}

/** Where library kernels come from: the library source (linked here) or prelinked files. */
export type KernelLibrary = ShaderLibrary | PrelinkedKernels;

function isPrelinked(library: KernelLibrary): library is PrelinkedKernels {
  return typeof (library as Partial<PrelinkedKernels>).prelinked === 'function';
}

/**
 * The name of one linked variant: the kernel and the conditions that are on, sorted
 * (`kernels/scene-render.wesl?emission,media`). WESL takes a condition that is not
 * given as false, so `{a: false}` and `{}` are the same variant and the same key.
 */
export function variantKey(kernelPath: string, conditions: LinkConditions = {}): string {
  const on = Object.keys(conditions)
    .filter((name) => conditions[name])
    .sort();
  return on.length === 0 ? kernelPath : `${kernelPath}?${on.join(',')}`;
}

/**
 * Linked WGSL by the library's contents, root source and conditions: two libraries that
 * differ only in a module the root imports (a benchmark's modified copy, a test's) must
 * not share a result, and equal libraries loaded twice still do.
 */
const cache = new Map<string, Promise<string>>();
const libraryDigests = new WeakMap<ShaderLibrary, string>();

/** A 53-bit FNV-1a style digest of every module's path and source (once per library object). */
function libraryDigest(library: ShaderLibrary): string {
  let digest = libraryDigests.get(library);
  if (digest === undefined) {
    let h1 = 0x811c9dc5;
    let h2 = 0x01000193;
    for (const path of Object.keys(library).sort()) {
      const text = `${path}\u0000${library[path]}\u0000`;
      for (let i = 0; i < text.length; i++) {
        const c = text.charCodeAt(i);
        h1 = Math.imul(h1 ^ c, 0x01000193);
        h2 = Math.imul(h2 ^ c, 0x5bd1e995);
      }
    }
    digest = `${(h1 >>> 0).toString(16)}${(h2 >>> 0).toString(16)}`;
    libraryDigests.set(library, digest);
  }
  return digest;
}

type Wesl = typeof import('wesl');
type ModuleResolver = InstanceType<Wesl['RecordResolver']>;

/**
 * The library parsed once per library object (a RecordResolver keeps the parsed modules):
 * the build links dozens of variants of one kernel, and re-parsing the whole library
 * for each took most of the time.
 */
const parsedLibraries = new WeakMap<ShaderLibrary, ModuleResolver>();

function libraryResolver(wesl: Wesl, library: ShaderLibrary): ModuleResolver {
  let resolver = parsedLibraries.get(library);
  if (!resolver) {
    const sources: Record<string, string> = {};
    for (const [path, source] of Object.entries(library)) sources[`./${path}`] = source;
    resolver = new wesl.RecordResolver(sources, { keepComments: false });
    parsedLibraries.set(library, resolver);
  }
  return resolver;
}

/**
 * Returns plain WGSL for `rootSource` (a kernel that imports `package::module::fn`),
 * with every referenced library function and nothing else. Results are cached by the
 * library's contents, the source and the conditions.
 */
export function linkKernel(
  library: ShaderLibrary,
  rootSource: string,
  conditions: LinkConditions = {},
): Promise<string> {
  const key = `${libraryDigest(library)}\n${JSON.stringify(conditions)}\n${rootSource}`;
  let linked = cache.get(key);
  if (!linked) {
    linked = import('wesl')
      .then((wesl) => {
        const root = new wesl.RecordResolver(
          { './__root__.wesl': rootSource },
          { keepComments: false },
        );
        return wesl.link({
          resolver: new wesl.CompositeResolver([root, libraryResolver(wesl, library)]),
          rootModuleName: './__root__.wesl',
          conditions: { ...conditions },
        });
      })
      .then((result) => result.dest);
    cache.set(key, linked);
    linked.catch(() => cache.delete(key));
  }
  return linked;
}

/**
 * The WGSL of `shaders/kernels/NAME.wesl` under `conditions`: linked from the library
 * source, or the prelinked file of that variant.
 */
export function linkLibraryKernel(
  library: KernelLibrary,
  kernelPath: string,
  conditions: LinkConditions = {},
): Promise<string> {
  if (isPrelinked(library)) return library.prelinked(kernelPath, conditions);
  const source = library[kernelPath];
  if (source === undefined) {
    return Promise.reject(new Error(`no shader module "${kernelPath}" in the library`));
  }
  return linkKernel(library, source, conditions);
}
