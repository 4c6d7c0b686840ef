// The two ways <sb-transfer-function> renders rows of its image, behind one
// interface (FrameRenderer): the GPU kernel (gpuBackend.ts, bands read back into
// the full image) and, without WebGPU, the float64 twin in model.ts at
// CPU_SIZE² pixels. Also the painting of images into 2D canvases.
import { TimeSlicer } from '../base/refinement.ts';
import { timingLabel, type GpuTiming } from '../base/timing.ts';
import type { Rgb } from '../base/imagePanel.ts';
import type { VolumeRendererGpu } from './gpuBackend.ts';
import {
  CPU_SIZE,
  emptyImage,
  IMAGE_SIZE,
  renderRowsCpu,
  type FrameInputs,
  type VolumeImage,
} from './model.ts';

export interface RowsCost {
  milliseconds: number;
  /** How the time was measured, for the readout (timingLabel of `timing`). */
  how: string;
  timing: GpuTiming | 'cpu';
}

export interface FrameRenderer {
  readonly kind: 'gpu' | 'cpu';
  /** Image size (pixels per side). */
  readonly size: number;
  /** A blank image of `size`² pixels (default: this renderer's full size) and its precision. */
  blank(size?: number): VolumeImage;
  /** Renders rows [rowStart, rowEnd) into `image` and adds their statistics. */
  renderInto(
    image: VolumeImage,
    inputs: FrameInputs,
    stepVoxels: number,
    threshold: number,
    rowStart: number,
    rowEnd: number,
  ): Promise<RowsCost>;
}

/** The float64 twin on the CPU at CPU_SIZE² pixels (or a preview's fewer), timed by the wall clock. */
export class CpuRenderer implements FrameRenderer {
  readonly kind = 'cpu';
  readonly size = CPU_SIZE;

  blank(size = this.size): VolumeImage {
    return emptyImage(size, new Float64Array(3 * size * size));
  }

  /**
   * Row by row, yielding to the page whenever a slice is used up (TimeSlicer), so that no
   * task is much longer than SLICE_MS; the time is the work's, not the pauses'.
   */
  async renderInto(
    image: VolumeImage,
    inputs: FrameInputs,
    stepVoxels: number,
    threshold: number,
    rowStart: number,
    rowEnd: number,
  ): Promise<RowsCost> {
    const slicer = new TimeSlicer();
    let milliseconds = 0;
    for (let row = rowStart; row < Math.min(rowEnd, image.size); row++) {
      const start = performance.now();
      renderRowsCpu(image, inputs, stepVoxels, threshold, row, row + 1);
      milliseconds += performance.now() - start;
      await slicer.pause();
    }
    return { milliseconds, how: timingLabel('cpu'), timing: 'cpu' };
  }
}

/** The GPU kernel at IMAGE_SIZE² pixels (or a preview's fewer); each call is one dispatch, timed on the GPU. */
export class GpuRenderer implements FrameRenderer {
  readonly kind = 'gpu';
  readonly size = IMAGE_SIZE;

  constructor(private readonly gpu: VolumeRendererGpu) {}

  blank(size = this.size): VolumeImage {
    return emptyImage(size, new Float32Array(3 * size * size));
  }

  async renderInto(
    image: VolumeImage,
    inputs: FrameInputs,
    stepVoxels: number,
    threshold: number,
    rowStart: number,
    rowEnd: number,
  ): Promise<RowsCost> {
    const { size } = image;
    const band = await this.gpu.renderRows({
      inputs,
      size,
      stepVoxels,
      threshold,
      rowStart,
      rowEnd,
    });
    const pixels = size * size;
    const bandPixels = band.rows * size;
    const offset = rowStart * size;
    for (let c = 0; c < 3; c++)
      image.rgb.set(band.rgb.subarray(c * bandPixels, (c + 1) * bandPixels), c * pixels + offset);
    image.stepsPerPixel.set(band.stepsPerPixel, offset);
    image.plannedPerPixel.set(band.plannedPerPixel, offset);
    image.steps += band.steps;
    image.plannedSteps += band.plannedSteps;
    image.terminatedRays += band.terminatedRays;
    image.cappedRays += band.cappedRays;
    return { milliseconds: band.milliseconds, how: timingLabel(band.timing), timing: band.timing };
  }
}

/** One whole frame on a renderer at `size`² pixels (default: its full size): the image and its cost. */
export async function renderFrame(
  renderer: FrameRenderer,
  inputs: FrameInputs,
  stepVoxels: number,
  threshold: number,
  size = renderer.size,
): Promise<{ image: VolumeImage } & RowsCost> {
  const image = renderer.blank(size);
  const cost = await renderer.renderInto(image, inputs, stepVoxels, threshold, 0, size);
  return { image, ...cost };
}

/** Paints size × size colours into a canvas, scaled to the canvas's size (nearest neighbour). */
export function paintImage(
  canvas: HTMLCanvasElement,
  size: number,
  colourAt: (index: number) => Rgb,
): void {
  const context = canvas.getContext('2d');
  if (!context) throw new Error('this browser cannot draw on a 2D canvas');
  const image = context.createImageData(size, size);
  for (let index = 0; index < size * size; index++) {
    const rgb = colourAt(index);
    for (let c = 0; c < 3; c++) image.data[4 * index + c] = Math.round(rgb[c]!);
    image.data[4 * index + 3] = 255;
  }
  if (size === canvas.width && size === canvas.height) {
    context.putImageData(image, 0, 0);
    return;
  }
  const small = new OffscreenCanvas(size, size);
  small.getContext('2d')?.putImageData(image, 0, 0);
  context.imageSmoothingEnabled = false;
  context.drawImage(small, 0, 0, canvas.width, canvas.height);
}
