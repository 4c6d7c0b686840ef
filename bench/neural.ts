// Benchmark of <sb-inverse-render>'s two models (chapter 8): the voxel grid
// (kernels/inverse-render.wesl) and the neural field, Instant-NGP's hash encoding and
// tiny MLP (kernels/neural-field.wesl), each trained through Dawn for the same wall
// time from the empty box on the same problem (views, rays per iteration, samples,
// η). Printed side by side: the batch loss and the held-out view's PSNR against
// training time, then where each model's time goes (set-up, one iteration's
// lossGradient alone, a whole iteration, the render of every view that measures the
// held-out error) and its memory (parameters, and the GPU buffers of the fit).
//
// Only the iterations count towards the training time: the held-out renders between
// checkpoints are measured and reported separately, so the curve is the model's, not
// the benchmark's. The widget pays those renders too (view.ts's redraws).
import { linkLibraryKernel } from '../src/gpu/link.ts';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import { neuralParameterCount } from '../src/reference/neural.ts';
import { InverseTrainerGpu, KERNEL } from '../src/widgets/inverse-render/gpuBackend.ts';
import {
  MAX_ITERATIONS,
  effectiveBatch,
  problemFrom,
  viewError,
  type Hyper,
  type ModelKind,
  type Problem,
} from '../src/widgets/inverse-render/model.ts';
import { NEURAL_KERNEL, NeuralTrainerGpu } from '../src/widgets/inverse-render/neuralGpuBackend.ts';
import type { BenchTable } from './table.ts';
import { median } from './table.ts';

export interface NeuralBenchOptions {
  /** Training wall time per model (s). */
  seconds: number;
  /** Training times (s) at which the held-out view is rendered and the row printed. */
  checkpoints: readonly number[];
  views: number;
  batch: number;
  steps: number;
  learningRate: number;
  /** log₂ of the neural field's entries per level. */
  tableLog2: number;
  /** Voxels per axis of the grid. */
  resolution: number;
  /** Repeats of the cost measurements (medians). */
  repeats: number;
}

interface Curve {
  model: ModelKind;
  parameters: number;
  /** GPU bytes of the fit: parameters, Adam's two moments, the gradient. */
  fitBytes: number;
  setupMs: number;
  /** Per checkpoint: training time (s), iterations, mean batch loss of the last 10, held-out PSNR (dB). */
  points: { seconds: number; iterations: number; loss: number; psnr: number }[];
  initialPsnr: number;
  renderMs: number[];
  iterationMs: number[];
  gpuIterationMs: number[];
  lossGradientMs: number[];
}

function psnr(mse: number): number {
  return 10 * Math.log10(1 / mse);
}

/** The widget's problem for these settings (problemFrom on the GPU, as the page builds it). */
function benchProblem(model: ModelKind, options: NeuralBenchOptions): Problem {
  return problemFrom(
    {
      model,
      views: options.views,
      steps: options.steps,
      table: options.tableLog2,
      grid: String(options.resolution),
      novel: 60,
      seed: 0,
    },
    'gpu',
  );
}

async function trainCurve(
  device: GPUDevice,
  codes: { grid: string; neural: string },
  model: ModelKind,
  options: NeuralBenchOptions,
): Promise<Curve> {
  const problem = benchProblem(model, options);
  const hyper: Hyper = {
    learningRate: options.learningRate,
    regularizer: 0,
    regularizerWeight: 0,
    batch: options.batch,
  };
  const setupStart = performance.now();
  const trainer =
    model === 'neural'
      ? await NeuralTrainerGpu.create(device, codes.neural, codes.grid, problem)
      : await InverseTrainerGpu.create(device, codes.grid, problem);
  const targets = await trainer.readTargets();
  const pixels = problem.size * problem.size;
  const renderMs: number[] = [];
  const heldOut = async (): Promise<number> => {
    const start = performance.now();
    const { image } = await trainer.render();
    renderMs.push(performance.now() - start);
    return psnr(viewError(image, targets, problem.trainViews, pixels));
  };
  const initialPsnr = await heldOut();
  const setupMs = performance.now() - setupStart;
  const parameters =
    model === 'neural' ? neuralParameterCount(problem.tableSize) : 4 * problem.resolution ** 3;
  const curve: Curve = {
    model,
    parameters,
    fitBytes: 16 * parameters,
    setupMs,
    points: [],
    initialPsnr,
    renderMs,
    iterationMs: [],
    gpuIterationMs: [],
    lossGradientMs: [],
  };
  // The gradient pass alone, before training (it changes nothing): what one
  // iteration's lossGradient dispatch costs without Adam and the read-back of losses.
  for (let r = 0; r < options.repeats; r++) {
    const start = performance.now();
    await trainer.lossAndGradient(hyper);
    curve.lossGradientMs.push(performance.now() - start);
  }
  const losses: number[] = [];
  let trained = 0;
  let perIteration = 0;
  for (const checkpoint of options.checkpoints.filter((c) => c <= options.seconds)) {
    while (trained < 1000 * checkpoint && trainer.iteration < MAX_ITERATIONS) {
      // Chunks of iterations sized to end near the checkpoint (at most 32, as the widget).
      const left = 1000 * checkpoint - trained;
      const count =
        perIteration > 0 ? Math.min(32, Math.max(1, Math.round(left / perIteration))) : 1;
      const start = performance.now();
      const report = await trainer.train(count, hyper);
      const wall = performance.now() - start;
      trained += wall;
      const done = report.losses.length;
      if (done === 0) break;
      perIteration = wall / done;
      curve.iterationMs.push(perIteration);
      if (report.gpuMs !== null) curve.gpuIterationMs.push(report.gpuMs / done);
      losses.push(...Array.from(report.losses));
    }
    const recent = losses.slice(-10);
    curve.points.push({
      seconds: trained / 1000,
      iterations: trainer.iteration,
      loss: recent.reduce((a, b) => a + b, 0) / Math.max(recent.length, 1),
      psnr: await heldOut(),
    });
  }
  trainer.destroy();
  return curve;
}

