// <sb-vre-ray>: one ray through an emitting, scattering medium in front of a
// background (chapter 4). Plots what reaches the eye from [0, s] term by term,
// draws the medium and the weighted source T(0,s)·(σa Le + σs L_in) on the GPU,
// and reports the marched radiance at the eye next to the exact integral form
// L = (1 − α)Le(1 − T) + αL_in(1 − T) + T·L_bg and the cost of the march.
import { acquireGpu, onDeviceLost, type GpuContext } from '../../gpu/device.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { LinePlot } from '../base/plot.ts';
import { timingLabel } from '../base/imageKernel.ts';
import { ReadoutList } from '../base/readoutList.ts';
import { gpuFailureReason } from '../base/backend.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import { VRE_RAY } from './schema.ts';
import { drawRayCpu, marchRayCpu } from './cpuBackend.ts';
import { VreRayGpu } from './gpuBackend.ts';
import {
  MARCH_STEPS,
  exactRadiance,
  inputsFrom,
  type VreRayInputs,
  type VreRayResult,
} from './model.ts';

type Backend =
  { kind: 'gpu'; gpu: GpuContext; renderer: VreRayGpu } | { kind: 'cpu'; reason: string };

const READOUT_ROWS = [
  ['tau', 'Optical thickness τ(0→d)'],
  ['transmittance', 'T(0→d)'],
  ['terms', 'Emission + in-scattering + background'],
  ['total', 'L at the eye, this backend'],
  ['reference', 'L at the eye, exact (float64)'],
  ['error', 'Relative difference'],
] as const;

export class VreRayElement extends WidgetElement {
  protected readonly entry = VRE_RAY;
  protected override presets: readonly Preset[] = [
    {
      label: 'absorbing only',
      values: { sigma: 1, albedo: 0, emission: 0.5, inscatter: 0, background: 1, length: 2 },
    },
    {
      label: 'scattering only',
      values: { sigma: 1, albedo: 1, emission: 0, inscatter: 0.3, background: 1, length: 2 },
    },
    {
      label: 'thick medium hides the background',
      values: { sigma: 3, albedo: 0.5, emission: 0.5, inscatter: 0.3, background: 1, length: 4 },
    },
    {
      label: 'vacuum',
      values: { sigma: 0, albedo: 0.5, emission: 0.5, inscatter: 0.3, background: 1, length: 2 },
    },
  ];

  private canvas: HTMLCanvasElement | null = null;
  private stage: HTMLElement | null = null;
  private plot: LinePlot | null = null;
  private readouts: ReadoutList | null = null;
  private backend: Promise<Backend> | null = null;

  protected buildStage(stage: HTMLElement): void {
    this.stage = stage;
    this.canvas = this.createCanvas();
    const legend = document.createElement('p');
    legend.className = 'sb-vre-legend';
    for (const text of [
      'eye, s = 0',
      'top: σt(s) · bottom: T(0,s)·(σa Le + σs L_in)',
      'L_bg / T·L_bg',
    ]) {
      const span = document.createElement('span');
      span.textContent = text;
      legend.appendChild(span);
    }
    stage.append(this.canvas, legend);
    const plotArea = document.createElement('div');
    plotArea.className = 'sb-plot';
    plotArea.setAttribute('role', 'img');
    plotArea.setAttribute(
      'aria-label',
      'Plot of the radiance reaching the eye from the segment [0, s], term by term, and T(0→s), against s',
    );
    stage.appendChild(plotArea);
    this.plot = new LinePlot(plotArea, {
      xLabel: 's (m)',
      yLabel: 'from [0, s]; T(0→s)',
      height: 280,
    });
  }

  private createCanvas(): HTMLCanvasElement {
    const canvas = document.createElement('canvas');
    canvas.className = 'sb-canvas';
    canvas.setAttribute('role', 'img');
    canvas.width = 960;
    canvas.height = 360;
    return canvas;
  }

  protected buildReadout(readout: HTMLElement): void {
    this.readouts = new ReadoutList(readout, READOUT_ROWS);
  }

