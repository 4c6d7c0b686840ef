// Stands in for src/gpu/staticKernels.ts under Vitest (vitest.config.ts): widget modules
// under test link their kernels from the library on disk, as the command line does.
// tests/book/static-kernels.test.ts holds the build's static files equal to this.
import type { KernelLibrary } from '../../src/gpu/link.ts';
import { SHADER_LIBRARY } from './shaderLibrary.ts';

export const STATIC_KERNELS: KernelLibrary = SHADER_LIBRARY;
