// Messages between the page (compute.ts) and the compute worker (compute.worker.ts).

export interface JobRequest {
  id: number;
  widget: string;
  name: string;
  args: readonly unknown[];
}

export type JobResponse =
  { id: number; ok: true; result: unknown } | { id: number; ok: false; error: string };
