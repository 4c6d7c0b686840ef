// The drawing of <sb-vre-ray>: the ray picture (medium on top, weighted source
// below; WebGPU, or the CPU twin at half resolution), a legend, and the plot of what
// reaches the eye from [0, s] term by term. Readouts and backends: widget.ts and the base.
import type { GpuContext } from '../../gpu/device.ts';
import { formatNumber } from '../base/format.ts';
import { LinePlot, createPlotArea } from '../base/plot.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import { CpuPicture } from '../base/cpuPicture.ts';
import { workerJobs } from '../../workers/compute.ts';
import { marchRayCpu } from './cpuBackend.ts';
import type { jobs } from './jobs.ts';
import { VreRayGpu } from './gpuBackend.ts';
import { exactRadiance, inputsFrom } from './model.ts';
import { marchedTransmittance, type VreRayFrame } from './widget.ts';

export function createView(context: ViewContext): WidgetView<VreRayFrame, VreRayGpu> {
  const ray = context.canvas({ width: 960, height: 360 });
  let plot: LinePlot | null = null;
  // Without WebGPU the ray is painted in the compute worker: 1/8, 1/4, then 1/2 of
  // the canvas's resolution, the first within the CPU's first-picture budget.
  const cpuRay = new CpuPicture(
    workerJobs<typeof jobs>('vre-ray'),
    'paintRay',
    ray.element,
    [8, 4, 2],
  );
  return {
    cpuNotice: 'Showing the float64 CPU march; the ray is drawn at up to half resolution.',
    build(stage) {
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
      stage.append(ray.element, legend);
      const plotArea = createPlotArea(
        'Plot of the radiance reaching the eye from the segment [0, s], term by term, and T(0→s), against s',
      );
      stage.appendChild(plotArea);
      plot = new LinePlot(plotArea, {
        xLabel: 's (m)',
        yLabel: 'from [0, s]; T(0→s)',
        height: 280,
      });
    },
    createRenderer: (gpu: GpuContext) => new VreRayGpu(gpu, ray.element),
    async renderGpu(renderer) {
      const inputs = inputsFrom(context.values);
      const twin = marchRayCpu(inputs);
      const result = await renderer.march(inputs);
      await renderer.draw(inputs);
      return { inputs, result, twin, exact: exactRadiance(inputs) };
    },
    async renderCpu(request) {
      const inputs = inputsFrom(context.values);
      const twin = marchRayCpu(inputs);
      const picture = await cpuRay.draw(ray.element, inputs, request);
      return { inputs, result: twin, twin, exact: exactRadiance(inputs), picture };
    },
    refinement: (frame) => frame.picture?.refinement,
    destroyRenderer: (renderer) => renderer.destroy(),
    show({ inputs, result }) {
      const T = marchedTransmittance(result);
      ray.element.setAttribute(
        'aria-label',
        `A ray ${formatNumber(inputs.length, 3)} m long from the eye on the left to a background of radiance ` +
          `${formatNumber(inputs.background, 3)} on the right; ${formatNumber(100 * T, 3)}% of the background reaches the eye.`,
      );
      const background = result.depths.map(() => T * inputs.background);
      plot?.update(result.depths, [
        { label: 'emission ∫T σa Le', color: '#d9822b', values: result.emitted },
        { label: 'in-scattering ∫T σs L_in', color: '#5b8def', values: result.inscattered },
        { label: 'background T(0→d)·L_bg', color: '#8a8f98', dash: [6, 4], values: background },
        { label: 'T(0→s)', color: '#3aa17e', dash: [2, 3], values: result.transmittance },
      ]);
    },
  };
}