  private chooseBackend(): Promise<Backend> {
    this.backend ??= (async (): Promise<Backend> => {
      if (new URLSearchParams(location.search).get('backend') === 'cpu') {
        return { kind: 'cpu', reason: 'the page was opened with ?backend=cpu' };
      }
      try {
        const gpu = await acquireGpu();
        if (!this.canvas) throw new Error('no canvas');
        onDeviceLost((reason) => this.fallBackToCpu(reason));
        return { kind: 'gpu', gpu, renderer: new VreRayGpu(gpu, this.canvas) };
      } catch (error) {
        return { kind: 'cpu', reason: error instanceof Error ? error.message : String(error) };
      }
    })();
    return this.backend;
  }

  /** After a device loss: a fresh canvas (a WebGPU canvas cannot become 2D) and the CPU path. */
  private fallBackToCpu(reason: string): void {
    if (this.canvas && this.stage) {
      const fresh = this.createCanvas();
      this.canvas.replaceWith(fresh);
      this.canvas = fresh;
    }
    this.backend = Promise.resolve({ kind: 'cpu', reason });
    this.scheduleRender();
  }

  protected async render(): Promise<void> {
    const inputs = inputsFrom(this.values);
    const backend = await this.chooseBackend();
    const twin = marchRayCpu(inputs);
    let result: VreRayResult;
    if (backend.kind === 'gpu') {
      try {
        result = await backend.renderer.march(inputs);
        await backend.renderer.draw(inputs);
      } catch (error) {
        this.fallBackToCpu(gpuFailureReason(error));
        return;
      }
      this.clearNotice('backend');
    } else {
      if (this.canvas) drawRayCpu(this.canvas, inputs);
      result = twin;
      this.showCpuFallbackNotice(
        backend.reason,
        `Showing the float64 CPU march, drawn at half resolution.`,
      );
    }
    this.showResult(inputs, result, twin, backend);
  }

  private showResult(
    inputs: VreRayInputs,
    result: VreRayResult,
    twin: VreRayResult,
    backend: Backend,
  ): void {
    const set = (key: string, text: string): void => this.readouts?.set(key, text);
    const exact = exactRadiance(inputs);
    const n = MARCH_STEPS;
    const T = result.transmittance[n] ?? NaN;
    const emitted = result.emitted[n] ?? NaN;
    const inscattered = result.inscattered[n] ?? NaN;
    set('tau', formatNumber(exact.opticalDepth));
    set('transmittance', `${formatNumber(T)} (exact ${formatNumber(exact.transmittance)})`);
    set(
      'terms',
      `${formatNumber(emitted, 4)} + ${formatNumber(inscattered, 4)} + ${formatNumber(T * inputs.background, 4)}`,
    );
    set(
      'total',
      `${formatNumber(result.total)}${backend.kind === 'gpu' ? ' (GPU, f32)' : ' (CPU, f64)'}`,
    );
    set('reference', `${formatNumber(exact.total)} = J(1−T) + T·L_bg`);
    const difference = Math.abs(result.total - exact.total);
    set(
      'error',
      exact.total > 0
        ? formatNumber(difference / exact.total, 2)
        : `${formatNumber(difference, 2)} (absolute)`,
    );

    const how = timingLabel(result.timing);
    this.recordFrameCost(result.milliseconds, how);
    const where =
      backend.kind === 'gpu' ? `WebGPU (${backend.gpu.adapterDescription})` : 'CPU fallback';
    if (this.readouts) {
      this.readouts.cost.textContent =
        `${where}: ${n} midpoint steps in ${formatMilliseconds(result.milliseconds)} (${how}); ` +
        `float64 march on the CPU in ${formatMilliseconds(twin.milliseconds)}.`;
    }
    if (this.canvas) {
      this.canvas.setAttribute(
        'aria-label',
        `A ray ${formatNumber(inputs.length, 3)} m long from the eye on the left to a background of radiance ` +
          `${formatNumber(inputs.background, 3)} on the right; ${formatNumber(100 * T, 3)}% of the background reaches the eye.`,
      );
    }
    const background = result.depths.map(() => T * inputs.background);
    this.plot?.update(result.depths, [
      { label: 'emission ∫T σa Le', color: '#d9822b', values: result.emitted },
      { label: 'in-scattering ∫T σs L_in', color: '#5b8def', values: result.inscattered },
      { label: 'background T(0→d)·L_bg', color: '#8a8f98', dash: [6, 4], values: background },
      { label: 'T(0→s)', color: '#3aa17e', dash: [2, 3], values: result.transmittance },
    ]);
  }
}

export function defineVreRay(): void {
  if (!customElements.get('sb-vre-ray')) customElements.define('sb-vre-ray', VreRayElement);
}
