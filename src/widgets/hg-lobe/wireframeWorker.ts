// The page's side of wireframe.worker.ts: a canvas handed to a dedicated worker,
// which draws the CPU fallback's 3D wireframe on it (issue 23: off the page's
// thread, so a slider drag has no long task from it). One picture at a time: LobeView
// waits for each before asking for the next, so pictures never queue up.
import type { Orbit } from './lobe3d.ts';
import type { HgLobeInputs } from './model.ts';

export type WireframeRequest =
  | { kind: 'canvas'; canvas: OffscreenCanvas }
  | {
      kind: 'draw';
      id: number;
      /** The backing store's size (the page cannot resize a transferred canvas). */
      width: number;
      height: number;
      inputs: HgLobeInputs;
      logFloor: number;
      orbit: Orbit;
      /** Backing pixels per CSS pixel (line widths). */
      scale: number;
    };

export type WireframeAnswer = { id: number; ok: true } | { id: number; ok: false; error: string };

interface Pending {
  resolve: () => void;
  reject: (error: Error) => void;
}

export class WireframeWorker {
  private readonly pending = new Map<number, Pending>();
  private nextId = 1;
  private failure: Error | null = null;

  private constructor(private readonly worker: Worker) {
    worker.addEventListener('message', (event: MessageEvent<WireframeAnswer>) => {
      const answer = event.data;
      const waiting = this.pending.get(answer.id);
      this.pending.delete(answer.id);
      if (answer.ok) waiting?.resolve();
      else waiting?.reject(new Error(answer.error));
    });
    // A worker that cannot start (its module failed to load) fails every picture.
    worker.addEventListener('error', (event) => this.fail(new Error(event.message)));
  }

  /**
   * Hands `canvas` (which must have no context yet) to a new worker; null where this
   * browser has no OffscreenCanvas or module worker, and the canvas is then untouched.
   */
  static start(canvas: HTMLCanvasElement): WireframeWorker | null {
    if (typeof Worker === 'undefined' || typeof canvas.transferControlToOffscreen !== 'function')
      return null;
    let worker: Worker;
    try {
      worker = new Worker(new URL('./wireframe.worker.ts', import.meta.url), { type: 'module' });
    } catch {
      return null;
    }
    const offscreen = canvas.transferControlToOffscreen();
    const request: WireframeRequest = { kind: 'canvas', canvas: offscreen };
    worker.postMessage(request, [offscreen]);
    return new WireframeWorker(worker);
  }

  /** Draws one picture; resolves once it is on the canvas, rejects if the worker failed. */
  draw(
    size: { width: number; height: number },
    inputs: HgLobeInputs,
    logFloor: number,
    orbit: Orbit,
    scale: number,
  ): Promise<void> {
    if (this.failure) return Promise.reject(this.failure);
    const id = this.nextId++;
    const request: WireframeRequest = {
      kind: 'draw',
      id,
      width: size.width,
      height: size.height,
      inputs,
      logFloor,
      orbit,
      scale,
    };
    return new Promise<void>((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage(request);
    });
  }

  private fail(error: Error): void {
    this.failure = error;
    for (const waiting of this.pending.values()) waiting.reject(error);
    this.pending.clear();
  }

  destroy(): void {
    this.worker.terminate();
    this.fail(new Error('the wireframe worker was stopped'));
  }
}
