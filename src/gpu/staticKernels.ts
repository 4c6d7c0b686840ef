// The kernels of the book's pages: the static WGSL files the build linked
// (src/book/build/staticKernels.ts), fetched under the site root. Widgets pass
// STATIC_KERNELS where Node code passes the library source (src/gpu/link.ts).
// (In Vitest, tests/support/staticKernels.ts stands in for this module: the tests
// link from source, and tests/book/static-kernels.test.ts holds the built files equal.)
import { siteUrl } from '../widgets/base/siteUrl.ts';
import { linkLibraryKernel, type KernelLibrary } from './link.ts';
import { prelinkedKernels } from './prelinked.ts';

export const STATIC_KERNELS: KernelLibrary = prelinkedKernels({
  // Imported when first needed, not at the top: the book's build configuration bundles
  // the widget modules (their definitions load them) and cannot resolve a virtual module.
  files: async () => (await import('virtual:static-kernels')).KERNEL_FILES,
  async fetchText(file) {
    const response = await fetch(siteUrl(file));
    if (!response.ok) throw new Error(`HTTP ${response.status}`);
    return response.text();
  },
  async linkFromSource(kernelPath, conditions) {
    const { SHADER_LIBRARY } = await import('./shaderSources.ts');
    return linkLibraryKernel(SHADER_LIBRARY, kernelPath, conditions);
  },
});
