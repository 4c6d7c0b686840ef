// The CPU fallback's optimizer (the voxel grid's or the neural field's) behind a message interface, so that the same code
// runs in a Web Worker (cpuWorker.ts; DESIGN.md asks heavy fallbacks to leave the
// page's thread) or, where no worker can be started, in the page itself. Each
// request is answered with one response; times are the float64 computing time.
import {
  InverseOptimizerCpu,
  MAX_ITERATIONS,
  problemCameras,
  renderTargetsCpu,
  type Hyper,
  type Problem,
  type ViewAngle,
} from './model.ts';
import { NeuralOptimizerCpu } from './neuralModel.ts';

export type CpuRequest =
  | { type: 'setup'; id: number; problem: Problem }
  | { type: 'train'; id: number; count: number; hyper: Hyper }
  | { type: 'render'; id: number }
  | { type: 'novel'; id: number; view: ViewAngle };

export type CpuResponse =
  | { type: 'targets'; id: number; targets: Float64Array }
  | { type: 'trained'; id: number; losses: Float64Array; iteration: number; milliseconds: number }
  | { type: 'rendered'; id: number; image: Float64Array; milliseconds: number }
  | { type: 'error'; id: number; message: string };

/** One optimization's state on the CPU, and the requests that drive it. */
export class CpuTrainingSession {
  /** The grid's or the neural field's optimizer (the same interface). */
  private optimizer: InverseOptimizerCpu | NeuralOptimizerCpu | null = null;

  handle(request: CpuRequest): CpuResponse {
    try {
      return this.answer(request);
    } catch (error) {
      return {
        type: 'error',
        id: request.id,
        message: error instanceof Error ? error.message : String(error),
      };
    }
  }

  private answer(request: CpuRequest): CpuResponse {
    if (request.type === 'setup') {
      const targets = renderTargetsCpu(request.problem);
      this.optimizer =
        request.problem.model === 'neural'
          ? new NeuralOptimizerCpu(request.problem, targets)
          : new InverseOptimizerCpu(request.problem, targets);
      // A copy: the worker hands the response's buffer over to the page.
      return { type: 'targets', id: request.id, targets: targets.slice() };
    }
    const optimizer = this.optimizer;
    if (!optimizer) throw new Error('the CPU optimizer was not set up');
    if (request.type === 'train') {
      const start = performance.now();
      const count = Math.max(0, Math.min(request.count, MAX_ITERATIONS - optimizer.iteration));
      const losses = new Float64Array(count);
      for (let k = 0; k < count; k++) losses[k] = optimizer.step(request.hyper);
      return {
        type: 'trained',
        id: request.id,
        losses,
        iteration: optimizer.iteration,
        milliseconds: performance.now() - start,
      };
    }
    if (request.type === 'novel') {
      const problem = optimizer.problem;
      problem.views = [...problem.views.slice(0, problem.trainViews), request.view];
      optimizer.cameras.splice(0, optimizer.cameras.length, ...problemCameras(problem));
      const targets = renderTargetsCpu(problem, optimizer.cameras);
      optimizer.targets.set(targets);
      return { type: 'targets', id: request.id, targets };
    }
    const start = performance.now();
    const image = optimizer.render();
    return { type: 'rendered', id: request.id, image, milliseconds: performance.now() - start };
  }
}
