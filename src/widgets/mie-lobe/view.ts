// The drawing of <sb-mie-lobe>: one log-scale plot of p(θ). The series and the table
// come from the compute worker (jobs.ts); the curve the widget draws is the tabulated
// phase function evaluated by the WGSL library on the GPU (gpuBackend.ts) or, without
// WebGPU, by its float64 twin.
import type { GpuContext } from '../../gpu/device.ts';
import { workerJobs } from '../../workers/compute.ts';
import type { FrameBackend } from '../base/definition.ts';
import { formatNumber } from '../base/format.ts';
import { LinePlot, createPlotArea } from '../base/plot.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import type { jobs } from './jobs.ts';
import { MieLobeGpu } from './gpuBackend.ts';
import { inputsFrom, plotAngles } from './model.ts';
import type { MieLobeFrame } from './widget.ts';
import { context2d } from '../base/canvas2d.ts';

/** Decades of p the polar picture spans below the lobe's peak. */
const POLAR_DECADES = 6;

/**
 * The lobe as a log-polar picture: the scattering point at the centre, the incident
 * beam from the left, radius ∝ log10 p above a floor POLAR_DECADES below the peak,
 * mirrored below the axis (the lobe is symmetric about the beam). The values are the
 * frame's numbers (the GPU's evaluation of the table, or its CPU twin); this only draws
 * them, with rings every decade.
 */
function drawPolar(
  canvas: HTMLCanvasElement,
  degrees: Float64Array,
  curves: readonly { values: ArrayLike<number>; color: string; dash: number[] }[],
): void {
  const ctx = context2d(canvas);
  if (!ctx) return;
  const { width, height } = canvas;
  const dark = matchMedia('(prefers-color-scheme: dark)').matches;
  ctx.fillStyle = dark ? '#15171c' : '#fbfaf7';
  ctx.fillRect(0, 0, width, height);
  let peak = 0;
  for (const curve of curves)
    for (let i = 0; i < curve.values.length; i++) peak = Math.max(peak, curve.values[i]!);
  if (!(peak > 0)) return;
  const top = Math.ceil(Math.log10(peak));
  const floor = top - POLAR_DECADES;
  const cx = width * 0.42;
  const cy = height / 2;
  const scale = (Math.min(width * 0.55, height * 0.48) / POLAR_DECADES) * 0.98;
  ctx.strokeStyle = dark ? '#3a3f4a' : '#d8d4cc';
  ctx.lineWidth = 1;
  for (let decade = 1; decade <= POLAR_DECADES; decade++) {
    ctx.beginPath();
    ctx.arc(cx, cy, decade * scale, 0, 2 * Math.PI);
    ctx.stroke();
  }
  ctx.beginPath();
  ctx.moveTo(0, cy);
  ctx.lineTo(width, cy);
  ctx.stroke();
  for (const curve of curves) {
    ctx.strokeStyle = curve.color;
    ctx.lineWidth = 2.5;
    ctx.setLineDash(curve.dash);
    for (const side of [1, -1]) {
      ctx.beginPath();
      for (let i = 0; i < degrees.length; i++) {
        const p = curve.values[i]!;
        const r = p > 0 ? Math.max(0, Math.log10(p) - floor) * scale : 0;
        const theta = (degrees[i]! * Math.PI) / 180;
        const x = cx + r * Math.cos(theta);
        const y = cy - side * r * Math.sin(theta);
        if (i === 0) ctx.moveTo(x, y);
        else ctx.lineTo(x, y);
      }
      ctx.stroke();
    }
  }
  ctx.setLineDash([]);
}

export function createView(context: ViewContext): WidgetView<MieLobeFrame, MieLobeGpu> {
  const work = workerJobs<typeof jobs>('mie-lobe');
  const angles = plotAngles();
  const polar = context.canvas({ width: 960, height: 420 });
  let plot: LinePlot | null = null;
  let plotArea: HTMLDivElement | null = null;
  const analyse = (signal: AbortSignal) =>
    work.run('analyseSphere', [inputsFrom(context.values)], { signal });
  return {
    cpuNotice: 'The tabulated phase function is evaluated by its float64 twin on the CPU.',
    build(stage) {
      stage.appendChild(polar.element);
      plotArea = createPlotArea('Plot of the phase function p(θ) against the scattering angle θ');
      stage.appendChild(plotArea);
      plot = new LinePlot(plotArea, {
        xLabel: 'scattering angle θ (°)',
        yLabel: 'p(θ) (1/sr)',
        yLog: true,
        height: 340,
      });
    },
    createRenderer: (gpu: GpuContext) => new MieLobeGpu(gpu),
    async renderGpu(renderer, _gpu, request) {
      const inputs = inputsFrom(context.values);
      const analysis = await analyse(request.signal);
      const lobe = await renderer.evaluate(analysis.table, angles.oneMinusMu, angles.onePlusMu);
      return {
        inputs,
        analysis,
        drawn: lobe.values,
        milliseconds: lobe.milliseconds,
        timing: lobe.timing,
      };
    },
    async renderCpu(request) {
      const inputs = inputsFrom(context.values);
      const analysis = await analyse(request.signal);
      // The worker evaluated the table's twin at the plot's angles already (jobs.ts).
      return {
        inputs,
        analysis,
        drawn: analysis.tabulated,
        milliseconds: analysis.tableMs,
        timing: 'cpu',
      };
    },
    show({ inputs, analysis, drawn }: MieLobeFrame, backend: FrameBackend) {
      drawPolar(polar.element, angles.degrees, [
        { values: analysis.hg, color: '#5b8def', dash: [8, 5] },
        { values: drawn, color: '#d9822b', dash: [] },
      ]);
      polar.element.setAttribute(
        'aria-label',
        `Log-polar picture of the lobe, light arriving from the left: Mie (solid) against Henyey–Greenstein with g = ${formatNumber(analysis.g, 3)} (dashed), rings every decade of p.`,
      );
      plotArea?.setAttribute(
        'aria-label',
        `Phase function of a sphere of radius ${formatNumber(inputs.radiusUm, 3)} µm, m = ${inputs.n} + ${inputs.kappa}i, at ${inputs.wavelengthNm} nm: ` +
          `forward ${formatNumber(analysis.exact[0]!, 3)}, backward ${formatNumber(analysis.exact[analysis.exact.length - 1]!, 3)} per steradian, g = ${formatNumber(analysis.g, 3)}.`,
      );
      plot?.update(angles.degrees, [
        {
          label: backend.kind === 'gpu' ? 'Mie, table on the GPU' : 'Mie, table (CPU twin)',
          color: '#d9822b',
          values: drawn,
        },
        { label: 'Mie series (float64)', color: '#8a5a2b', dash: [2, 3], values: analysis.exact },
        {
          label: `HG, g = ${formatNumber(analysis.g, 3)}`,
          color: '#5b8def',
          dash: [6, 4],
          values: analysis.hg,
        },
        { label: 'Rayleigh', color: '#3aa66a', dash: [10, 4], values: analysis.rayleigh },
      ]);
    },
  };
}
