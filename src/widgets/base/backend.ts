// Which backend a widget draws with: the shared WebGPU device when the page has
// one, otherwise (no WebGPU, `?backend=cpu`, or after a device loss) the float64
// CPU path, with the reason kept for the widget's notice.
import { acquireGpu, onDeviceLost, type GpuContext } from '../../gpu/device.ts';

export type Backend<Renderer> =
  { kind: 'gpu'; gpu: GpuContext; renderer: Renderer } | { kind: 'cpu'; reason: string };

export class BackendChooser<Renderer> {
  private current: Promise<Backend<Renderer>> | null = null;
  private stopListening: (() => void) | null = null;

  /**
   * @param makeRenderer builds the widget's GPU renderer once the device exists.
   * @param onLost called when the device is lost; the chooser has already switched to the CPU.
   */
  constructor(
    private readonly makeRenderer: (gpu: GpuContext) => Renderer,
    private readonly onLost: (reason: string) => void,
  ) {}

  choose(): Promise<Backend<Renderer>> {
    this.current ??= (async (): Promise<Backend<Renderer>> => {
      if (new URLSearchParams(location.search).get('backend') === 'cpu') {
        return { kind: 'cpu', reason: 'the page was opened with ?backend=cpu' };
      }
      try {
        const gpu = await acquireGpu();
        const renderer = this.makeRenderer(gpu);
        this.stopListening = onDeviceLost((reason) => {
          this.useCpu(reason);
          this.onLost(reason);
        });
        return { kind: 'gpu', gpu, renderer };
      } catch (error) {
        return { kind: 'cpu', reason: error instanceof Error ? error.message : String(error) };
      }
    })();
    return this.current;
  }

  /** Switches to the CPU path for good (device lost, or the GPU path failed). */
  useCpu(reason: string): void {
    this.current = Promise.resolve({ kind: 'cpu', reason });
    this.unsubscribe();
  }

  /** Stops listening for device loss (the widget was destroyed, or is on the CPU for good). */
  unsubscribe(): void {
    this.stopListening?.();
    this.stopListening = null;
  }

  /** Forgets the choice (and the loss subscription): the next choose() starts over. */
  reset(): void {
    this.unsubscribe();
    this.current = null;
  }
}

/** The reason a widget gives when its GPU path threw and it switches to the CPU twin. */
export function gpuFailureReason(error: unknown): string {
  return `the GPU path failed: ${error instanceof Error ? error.message : String(error)}`;
}
