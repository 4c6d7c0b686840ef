// Linked WGSL cached on disk, for the command line (Node only): `scatterbook render`
// spent 0.2–0.4 s of an idle machine's start-up (seconds under load) importing WESL and
// linking the scene kernel and the accumulation kernels, the same work every run for the
// same plan. This library links each variant once and keeps the WGSL in a file named by
// a hash of the whole shader library, the kernel and its conditions (variantKey), so an
// edited shader, another plan or another kernel never reads a stale file. The cache is a
// folder that git ignores (.cache/); a file that cannot be written only costs the link.
import { createHash } from 'node:crypto';
import { mkdirSync, readFileSync, renameSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import {
  linkLibraryKernel,
  variantKey,
  type LinkConditions,
  type PrelinkedKernels,
  type ShaderLibrary,
} from './link.ts';

/** A hash of every module of the library (path and source), in path order. */
export function libraryHash(library: ShaderLibrary): string {
  const hash = createHash('sha256');
  for (const path of Object.keys(library).sort()) hash.update(`${path}\0${library[path]}\0`);
  return hash.digest('hex');
}

/** The cache file of one linked variant. */
export function linkedFileName(
  libraryDigest: string,
  kernelPath: string,
  conditions: LinkConditions,
): string {
  const key = createHash('sha256')
    .update(`${libraryDigest}\0${variantKey(kernelPath, conditions)}`)
    .digest('hex')
    .slice(0, 32);
  return `${key}.wgsl`;
}

/**
 * Library kernels from `directory`'s cache, linked from `library` (and stored) on a miss.
 * Returns the kernels and how many variants were linked rather than read (for tests).
 */
export function diskCachedKernels(
  library: ShaderLibrary,
  directory: string,
): PrelinkedKernels & { readonly misses: () => number } {
  const digest = libraryHash(library);
  let misses = 0;
  return {
    misses: () => misses,
    prelinked: async (kernelPath, conditions) => {
      const path = join(directory, linkedFileName(digest, kernelPath, conditions));
      try {
        return readFileSync(path, 'utf8');
      } catch {
        misses += 1;
      }
      const code = await linkLibraryKernel(library, kernelPath, conditions);
      try {
        mkdirSync(directory, { recursive: true });
        // Written under a temporary name and renamed, so a concurrent run never reads half a file.
        const temporary = `${path}.${process.pid}.tmp`;
        writeFileSync(temporary, code);
        renameSync(temporary, path);
      } catch {
        // A read-only checkout: link every time.
      }
      return code;
    },
  };
}
