// The shader library as the tests see it: read from disk, linked by the same
// function the browser uses.
import { fileURLToPath } from 'node:url';
import { loadShaderLibrary } from '../../src/gpu/shaderSourcesNode.ts';

export const SHADERS_DIRECTORY = fileURLToPath(new URL('../../shaders', import.meta.url));
export const SHADER_LIBRARY = loadShaderLibrary(SHADERS_DIRECTORY);
