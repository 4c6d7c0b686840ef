// Vitest setup for every test file: release the Dawn device after the file's
// tests so that SwiftShader's worker threads stop before the process exits.
import { afterAll } from 'vitest';
import { releaseNodeDevice } from './nodeGpu.ts';

afterAll(async () => {
  await releaseNodeDevice();
});
