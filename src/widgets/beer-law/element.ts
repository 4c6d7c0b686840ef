// <sb-beer-law>: a collimated beam crossing a slab (chapter 2). Plots T(s),
// draws the attenuated beam on the GPU, reports T at the exit next to its float64
// reference and the cost of computing it, and checks the multiplicative property
// T(0→d) = T(0→s₀)·T(s₀→d) at the split point.
import {
  BackendChooser,
  type Backend as ChosenBackend,
  gpuFailureReason,
} from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { LinePlot } from '../base/plot.ts';
import { timingLabel } from '../base/imageKernel.ts';
import { ReadoutList } from '../base/readoutList.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import { BEER_LAW } from './schema.ts';
import { computeCurveCpu, drawBeamCpu } from './cpuBackend.ts';
import { BeerLawGpu } from './gpuBackend.ts';
import { inputsFrom, type BeerLawInputs, type BeerLawResult } from './model.ts';

type Backend = ChosenBackend<BeerLawGpu>;

const READOUT_ROWS = [
  ['tau', 'Optical thickness τ(0→d)'],
  ['exit', 'T(0→d), this backend'],
  ['reference', 'T(0→d), float64 reference'],
  ['error', 'Relative difference'],
  ['split', 'T(0→s₀) · T(s₀→d)'],
  ['split-check', 'Multiplicative property'],
  ['mfp', 'Mean free path 1/σ̄t'],
] as const;

export class BeerLawElement extends WidgetElement {
  protected readonly entry = BEER_LAW;
  protected override presets: readonly Preset[] = [
    {
      label: 'thin fog',
      values: { 'sigma-a': 0.02, 'sigma-s': 0.3, thickness: 3, profile: 'homogeneous', split: 1 },
    },
    {
      label: 'smoke',
      values: { 'sigma-a': 1.2, 'sigma-s': 0.8, thickness: 2, profile: 'homogeneous', split: 1 },
    },
    {
      label: 'layered',
      values: { 'sigma-a': 0.2, 'sigma-s': 0.6, thickness: 6, profile: 'layered', split: 2.5 },
    },
    {
      label: 'τ = 100',
      values: { 'sigma-a': 5, 'sigma-s': 5, thickness: 10, profile: 'smooth', split: 5 },
    },
  ];

  private canvas: HTMLCanvasElement | null = null;
  private stage: HTMLElement | null = null;
  private plot: LinePlot | null = null;
  private readouts: ReadoutList | null = null;
  private readonly backends = new BackendChooser<BeerLawGpu>(
    (gpu) => {
      if (!this.canvas) throw new Error('no canvas');
      return new BeerLawGpu(gpu, this.canvas);
    },
    (reason) => this.fallBackToCpu(reason),
  );

