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
  const hasTimestamps = adapter.features.has('timestamp-query') && trustsTimestamps(adapter);
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
  return { device, adapterDescription: describeAdapter(adapter), hasTimestamps };
}

/**
 * The adapter as the widgets name it in their cost line, "WebGPU (…)". Firefox leaves
 * vendor, architecture and description empty, and calls a CPU Vulkan driver such as
 * lavapipe a fallback adapter: the figures are right but slow there, so say so.
 */
export function describeAdapter(adapter: GPUAdapter): string {
  const { name, fallback } = adapterIdentity(adapter);
  if (fallback) return name ? `${name}, a software fallback adapter` : 'software fallback adapter';
  return name || 'adapter unnamed by the browser';
}

function adapterIdentity(adapter: GPUAdapter): { name: string; fallback: boolean } {
  const info = adapter.info;
  const name = [info.vendor, info.architecture, info.description].filter(Boolean).join(' ');
  // `isFallbackAdapter` moved from the adapter to its info; older browsers have the former.
  const legacy = (adapter as GPUAdapter & { isFallbackAdapter?: boolean }).isFallbackAdapter;
  const fallback = (info.isFallbackAdapter as boolean | undefined) ?? legacy ?? false;
  return { name, fallback };
}

/**
 * Whether the widgets time their passes with the adapter's timestamp queries. Not on
 * a fallback adapter that gives no name, which is Firefox (wgpu) on a CPU driver such
 * as lavapipe: there, once a page has run a few kernels, timestamp spans come back far
 * too short (the transfer function 0.053 ms against 436 ms by wall clock on the same
 * machine), and a widget that sizes its work by measured time runs away (the
 * delta-tracking calibration took 90 s instead of 7 s). A software adapter is the
 * CPU, so wall time is its true cost; the widgets then say "wall time".
 */
function trustsTimestamps(adapter: GPUAdapter): boolean {
  const { name, fallback } = adapterIdentity(adapter);
  return !(fallback && !name);
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
