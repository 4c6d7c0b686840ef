// The drawing of <sb-dipole-profile>: the profile plot with its legend, the lit disc
// (WebGPU, or the CPU twin at CPU_DISC_SIZE pixels), the plot of the errors against
// the Monte Carlo's time, the table of totals, the material ↔ coefficient link of the
// controls, and the progressive Monte Carlo ("More photons", Cancel). Readouts,
// backends and fallback: widget.ts and the base element.
import type { Backend } from '../base/backend.ts';
import type { FrameBackend } from '../base/definition.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { LinePlot, createPlotArea } from '../base/plot.ts';
import { timingLabel, type GpuTiming } from '../base/timing.ts';
import type { FrameRequest } from '../base/refinement.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import {
  appendBatches,
  summarize,
  type ChannelEstimate,
  type SlabBatches,
  type SlabRun,
} from '../../subsurface/slabKernel.ts';
import { findMaterial } from '../../subsurface/materials.ts';
import { CPU_DISC_SIZE, monteCarloCpu, paintDiscPixels } from './cpuBackend.ts';
import { curveInputsOf, discInputsOf, type jobs as dipoleJobTable } from './jobs.ts';
import { workerJobs } from '../../workers/compute.ts';
import { DipoleProfileGpu } from './gpuBackend.ts';
import {
  CHANNEL_NAMES,
  MATERIAL_PARAMETERS,
  MC_MAX_COLLISIONS,
  compareTotal,
  firstRunPhotons,
  inputsFrom,
  materialValues,
  meanAbsolute,
  monteCarloKey,
  slabRunFor,
  type ProfileCurves,
  type ProfileInputs,
} from './model.ts';
import { ProfilePlot, profileLegend } from './profilePlot.ts';
import { betterDipoleNote } from './modelNote.ts';
import { count, type DipoleFrame, type MonteCarloSummary } from './widget.ts';

/**
 * The CPU fallback's curves, disc and Monte Carlo chunks, in the compute worker, cached by
 * parameters (jobs.ts).
 */
const cpuJobs = workerJobs<typeof dipoleJobTable>('dipole-profile');

/** Side of the disc picture on the GPU (pixels). */
const DISC_SIZE = 320;
/** A progressive step aims at this much GPU time, so the page stays responsive. */
const STEP_BUDGET_MS = 400;

const MODEL_ROWS = [
  ['dipole', 'Dipole'],
  ['better', 'Better dipole'],
  ['burley', 'Christensen–Burley'],
  ['mc', 'Monte Carlo ± SE'],
] as const;

/** The Monte Carlo accumulated for one medium (cleared when the medium changes). */
interface MonteCarloState {
  key: string;
  /** The run that set up the accumulation (profile bins, η: what summarize needs). */
  template: SlabRun | null;
  batches: SlabBatches | null;
  photons: number;
  milliseconds: number;
  timing: string;
  nextOffset: number;
  /** Cumulative time and the errors at each step, for the error-vs-time plot. */
  history: { milliseconds: number; se: number; dipole: number; better: number }[];
}

const emptyMonteCarlo = (key: string): MonteCarloState => ({
  key,
  template: null,
  batches: null,
  photons: 0,
  milliseconds: 0,
  timing: '',
  nextOffset: 0,
  history: [],
});

function frameBackend(backend: Backend<DipoleProfileGpu>): FrameBackend {
  return backend.kind === 'gpu'
    ? { kind: 'gpu', adapterDescription: backend.gpu.adapterDescription }
    : { kind: 'cpu', reason: backend.reason };
}

