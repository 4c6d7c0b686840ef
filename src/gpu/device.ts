// One GPU device per page, shared by every widget. Asks for timestamp queries
// when the adapter offers them. If WebGPU is missing or the device is lost,
// callers get the reason as text and fall back to the CPU reference.

export interface GpuContext {
  device: GPUDevice;
  adapterDescription: string;
  hasTimestamps: boolean;
}

export class GpuUnavailableError extends Error {
  constructor(reason: string) {
    super(reason);
    this.name = 'GpuUnavailableError';
  }
}

type LossListener = (reason: string) => void;

let shared: Promise<GpuContext> | null = null;
const lossListeners = new Set<LossListener>();
const errorListeners = new Set<(message: string) => void>();

async function createContext(): Promise<GpuContext> {
  if (typeof navigator === 'undefined' || !('gpu' in navigator) || !navigator.gpu) {
    throw new GpuUnavailableError('this browser has no WebGPU (navigator.gpu is missing)');
  }
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) throw new GpuUnavailableError('WebGPU found no suitable GPU adapter');
  const hasTimestamps = adapter.features.has('timestamp-query');
  const device = await adapter.requestDevice({
    requiredFeatures: hasTimestamps ? ['timestamp-query'] : [],
  });
  device.lost.then((info) => {
    shared = null;
    const reason = `the GPU device was lost (${info.reason}): ${info.message || 'no message'}`;
    for (const listener of lossListeners) listener(reason);
  });
  device.addEventListener('uncapturederror', (event) => {
    const message = (event as GPUUncapturedErrorEvent).error.message;
    for (const listener of errorListeners) listener(message);
  });
  const info = adapter.info;
  const adapterDescription =
    [info.vendor, info.architecture, info.description].filter(Boolean).join(' ') || 'WebGPU';
  return { device, adapterDescription, hasTimestamps };
}

/** The page's shared device; rejects with GpuUnavailableError when there is none. */
export function acquireGpu(): Promise<GpuContext> {
  if (!shared) {
    shared = createContext();
    shared.catch(() => {
      shared = null;
    });
  }
  return shared;
}

export function onDeviceLost(listener: LossListener): () => void {
  lossListeners.add(listener);
  return () => lossListeners.delete(listener);
}

export function onUncapturedError(listener: (message: string) => void): () => void {
  errorListeners.add(listener);
  return () => errorListeners.delete(listener);
}
