// The CPU fallback's render passes of <sb-single-scatter>, run in the compute worker
// (src/workers/compute.ts) through WorkerSceneRenderer (src/scene/workerRenderer.ts)
// instead of on the page's thread.
import { scenePassJobs } from '../../scene/passJob.ts';

export const jobs = scenePassJobs;