export function createView(
  context: ViewContext<DipoleProfileGpu>,
): WidgetView<DipoleFrame, DipoleProfileGpu> {
  const disc = context.canvas({ width: DISC_SIZE, height: DISC_SIZE });
  disc.element.setAttribute('aria-label', 'Disc of the material lit by a thin beam at its centre');
  let plot: ProfilePlot | null = null;
  let errorPlot: LinePlot | null = null;
  const totalCells = new Map<string, HTMLElement>();
  const moreButton = document.createElement('button');
  const cancelButton = document.createElement('button');
  const progress = document.createElement('progress');
  const status = document.createElement('span');
  let curves: ProfileCurves | null = null;
  let curvesCost: { milliseconds: number; timing: GpuTiming | 'cpu' } = {
    milliseconds: 0,
    timing: 'cpu',
  };
  /** The last render's cost (profiles and a first Monte Carlo run), kept for the steps' reports. */
  let frameMilliseconds = 0;
  let mc: MonteCarloState = emptyMonteCarlo('');
  /** Bumped to stop a progressive run (Cancel, a new medium, a lost device). */
  let mcToken = 0;
  let running = false;

  /** Says what the better dipole leaves out, with this medium's reduced albedos (issue 17). */
  const modelNote = document.createElement('p');

  const setStatus = (text: string): void => {
    status.textContent = text;
  };

  const setRunning = (on: boolean): void => {
    running = on;
    moreButton.disabled = on;
    cancelButton.disabled = !on;
    if (on) progress.value = 0;
  };

  const cancelRun = (message: string): void => {
    mcToken += 1;
    if (running) {
      setRunning(false);
      if (message) setStatus(`Monte Carlo ${message} at ${count(mc.photons)} photons per channel.`);
    }
  };

  const estimates = (): ChannelEstimate[] | null =>
    mc.batches && mc.template ? summarize(mc.template, mc.batches) : null;

  /** The frame the readouts show: the current profiles and the Monte Carlo so far. */
  const frameOf = (inputs: ProfileInputs, shownCurves: ProfileCurves): DipoleFrame => {
    const channels = estimates();
    let monteCarlo: MonteCarloSummary | null = null;
    if (channels) {
      monteCarlo = {
        batches: channels[0]!.batches,
        channels: channels.map((e, c) => ({
          se: e.diffuseReflectance.se,
          dipole: compareTotal(shownCurves.dipoleTotal[c]!, e),
          better: compareTotal(shownCurves.betterTotal[c]!, e),
          collisionsPerPhoton: e.collisionsPerPhoton,
        })),
        capped: channels.reduce((sum, e) => sum + e.capped, 0),
        cappedWeight: Math.max(...channels.map((e) => e.cappedWeight)),
        cap: MC_MAX_COLLISIONS,
      };
    }
    return {
      inputs,
      curves: shownCurves,
      curvesMilliseconds: curvesCost.milliseconds,
      curvesTiming: curvesCost.timing,
      frameMilliseconds,
      photons: mc.photons,
      mcMilliseconds: mc.milliseconds,
      mcTiming: mc.timing,
      monteCarlo,
    };
  };

  /**
   * One Monte Carlo run of `photons` per channel, appended to the accumulation if the
   * medium is still the same and the run was not cancelled. Returns its cost. On the CPU,
   * `signal` (a render's input signal) ends the run early with the batches done, so that
   * the next input's picture does not wait for it.
   */
  const monteCarloStep = async (
    backend: Backend<DipoleProfileGpu>,
    inputs: ProfileInputs,
    photons: number,
    token: number,
    signal?: AbortSignal,
  ): Promise<{ milliseconds: number } | null> => {
    const key = mc.key;
    const run = slabRunFor(inputs, photons, mc.nextOffset);
    let batches: SlabBatches;
    let milliseconds: number;
    let timing: GpuTiming | 'cpu';
    if (backend.kind === 'gpu') {
      const result = await backend.renderer.monteCarlo(run);
      batches = result.batches;
      milliseconds = result.gpuMs ?? result.wallMs;
      timing = result.gpuMs === null ? 'gpu-wall' : 'gpu-timestamp';
    } else {
      const result = await monteCarloCpu(
        run,
        (chunkRun, first, last) =>
          cpuJobs.run('slabChunk', [chunkRun, first, last], signal ? { signal } : {}),
        () => token !== mcToken,
      );
      batches = result.batches;
      milliseconds = result.milliseconds;
      timing = 'cpu';
    }
    if (mc.key !== key) return null;
    const done = batches.channels[0]?.walks.length ?? 0;
    if (done === 0) return null;
    mc.template ??= run;
    mc.batches = mc.batches ? appendBatches(mc.batches, batches) : batches;
    mc.nextOffset += done * 64;
    mc.photons += batches.channels[0]!.walks.reduce((a, b) => a + b, 0);
    mc.milliseconds += milliseconds;
    mc.timing = timingLabel(timing);
    const channels = estimates();
    if (channels && curves) {
      const shown = curves;
      // Relative errors in per cent, averaged over the channels.
      const relative = (totals: number[]): number =>
        100 * meanAbsolute(channels.map((e, c) => compareTotal(totals[c]!, e).relative));
      mc.history.push({
        milliseconds: mc.milliseconds,
        se:
          100 *
          meanAbsolute(
            channels.map(
              (e) => e.diffuseReflectance.se / Math.max(e.diffuseReflectance.mean, 1e-12),
            ),
          ),
        dipole: relative(shown.dipoleTotal),
        better: relative(shown.betterTotal),
      });
    }
    return { milliseconds };
  };

  /** "More photons": doubles the Monte Carlo (steps of ≈ STEP_BUDGET_MS) up to the target. */
  const runMore = async (): Promise<void> => {
    if (running) return;
    const token = ++mcToken;
    const inputs = inputsFrom(context.values);
    const backend = await context.backend();
    if (mc.key !== monteCarloKey(inputs)) return;
    const target = inputs.photonTarget;
    const start = mc.photons;
    setRunning(true);
    try {
      while (token === mcToken && mc.photons < target) {
        const perPhoton = mc.milliseconds / Math.max(mc.photons, 1);
        const affordable = perPhoton > 0 ? STEP_BUDGET_MS / perPhoton : mc.photons;
        const photons = Math.max(256, Math.min(mc.photons, target - mc.photons, affordable));
        setStatus(`${count(mc.photons)} of ${count(target)} photons per channel…`);
        const step = await monteCarloStep(backend, inputs, photons, token);
        if (!step) break;
        progress.value = Math.min((mc.photons - start) / Math.max(target - start, 1), 1);
        if (curves) context.report(frameOf(inputs, curves), frameBackend(backend));
        await new Promise((resolve) => requestAnimationFrame(resolve));
      }
      if (token === mcToken)
        setStatus(
          `Done: ${count(mc.photons)} photons per channel in ${formatMilliseconds(mc.milliseconds)}.`,
        );
    } catch (error) {
      setStatus(`Failed: ${error instanceof Error ? error.message : String(error)}`);
    } finally {
      if (token === mcToken) setRunning(false);
    }
  };

  /** A link that names a preset but not its coefficients shows the preset's numbers in the controls. */
  const syncMaterialControls = (): void => {
    const values = materialValues(String(context.values['material']));
    if (!values) return;
    for (const [key, value] of Object.entries(values))
      if (context.values[key] !== value) context.setValue(key, String(value));
  };

  /** The first Monte Carlo run of a new medium, after its profiles; the frame of this render. */
  const finishRender = async (
    backend: Backend<DipoleProfileGpu>,
    inputs: ProfileInputs,
    result: { curves: ProfileCurves; milliseconds: number },
    timing: GpuTiming | 'cpu',
    request: FrameRequest,
  ): Promise<DipoleFrame> => {
    curves = result.curves;
    curvesCost = { milliseconds: result.milliseconds, timing };
    frameMilliseconds = result.milliseconds;
    const key = monteCarloKey(inputs);
    if (mc.key !== key) {
      cancelRun('');
      mc = emptyMonteCarlo(key);
    }
    // The first run is complete once it reached its photons (planBatches rounds up); one
    // an input cut short (CPU) is finished by the next render of the same medium.
    const firstRun = firstRunPhotons(inputs);
    if (mc.photons < firstRun) {
      // Issue 23: the models first (a millisecond), the Monte Carlo's first run (most of
      // a second on a CPU WebGPU) in the next stage, so a slider shows its curves at once.
      if (request.stage === 0)
        return {
          ...frameOf(inputs, result.curves),
          refinement: {
            label: 'Preview: the three models; the first Monte Carlo run follows',
            pending: 'frame',
          },
        };
      const step = await monteCarloStep(
        backend,
        inputs,
        firstRun - mc.photons,
        mcToken,
        request.signal,
      );
      if (step) frameMilliseconds += step.milliseconds;
    }
    return frameOf(inputs, result.curves);
  };

  return {
    cpuNotice: `Showing the float64 CPU twins: the same profiles and Monte Carlo walks, the disc at ${CPU_DISC_SIZE}×${CPU_DISC_SIZE} pixels.`,
    build(stage) {
      const plotArea = document.createElement('div');
      plotArea.className = 'sb-plot sb-dp-profile';
      plotArea.setAttribute('role', 'img');
      plotArea.setAttribute(
        'aria-label',
        'Log–log plot of the diffuse reflectance profile Rd(r) per colour channel: dipole, better dipole, Christensen–Burley and Monte Carlo with error bars',
      );
      modelNote.className = 'sb-dp-model-note';
      stage.append(plotArea, profileLegend(), modelNote);
      plot = new ProfilePlot(plotArea);

      const row = document.createElement('div');
      row.className = 'sb-dp-row';
      const discFigure = document.createElement('figure');
      discFigure.className = 'sb-dp-disc';
      const caption = document.createElement('figcaption');
      caption.textContent =
        'The material seen from above, lit by a thin beam at the centre (classic dipole, exposure tone curve).';
      discFigure.append(disc.element, caption);

      const errorArea = document.createElement('div');
      errorArea.className = 'sb-dp-errors';
      const errorHint = document.createElement('p');
      errorHint.className = 'sb-sweep-hint';
      errorHint.textContent =
        'Relative error of the total Rd (mean of R, G, B) against the Monte Carlo’s time: the Monte Carlo’s standard error falls as t^−½, while each model’s difference from it levels off at the model’s own error.';
      const errorPlotArea = createPlotArea(
        'Log plot of the Monte Carlo’s relative standard error and of the dipole models’ relative differences from the Monte Carlo against Monte Carlo time',
      );
      errorArea.append(errorHint, errorPlotArea);
      errorPlot = new LinePlot(errorPlotArea, {
        xLabel: 'log₁₀ Monte Carlo time (ms)',
        yLabel: 'error of total Rd (%)',
        yLog: true,
        height: 200,
      });
      row.append(discFigure, errorArea);
      stage.appendChild(row);

      const controls = document.createElement('div');
      controls.className = 'sb-sweep sb-dp-mc';
      moreButton.type = 'button';
      moreButton.className = 'sb-button';
      moreButton.textContent = 'More photons';
      moreButton.addEventListener('click', () => void runMore());
      cancelButton.type = 'button';
      cancelButton.className = 'sb-button';
      cancelButton.textContent = 'Cancel';
      cancelButton.disabled = true;
      cancelButton.addEventListener('click', () => cancelRun('cancelled'));
      progress.max = 1;
      progress.value = 0;
      progress.setAttribute('aria-label', 'Monte Carlo progress');
      status.className = 'sb-dp-status';
      status.setAttribute('role', 'status');
      controls.append(moreButton, cancelButton, progress, status);
      stage.appendChild(controls);
    },
    buildReadoutExtras(area) {
      // The table of totals comes first, above the readout list.
      const table = document.createElement('table');
      table.className = 'sb-dp-totals';
      const caption = document.createElement('caption');
      caption.textContent =
        'Total diffuse reflectance Rd: the dipole of Jensen et al. 2001, the better dipole of d’Eon 2012, Christensen–Burley matched to the dipole’s total, and the Monte Carlo with one standard error.';
      const head = document.createElement('thead');
      head.innerHTML = `<tr><th scope="col">Model</th>${CHANNEL_NAMES.map((c) => `<th scope="col">${c}</th>`).join('')}</tr>`;
      const body = document.createElement('tbody');
      for (const [key, label] of MODEL_ROWS) {
        const tr = document.createElement('tr');
        const th = document.createElement('th');
        th.scope = 'row';
        th.textContent = label;
        tr.appendChild(th);
        CHANNEL_NAMES.forEach((channel) => {
          const td = document.createElement('td');
          td.dataset['readout'] = `total-${key}-${channel.toLowerCase()}`;
          td.textContent = '…';
          tr.appendChild(td);
          totalCells.set(`${key}-${channel}`, td);
        });
        body.appendChild(tr);
      }
      table.append(caption, head, body);
      area.prepend(table);
    },
    /** Editing a coefficient by hand leaves the preset; choosing a preset fills in its coefficients. */
    valueChanged(name) {
      if (name === 'material') {
        const values = materialValues(String(context.values['material']));
        if (values)
          for (const [key, value] of Object.entries(values)) context.setValue(key, String(value));
        return;
      }
      if (
        (MATERIAL_PARAMETERS as readonly string[]).includes(name) &&
        context.values['material'] !== 'manual'
      )
        context.setValue('material', 'manual');
    },
    createRenderer: (gpu) => new DipoleProfileGpu(gpu, disc.element),
    refinement: (frame) => frame.refinement,
    async renderGpu(renderer, gpu, request) {
      syncMaterialControls();
      const inputs = inputsFrom(context.values);
      const result = await renderer.curves(inputs);
      await renderer.drawDisc(inputs);
      return finishRender({ kind: 'gpu', gpu, renderer }, inputs, result, result.timing, request);
    },
    async renderCpu(request) {
      syncMaterialControls();
      const inputs = inputsFrom(context.values);
      // The float64 curves and the disc's pixels in the worker: the page only paints.
      const options = { signal: request.signal };
      const [result, picture] = await Promise.all([
        cpuJobs.run('curves', [curveInputsOf(inputs)], options),
        cpuJobs.run('disc', [discInputsOf(inputs)], options),
      ]);
      paintDiscPixels(disc.element, picture);
      return finishRender({ kind: 'cpu', reason: '' }, inputs, result, 'cpu', request);
    },
    onCpuFallback: () => {
      cancelRun('stopped: the GPU was lost');
      mc = emptyMonteCarlo('');
    },
    destroy: () => cancelRun(''),
    /** Plot, totals, the capped notice and the error plot from the current curves and Monte Carlo. */
    show({ inputs, curves: shown, monteCarlo }) {
      const channels = estimates();
      modelNote.textContent = betterDipoleNote(inputs, monteCarlo);
      plot?.update({ curves: shown, monteCarlo: channels?.map((e) => e.profile) ?? null });
      const setTotal = (row: string, channel: number, text: string): void => {
        const cell = totalCells.get(`${row}-${CHANNEL_NAMES[channel]}`);
        if (cell) cell.textContent = text;
      };
      // Totals to five decimals: the columns line up, and ketchup's 0.00183 keeps three digits.
      const total = (x: number): string => x.toFixed(5);
      for (let c = 0; c < 3; c++) {
        setTotal('dipole', c, total(shown.dipoleTotal[c]!));
        setTotal('better', c, total(shown.betterTotal[c]!));
        setTotal('burley', c, total(shown.dipoleTotal[c]!));
        const e = channels?.[c];
        setTotal(
          'mc',
          c,
          e
            ? `${total(e.diffuseReflectance.mean)} ± ${formatNumber(e.diffuseReflectance.se, 2)}`
            : '…',
        );
      }
      if (monteCarlo) {
        const { capped, cappedWeight } = monteCarlo;
        if (capped > 0)
          context.showNotice(
            'capped',
            'warning',
            `${capped} Monte Carlo walks reached the cap of ${MC_MAX_COLLISIONS} flights with light still inside (up to ${formatNumber(100 * cappedWeight, 2)}% of the incident light per channel): the Monte Carlo Rd is low by about that much. Nearly conservative media (σa → 0) have very long walks.`,
          );
        else context.clearNotice('capped');
      }
      const history = mc.history;
      if (history.length > 0) {
        errorPlot?.update(
          history.map((h) => Math.log10(Math.max(h.milliseconds, 1e-3))),
          [
            { label: 'MC standard error', color: '#7a5cc7', values: history.map((h) => h.se) },
            { label: '|dipole − MC|/MC', color: '#d9822b', values: history.map((h) => h.dipole) },
            {
              label: '|better dipole − MC|/MC',
              color: '#1f8a8a',
              dash: [6, 4],
              values: history.map((h) => h.better),
            },
          ],
        );
      }
      disc.element.setAttribute(
        'aria-label',
        `Disc of ${findMaterial(inputs.material)?.label ?? 'the material'} lit by a thin beam: total Rd (dipole) ${shown.dipoleTotal.map((v) => formatNumber(v, 3)).join(', ')} in R, G, B`,
      );
    },
  };
}
