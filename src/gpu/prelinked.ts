// Kernels from the build's static WGSL files (src/book/build/staticKernels.ts), looked
// up by variant: the page fetches the file of the kernel and conditions it asks for.
// A variant the build did not enumerate (a plan no widget setting, preset, slide or
// example scene produces) still works: the linker and the library source are loaded
// on demand, once, and the variant is linked in the page, with a console warning that
// names it so that it can be added to src/book/build/kernelVariants.ts. A file that
// cannot be fetched is an error that names the file.
import { variantKey, type LinkConditions, type PrelinkedKernels } from './link.ts';

export interface PrelinkedSources {
  /** variantKey → path of the file (under the site root); read once, on first use. */
  files(): Promise<Readonly<Record<string, string>>>;
  /** The text of a file named in `files`. */
  fetchText(file: string): Promise<string>;
  /** Links a variant missing from `files` (the linker is loaded only then). */
  linkFromSource(kernelPath: string, conditions: LinkConditions): Promise<string>;
  warn?: (message: string) => void;
}

export function prelinkedKernels(sources: PrelinkedSources): PrelinkedKernels {
  const loaded = new Map<string, Promise<string>>();
  const warn = sources.warn ?? ((message: string) => console.warn(message));
  let files: Promise<Readonly<Record<string, string>>> | null = null;
  const fileMap = (): Promise<Readonly<Record<string, string>>> => {
    if (!files) {
      files = sources.files();
      files.catch(() => (files = null));
    }
    return files;
  };
  const load = async (
    kernelPath: string,
    conditions: LinkConditions,
    key: string,
  ): Promise<string> => {
    const file = (await fileMap())[key];
    if (file === undefined) {
      warn(
        `Kernel variant ${key} is not among the build's static kernels; linking it in the page ` +
          '(loads the WESL linker and the shader library; add the scene to src/book/build/kernelVariants.ts)',
      );
      return sources.linkFromSource(kernelPath, conditions);
    }
    return sources.fetchText(file).catch((error: unknown) => {
      throw new Error(`could not load the kernel ${key} from ${file}: ${String(error)}`);
    });
  };
  return {
    prelinked(kernelPath, conditions) {
      const key = variantKey(kernelPath, conditions);
      let code = loaded.get(key);
      if (!code) {
        code = load(kernelPath, conditions, key);
        loaded.set(key, code);
        // A failed fetch (offline before the first visit finished) is tried again next time.
        code.catch(() => loaded.delete(key));
      }
      return code;
    },
  };
}
