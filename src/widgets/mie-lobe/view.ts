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

export function createView(context: ViewContext): WidgetView<MieLobeFrame, MieLobeGpu> {
  const work = workerJobs<typeof jobs>('mie-lobe');
  const angles = plotAngles();
  let plot: LinePlot | null = null;
  let plotArea: HTMLDivElement | null = null;
  const analyse = (signal: AbortSignal) =>
    work.run('analyseSphere', [inputsFrom(context.values)], { signal });
  return {
    cpuNotice: 'The tabulated phase function is evaluated by its float64 twin on the CPU.',
    build(stage) {
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
