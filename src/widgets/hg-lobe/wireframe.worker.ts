// The CPU fallback's 3D wireframe of <sb-hg-lobe>, drawn off the page's thread
// (issue 23): LobeView hands its canvas over (transferControlToOffscreen) and asks
// for a picture per lobe or view; this worker draws it with lobe3dCpu.ts on the
// OffscreenCanvas, which rasterises it here too (willReadFrequently), and answers
// once drawn. In the page, drawing and rasterising the few thousand segments took
// 20–120 ms a picture on a loaded two-core machine: the longest tasks of a slider
// drag (bench/dragProfile.ts: the figure's Paint and drawLobeWireframe).
import { drawLobeWireframe } from './lobe3dCpu.ts';
import type { WireframeAnswer, WireframeRequest } from './wireframeWorker.ts';

const scope = self as unknown as {
  onmessage: ((event: MessageEvent<WireframeRequest>) => void) | null;
  postMessage(message: WireframeAnswer): void;
};

let canvas: OffscreenCanvas | null = null;

scope.onmessage = (event) => {
  const request = event.data;
  if (request.kind === 'canvas') {
    canvas = request.canvas;
    return;
  }
  try {
    if (!canvas) throw new Error('no canvas handed to the wireframe worker');
    if (canvas.width !== request.width) canvas.width = request.width;
    if (canvas.height !== request.height) canvas.height = request.height;
    drawLobeWireframe(canvas, request.inputs, request.logFloor, request.orbit, request.scale);
    scope.postMessage({ id: request.id, ok: true });
  } catch (error) {
    scope.postMessage({
      id: request.id,
      ok: false,
      error: error instanceof Error ? error.message : String(error),
    });
  }
};
