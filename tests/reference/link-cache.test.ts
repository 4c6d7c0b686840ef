// The command line's disk cache of linked WGSL (src/gpu/linkCacheNode.ts): a hit returns
// exactly what linking returns, a second process (a new cache object) reads the file
// instead of linking, and another plan or an edited shader is a different file.
import { mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { linkLibraryKernel } from '../../src/gpu/link.ts';
import { diskCachedKernels, linkedFileName, libraryHash } from '../../src/gpu/linkCacheNode.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

const directory = mkdtempSync(join(tmpdir(), 'scatterbook-wgsl-'));
afterAll(() => rmSync(directory, { recursive: true, force: true }));

const KERNEL = 'kernels/scene-render.wesl';
const PLAN = {
  media: true,
  homogeneousClosedForm: true,
  volumeScattering: true,
  lightDirectional: true,
};

describe('linked WGSL cached on disk', () => {
  it('a miss links and stores, a new cache object reads the same WGSL back without linking', async () => {
    const first = diskCachedKernels(SHADER_LIBRARY, directory);
    const linked = await first.prelinked(KERNEL, PLAN);
    expect(linked).toBe(await linkLibraryKernel(SHADER_LIBRARY, KERNEL, PLAN));
    expect(first.misses()).toBe(1);
    expect(readdirSync(directory)).toEqual([
      linkedFileName(libraryHash(SHADER_LIBRARY), KERNEL, PLAN),
    ]);
    const second = diskCachedKernels(SHADER_LIBRARY, directory);
    expect(await second.prelinked(KERNEL, PLAN)).toBe(linked);
    expect(second.misses()).toBe(0);
  });

  it('another plan and an edited library are other files', async () => {
    const cache = diskCachedKernels(SHADER_LIBRARY, directory);
    const other = await cache.prelinked(KERNEL, { ...PLAN, pathTracing: true });
    expect(cache.misses()).toBe(1);
    expect(other).not.toBe(await cache.prelinked(KERNEL, PLAN));
    const edited = { ...SHADER_LIBRARY, 'rng.wesl': `${SHADER_LIBRARY['rng.wesl']}\n// edited\n` };
    expect(libraryHash(edited)).not.toBe(libraryHash(SHADER_LIBRARY));
    const editedCache = diskCachedKernels(edited, directory);
    await editedCache.prelinked(KERNEL, PLAN);
    expect(editedCache.misses()).toBe(1);
  });

  it('the in-memory link cache tells apart libraries that differ only in a module the kernel imports', async () => {
    // Only geometry.wesl differs, so the kernel's own source and the conditions are the
    // same: a cache keyed by those alone returned the first library's WGSL for both.
    const original = await linkLibraryKernel(SHADER_LIBRARY, KERNEL, PLAN);
    const changed = {
      ...SHADER_LIBRARY,
      'geometry.wesl': SHADER_LIBRARY['geometry.wesl']!.replace(
        'const RAY_T_LIMIT: f32 = 1e17;',
        'const RAY_T_LIMIT: f32 = 2e17;',
      ),
    };
    expect(changed['geometry.wesl']).not.toBe(SHADER_LIBRARY['geometry.wesl']);
    const relinked = await linkLibraryKernel(changed, KERNEL, PLAN);
    expect(relinked).toContain('2e17');
    expect(original).not.toContain('2e17');
    // Equal contents in another object share the linked result.
    expect(await linkLibraryKernel({ ...SHADER_LIBRARY }, KERNEL, PLAN)).toBe(original);
  });
});
