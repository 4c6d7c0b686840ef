// The drawing of <sb-beer-law>: the beam picture (WebGPU render pass, or the CPU
// twin at half resolution) and the plot of T(s). The readouts, backend choice and
// fallback are the base element's (widget.ts holds the rows).
import type { GpuContext } from '../../gpu/device.ts';
import type { FrameBackend } from '../base/definition.ts';
import { formatNumber } from '../base/format.ts';
import { LinePlot, createPlotArea } from '../base/plot.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import { CpuPicture } from '../base/cpuPicture.ts';
import { workerJobs } from '../../workers/compute.ts';
import { computeCurveCpu } from './cpuBackend.ts';
import type { jobs } from './jobs.ts';
import { BeerLawGpu } from './gpuBackend.ts';
import { inputsFrom } from './model.ts';
import type { BeerLawFrame } from './widget.ts';

export function createView(context: ViewContext): WidgetView<BeerLawFrame, BeerLawGpu> {
  const beam = context.canvas({ width: 960, height: 360 });
  let plot: LinePlot | null = null;
  // Without WebGPU the beam is painted in the compute worker: 1/8, 1/4, then 1/2 of
  // the canvas's resolution, the first within the CPU's first-picture budget.
  const cpuBeam = new CpuPicture(
    workerJobs<typeof jobs>('beer-law'),
    'paintBeam',
    beam.element,
    [8, 4, 2],
  );
  return {
    cpuNotice: 'Showing the float64 CPU reference; the beam is drawn at up to half resolution.',
    build(stage) {
      stage.appendChild(beam.element);
      const plotArea = createPlotArea('Plot of transmittance T(s) against depth s');
      stage.appendChild(plotArea);
      plot = new LinePlot(plotArea, {
        xLabel: 'depth s (m)',
        yLabel: 'T(0→s)',
        yRange: [0, 1],
        height: 280,
      });
    },
    createRenderer: (gpu: GpuContext) => new BeerLawGpu(gpu, beam.element),
    async renderGpu(renderer) {
      const inputs = inputsFrom(context.values);
      const reference = computeCurveCpu(inputs);
      const result = await renderer.computeCurve(inputs);
      await renderer.draw(inputs);
      return { inputs, result, reference };
    },
    async renderCpu(request) {
      const inputs = inputsFrom(context.values);
      const reference = computeCurveCpu(inputs);
      const picture = await cpuBeam.draw(beam.element, inputs, request);
      return { inputs, result: reference, reference, picture };
    },
    refinement: (frame) => frame.picture?.refinement,
    destroyRenderer: (renderer) => renderer.destroy(),
    show({ inputs, result }: BeerLawFrame, _backend: FrameBackend) {
      beam.element.setAttribute(
        'aria-label',
        `A beam entering a ${inputs.profile} slab ${formatNumber(inputs.thickness, 3)} m thick from the left; ` +
          `it leaves with ${formatNumber(100 * result.exit, 3)}% of its intensity.`,
      );
      const series = [{ label: 'T(0→s)', color: '#d9822b', values: result.transmittance }];
      if (inputs.profile !== 'homogeneous') {
        series.push({
          label: 'homogeneous, same σ̄t',
          color: '#5b8def',
          values: result.depths.map((s) => Math.exp(-inputs.sigmaT * s)),
        });
      }
      plot?.update(
        result.depths,
        series.map((s, i) => (i === 1 ? { ...s, dash: [6, 4] } : s)),
      );
    },
  };
}
