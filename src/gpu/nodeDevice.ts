// A WebGPU device in Node through Dawn (the `webgpu` npm package), for the tests
// and the command line. On machines without a GPU, Dawn uses SwiftShader through
// the Vulkan ICD that Debian's chromium ships (scripts/gpu-env.sh points
// VK_ICD_FILENAMES at it). Never imported by browser code.
import { create, globals } from 'webgpu';
import { installQuietPolling } from './quietPolling.ts';

Object.assign(globalThis, globals);
// dawn.node busy-polls pending promises; sleep between polls instead (quietPolling.ts).
installQuietPolling(globals);

let shared: Promise<GPUDevice> | null = null;
// The Dawn instance must outlive its devices: if it is garbage-collected while a
// device is in use, the process crashes. Keep it for the life of the worker.
let instance: GPU | null = null;

async function createDevice(): Promise<GPUDevice> {
  instance ??= create([]);
  const gpu = instance;
  const adapter = await gpu.requestAdapter();
  if (!adapter) {
    throw new Error(
      "Dawn found no WebGPU adapter. Install Debian's chromium (it ships SwiftShader) and run the tests " +
        'through `npm test`, which sets VK_ICD_FILENAMES=/usr/lib/chromium/vk_swiftshader_icd.json.',
    );
  }
  const features: GPUFeatureName[] = adapter.features.has('timestamp-query')
    ? ['timestamp-query']
    : [];
  const device = await adapter.requestDevice({ requiredFeatures: features });
  device.addEventListener('uncapturederror', (event) => {
    throw new Error(`uncaptured WebGPU error: ${(event as GPUUncapturedErrorEvent).error.message}`);
  });
  return device;
}

/** One device per process (per test worker). */
export function nodeDevice(): Promise<GPUDevice> {
  shared ??= createDevice();
  return shared;
}

/** Destroys the process's device, if one was made (SwiftShader's threads must stop before exit). */
export async function releaseNodeDevice(): Promise<void> {
  if (!shared) return;
  const device = await shared.catch(() => null);
  shared = null;
  device?.destroy();
  // Let Dawn finish the destruction before the process exits.
  await new Promise((resolve) => setTimeout(resolve, 10));
}