export async function benchNeural(
  device: GPUDevice,
  options: NeuralBenchOptions,
): Promise<BenchTable[]> {
  const library = loadShaderLibrary(new URL('../shaders', import.meta.url).pathname);
  const codes = {
    grid: await linkLibraryKernel(library, KERNEL),
    neural: await linkLibraryKernel(library, NEURAL_KERNEL),
  };
  const grid = await trainCurve(device, codes, 'grid', options);
  const neural = await trainCurve(device, codes, 'neural', options);
  const problem = benchProblem('neural', options);
  const batch = effectiveBatch(
    { learningRate: 0, regularizer: 0, regularizerWeight: 0, batch: options.batch },
    problem.trainViews * problem.size * problem.size,
  );
  const setting = `${options.views} training views of ${problem.size}×${problem.size} pixels, B = ${batch} rays × ${options.steps} samples per iteration, η = ${options.learningRate}, Adam; grid ${options.resolution}³, neural field T = 2^${options.tableLog2}`;
  const curves: BenchTable = {
    title: 'Inverse rendering: voxel grid and neural field against training time (Dawn)',
    notes: [
      setting,
      'Both start from the empty box; time is the iterations’ wall time only (the held-out renders at the checkpoints are excluded and listed below).',
      `Held-out view at the start: grid ${grid.initialPsnr.toFixed(2)} dB, neural field ${neural.initialPsnr.toFixed(2)} dB. Loss: mean batch MSE of the last 10 iterations.`,
    ],
    rows: grid.points.map((g, k) => {
      const n = neural.points[k];
      return {
        'checkpoint (s)': options.checkpoints[k] ?? null,
        'grid: s': g.seconds,
        'grid: iterations': g.iterations,
        'grid: loss': g.loss,
        'grid: held-out PSNR (dB)': g.psnr,
        'neural: s': n?.seconds ?? null,
        'neural: iterations': n?.iterations ?? null,
        'neural: loss': n?.loss ?? null,
        'neural: held-out PSNR (dB)': n?.psnr ?? null,
      };
    }),
  };
  const costs: BenchTable = {
    title: 'Inverse rendering: where each model’s time goes, and its memory (Dawn)',
    notes: [
      setting,
      'Medians. lossGradient alone: one dispatch and the read-back of the gradient (lossAndGradient), no Adam. Iteration: train() chunks, wall time per iteration, and GPU time from timestamp queries where the adapter has them. Render: every view, the held-out error from it.',
    ],
    rows: [grid, neural].map((c) => ({
      model: c.model === 'neural' ? 'neural field' : 'voxel grid',
      parameters: c.parameters,
      'parameters (KiB)': (4 * c.parameters) / 1024,
      'fit on the GPU (KiB)': c.fitBytes / 1024,
      'set-up (ms)': c.setupMs,
      'lossGradient alone (ms)': median(c.lossGradientMs),
      'iteration, wall (ms)': median(c.iterationMs),
      'iteration, GPU (ms)': c.gpuIterationMs.length ? median(c.gpuIterationMs) : null,
      'render of every view (ms)': median(c.renderMs),
    })),
  };
  return [curves, costs];
}
