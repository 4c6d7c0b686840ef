// GPU failures are surfaced, never swallowed: a validation error in a dispatch
// becomes an exception with the driver's message, and device loss is reported to
// whoever listens (the widgets then fall back to the CPU reference).

export class GpuValidationError extends Error {
  constructor(what: string, message: string) {
    super(`${what}: ${message}`);
    this.name = 'GpuValidationError';
  }
}

/** Runs `body` inside validation and out-of-memory error scopes and throws the first error. */
export async function withErrorScopes<T>(
  device: GPUDevice,
  what: string,
  body: () => T,
): Promise<T> {
  device.pushErrorScope('out-of-memory');
  device.pushErrorScope('validation');
  let result: T | undefined;
  let thrown: unknown = null;
  try {
    result = body();
  } catch (error) {
    thrown = error;
  }
  // Pop both scopes whatever happened, so that the device's scope stack stays balanced.
  const validation = await device.popErrorScope();
  const memory = await device.popErrorScope();
  const error = validation ?? memory;
  if (error) throw new GpuValidationError(what, error.message);
  if (thrown !== null) throw thrown;
  return result as T;
}
