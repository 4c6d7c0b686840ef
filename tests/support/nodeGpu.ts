// A WebGPU device in Node through Dawn, one per test worker. The device helper
// lives in src/gpu/nodeDevice.ts so that the command line shares it; it keeps the
// Dawn instance alive for the life of the worker, because a Dawn instance that is
// garbage-collected while a device is in use crashes the process.
export { nodeDevice, releaseNodeDevice } from '../../src/gpu/nodeDevice.ts';
