// The compute worker: runs widgets' jobs (jobs.ts) one at a time, off the main thread,
// and answers each request with its result (typed arrays moved, not copied) or its
// error message. Started once per page by compute.ts.
import { runJob, transferables } from './jobs.ts';
import type { JobRequest, JobResponse } from './protocol.ts';

const scope = self as unknown as {
  onmessage: ((event: MessageEvent<JobRequest>) => void) | null;
  postMessage(message: JobResponse, transfer: Transferable[]): void;
};

scope.onmessage = (event) => {
  const { id, widget, name, args } = event.data;
  void (async () => {
    try {
      const result = await runJob(widget, name, args);
      scope.postMessage({ id, ok: true, result }, transferables(result));
    } catch (error) {
      scope.postMessage(
        { id, ok: false, error: error instanceof Error ? error.message : String(error) },
        [],
      );
    }
  })();
};