  protected buildStage(stage: HTMLElement): void {
    this.stage = stage;
    this.canvas = this.createCanvas();
    stage.appendChild(this.canvas);
    const plotArea = document.createElement('div');
    plotArea.className = 'sb-plot';
    plotArea.setAttribute('role', 'img');
    plotArea.setAttribute('aria-label', 'Plot of transmittance T(s) against depth s');
    stage.appendChild(plotArea);
    this.plot = new LinePlot(plotArea, {
      xLabel: 'depth s (m)',
      yLabel: 'T(0→s)',
      yRange: [0, 1],
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

  /** After a device loss: a fresh canvas (a WebGPU canvas cannot become 2D) and the CPU path. */
  private fallBackToCpu(reason: string): void {
    if (this.canvas && this.stage) {
      const fresh = this.createCanvas();
      this.canvas.replaceWith(fresh);
      this.canvas = fresh;
    }
    this.backends.useCpu(reason);
    this.scheduleRender();
  }

  protected async render(): Promise<void> {
    const inputs = inputsFrom(this.values);
    const backend = await this.backends.choose();
    const reference = computeCurveCpu(inputs);
    let result: BeerLawResult;
    if (backend.kind === 'gpu') {
      try {
        result = await backend.renderer.computeCurve(inputs);
        await backend.renderer.draw(inputs);
      } catch (error) {
        this.fallBackToCpu(gpuFailureReason(error));
        return;
      }
      this.clearNotice('backend');
    } else {
      if (this.canvas) drawBeamCpu(this.canvas, inputs);
      result = reference;
      this.showCpuFallbackNotice(
        backend.reason,
        `Showing the float64 CPU reference, drawn at half resolution.`,
      );
    }
    this.showResult(inputs, result, reference, backend);
  }

  private showResult(
    inputs: BeerLawInputs,
    result: BeerLawResult,
    reference: BeerLawResult,
    backend: Backend,
  ): void {
    const set = (key: string, text: string, state?: 'ok' | 'bad'): void =>
      this.readouts?.set(key, text, state);
    const tauExit = reference.opticalDepth[reference.opticalDepth.length - 1] ?? 0;
    set('tau', formatNumber(tauExit));
    set(
      'exit',
      `${formatNumber(result.exit)}${backend.kind === 'gpu' ? ' (GPU, f32)' : ' (CPU, f64)'}`,
    );
    set(
      'reference',
      inputs.profile === 'homogeneous'
        ? `${formatNumber(reference.exit)} = e^(−σt·d)`
        : formatNumber(reference.exit),
    );
    const difference = Math.abs(result.exit - reference.exit);
    const relative = reference.exit > 0 ? difference / reference.exit : difference;
    set(
      'error',
      reference.exit > 0 ? formatNumber(relative, 2) : `${formatNumber(difference, 2)} (absolute)`,
    );
    const product = result.beforeSplit * result.afterSplit;
    set(
      'split',
      `${formatNumber(result.beforeSplit)} × ${formatNumber(result.afterSplit)} = ${formatNumber(product)}`,
    );
    // The identity is exact; what remains is rounding. On the GPU that is f32 plus
    // WGSL's sin, allowed an absolute error of 2^-11 (≈ 5e-4 relative on τ here).
    const budget = backend.kind === 'gpu' ? 5e-4 : 1e-12;
    const splitDifference =
      Math.abs(product - result.exit) / Math.max(result.exit, Number.MIN_VALUE);
    const holds = splitDifference <= budget || Math.abs(product - result.exit) < 1e-37;
    set(
      'split-check',
      holds
        ? `holds: equals T(0→d) to ${formatNumber(splitDifference, 2)} (rounding budget ${formatNumber(budget, 1)})`
        : `differs by ${formatNumber(splitDifference, 2)}, above the rounding budget ${formatNumber(budget, 1)}`,
      holds ? 'ok' : 'bad',
    );
    set('mfp', inputs.sigmaT > 0 ? `${formatNumber(1 / inputs.sigmaT, 4)} m` : '∞ (no medium)');

    const how = timingLabel(result.timing);
    this.recordFrameCost(result.milliseconds, how);
    const where =
      backend.kind === 'gpu' ? `WebGPU (${backend.gpu.adapterDescription})` : 'CPU fallback';
    if (this.readouts) {
      this.readouts.cost.textContent =
        `${where}: ${result.transmittance.length} samples of T(s) in ${formatMilliseconds(result.milliseconds)} (${how}); ` +
        `float64 reference on the CPU in ${formatMilliseconds(reference.milliseconds)}.`;
    }
    if (this.canvas) {
      this.canvas.setAttribute(
        'aria-label',
        `A beam entering a ${inputs.profile} slab ${formatNumber(inputs.thickness, 3)} m thick from the left; ` +
          `it leaves with ${formatNumber(100 * result.exit, 3)}% of its intensity.`,
      );
    }
    const series = [{ label: 'T(0→s)', color: '#d9822b', values: result.transmittance }];
    if (inputs.profile !== 'homogeneous') {
      series.push({
        label: 'homogeneous, same σ̄t',
        color: '#5b8def',
        values: result.depths.map((s) => Math.exp(-inputs.sigmaT * s)),
      });
    }
    this.plot?.update(
      result.depths,
      series.map((s, i) => (i === 1 ? { ...s, dash: [6, 4] } : s)),
    );
  }
}

export function defineBeerLaw(): void {
  if (!customElements.get('sb-beer-law')) customElements.define('sb-beer-law', BeerLawElement);
}
