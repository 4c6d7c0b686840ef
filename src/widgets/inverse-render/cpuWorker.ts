// The Web Worker of the inverse-render CPU fallback: runs the float64 optimizer
// (cpuTraining.ts) off the page's thread and answers each request with a message.
import { CpuTrainingSession, type CpuRequest } from './cpuTraining.ts';

const session = new CpuTrainingSession();
const scope = globalThis as unknown as DedicatedWorkerGlobalScope;

scope.addEventListener('message', (event: MessageEvent<CpuRequest>) => {
  const response = session.handle(event.data);
  const transfer =
    response.type === 'targets'
      ? [response.targets.buffer]
      : response.type === 'trained'
        ? [response.losses.buffer]
        : response.type === 'rendered'
          ? [response.image.buffer]
          : [];
  scope.postMessage(response, transfer);
});
