// Drawing of <sb-inverse-render> and its CPU backend. Without WebGPU, the float64
// optimizer of model.ts runs at a smaller size (16³ voxels, 20×20 images) in a Web
// Worker (cpuWorker.ts), so the page never waits for it; where no worker can be
// started it runs in the page, one batch per animation frame. The painting helpers
// turn either backend's images into 2D-canvas pixels.
import { interpolate, type Rgb } from '../base/imagePanel.ts';
import { CpuTrainingSession, type CpuRequest, type CpuResponse } from './cpuTraining.ts';
import type { Hyper, Problem, TrainReport, Trainer, ViewAngle } from './model.ts';
import { context2d } from '../base/canvas2d.ts';

type Pending = (response: CpuResponse) => void;

export class CpuTrainer implements Trainer {
  private worker: Worker | null = null;
  private local: CpuTrainingSession | null = null;
  private readonly pending = new Map<number, Pending>();
  private nextId = 1;
  private targets: Float64Array = new Float64Array(0);
  /** Whether the optimizer runs in a Web Worker (else in the page). */
  inWorker = false;

  private constructor(public problem: Problem) {
    try {
      this.worker = new Worker(new URL('./cpuWorker.ts', import.meta.url), { type: 'module' });
      this.worker.addEventListener('message', (event: MessageEvent<CpuResponse>) => {
        const resolve = this.pending.get(event.data.id);
        this.pending.delete(event.data.id);
        resolve?.(event.data);
      });
      this.worker.addEventListener('error', (event) => {
        const failure: CpuResponse = { type: 'error', id: 0, message: event.message };
        for (const resolve of this.pending.values()) resolve(failure);
        this.pending.clear();
      });
      this.inWorker = true;
    } catch {
      this.worker = null;
      this.local = new CpuTrainingSession();
    }
  }

  static async create(problem: Problem): Promise<CpuTrainer> {
    const trainer = new CpuTrainer(problem);
    const response = await trainer.request({ type: 'setup', id: 0, problem });
    if (response.type !== 'targets') throw new Error('the CPU optimizer did not start');
    trainer.targets = response.targets;
    return trainer;
  }

  private request(request: CpuRequest): Promise<CpuResponse> {
    const id = this.nextId++;
    const message = { ...request, id };
    if (!this.worker) {
      // In the page: answer after the current task, so that painting and input keep going.
      return new Promise((resolve) =>
        setTimeout(() => resolve(this.local!.handle(message)), 0),
      ).then((response) => this.check(response as CpuResponse));
    }
    const worker = this.worker;
    return new Promise<CpuResponse>((resolve) => {
      this.pending.set(id, resolve);
      worker.postMessage(message);
    }).then((response) => this.check(response));
  }

  private check(response: CpuResponse): CpuResponse {
    if (response.type === 'error') throw new Error(`CPU optimizer: ${response.message}`);
    return response;
  }

  readTargets(): Promise<Float64Array> {
    return Promise.resolve(this.targets);
  }

  async train(count: number, hyper: Hyper): Promise<TrainReport> {
    const response = await this.request({ type: 'train', id: 0, count, hyper });
    if (response.type !== 'trained') throw new Error('unexpected answer from the CPU optimizer');
    return {
      losses: response.losses,
      iteration: response.iteration,
      dropped: 0,
      gpuMs: null,
      wallMs: response.milliseconds,
    };
  }

  async render(): Promise<{ image: Float64Array; gpuMs: null }> {
    const response = await this.request({ type: 'render', id: 0 });
    if (response.type !== 'rendered') throw new Error('unexpected answer from the CPU optimizer');
    return { image: response.image, gpuMs: null };
  }

  async setNovelView(view: ViewAngle): Promise<void> {
    this.problem = {
      ...this.problem,
      views: [...this.problem.views.slice(0, this.problem.trainViews), view],
    };
    const response = await this.request({ type: 'novel', id: 0, view });
    if (response.type === 'targets') this.targets = response.targets;
  }

  destroy(): void {
    this.worker?.terminate();
    this.worker = null;
    for (const resolve of this.pending.values())
      resolve({ type: 'error', id: 0, message: 'stopped' });
    this.pending.clear();
  }
}

/** A display value in [0, 1] (the book's radiances are display-referred) as a byte. */
function toByte(value: number): number {
  return Math.round(255 * Math.min(Math.max(value, 0), 1));
}

/**
 * Paints view `view` of an image array (3 numbers per pixel, size × size per view)
 * into a canvas of that size.
 */
export function paintView(
  canvas: HTMLCanvasElement,
  image: ArrayLike<number>,
  view: number,
  size: number,
): void {
  if (canvas.width !== size || canvas.height !== size) {
    canvas.width = size;
    canvas.height = size;
  }
  const context = context2d(canvas);
  if (!context) throw new Error('this browser cannot draw on a 2D canvas');
  const pixels = context.createImageData(size, size);
  const offset = 3 * view * size * size;
  for (let i = 0; i < size * size; i++) {
    for (let c = 0; c < 3; c++) pixels.data[4 * i + c] = toByte(image[offset + 3 * i + c] ?? 0);
    pixels.data[4 * i + 3] = 255;
  }
  context.putImageData(pixels, 0, 0);
}

/** Colour scale of the error image: black, violet, orange, pale yellow (perceptually ordered). */
const ERROR_STOPS: readonly Rgb[] = [
  [0, 0, 4],
  [81, 18, 124],
  [183, 55, 121],
  [252, 137, 97],
  [252, 253, 191],
];

export function errorColour(x: number): Rgb {
  return interpolate(ERROR_STOPS, x);
}

/** Paints the per-pixel error |C − C*| (mean over channels) of one view on the scale [0, top]. */
export function paintError(
  canvas: HTMLCanvasElement,
  image: ArrayLike<number>,
  target: ArrayLike<number>,
  view: number,
  size: number,
  top: number,
): void {
  if (canvas.width !== size || canvas.height !== size) {
    canvas.width = size;
    canvas.height = size;
  }
  const context = context2d(canvas);
  if (!context) throw new Error('this browser cannot draw on a 2D canvas');
  const pixels = context.createImageData(size, size);
  const offset = 3 * view * size * size;
  for (let i = 0; i < size * size; i++) {
    let error = 0;
    for (let c = 0; c < 3; c++)
      error += Math.abs((image[offset + 3 * i + c] ?? 0) - (target[offset + 3 * i + c] ?? 0));
    const [r, g, b] = errorColour(Math.sqrt(error / 3 / top));
    pixels.data[4 * i] = Math.round(r);
    pixels.data[4 * i + 1] = Math.round(g);
    pixels.data[4 * i + 2] = Math.round(b);
    pixels.data[4 * i + 3] = 255;
  }
  context.putImageData(pixels, 0, 0);
}
