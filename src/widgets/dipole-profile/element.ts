// <sb-dipole-profile>: the diffusion dipole and its profiles (chapter 11). Evaluates
// the classic dipole, the better dipole and the Christensen–Burley profile per RGB
// channel on the GPU (the library's dipole module) and plots them on log–log axes
// against a GPU Monte Carlo of the same half-space with ±1 SE error bars; tabulates the
// total R_d of each; shows the Monte Carlo's cost (GPU ms, photons, collisions) next
// to its standard error and to each model's difference from it, with a plot of those
// errors against the Monte Carlo's time; draws a disc of the material lit by a thin
// beam from the dipole. "More photons" continues the Monte Carlo progressively and can
// be cancelled. Without WebGPU the float64 twins do all of it on the CPU.
import { BackendChooser, type Backend, gpuFailureReason } from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel, type GpuTiming } from '../base/timing.ts';
import { LinePlot } from '../base/plot.ts';
import { ReadoutList } from '../base/readoutList.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import {
  appendBatches,
  summarize,
  type ChannelEstimate,
  type SlabBatches,
  type SlabRun,
} from '../../subsurface/slabKernel.ts';
import { findMaterial } from '../../subsurface/materials.ts';
import { DIPOLE_PROFILE } from './schema.ts';
import { CPU_DISC_SIZE, curvesCpu, monteCarloCpu, paintDiscCpu } from './cpuBackend.ts';
import { DipoleProfileGpu } from './gpuBackend.ts';
import {
  CHANNEL_NAMES,
  GRID_COUNT,
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

/** Side of the disc picture on the GPU (pixels). */
const DISC_SIZE = 320;
/** A progressive step aims at this much GPU time, so the page stays responsive. */
const STEP_BUDGET_MS = 400;

const READOUT_ROWS = [
  ['mc-photons', 'Monte Carlo photons'],
  ['mc-time', 'Monte Carlo time'],
  ['mc-se', 'Monte Carlo SE of Rd (R · G · B)'],
  ['dipole-error', 'Dipole − MC (R · G · B)'],
  ['better-error', 'Better dipole − MC'],
  ['collisions', 'Collisions per photon'],
  ['capped', 'Walks stopped by the cap'],
  ['curves-time', 'Diffusion profiles time'],
] as const;

const MODEL_ROWS = [
  ['dipole', 'Dipole'],
  ['better', 'Better dipole'],
  ['burley', 'Christensen–Burley'],
  ['mc', 'Monte Carlo ± SE'],
] as const;

function preset(name: string): Preset {
  const m = findMaterial(name)!;
  return { label: m.label, values: { material: name, ...materialValues(name)! } };
}

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

const signed = (x: number, digits = 2): string =>
  `${x >= 0 ? '+' : '−'}${formatNumber(Math.abs(x), digits)}`;
/** A photon count exactly, with thin spaces between groups of three digits (65 536). */
const count = (n: number): string => Math.round(n).toLocaleString('en-US').replace(/,/g, '\u2009');
const percent = (x: number): string =>
  `${x >= 0 ? '+' : '−'}${formatNumber(Math.abs(100 * x), 2)}%`;

export class DipoleProfileElement extends WidgetElement {
  protected readonly entry = DIPOLE_PROFILE;
  protected override presets: readonly Preset[] = [
    preset('skin1'),
    preset('marble'),
    preset('ketchup'),
    preset('wholemilk'),
    preset('skin2'),
    preset('apple'),
    preset('chicken1'),
  ];

  private discCanvas: HTMLCanvasElement | null = null;
  private plot: ProfilePlot | null = null;
  private errorPlot: LinePlot | null = null;
  private errorHint: HTMLElement | null = null;
  private readouts: ReadoutList | null = null;
  private readonly totalCells = new Map<string, HTMLElement>();
  private moreButton: HTMLButtonElement | null = null;
  private cancelButton: HTMLButtonElement | null = null;
  private progress: HTMLProgressElement | null = null;
  private status: HTMLElement | null = null;
  private curves: ProfileCurves | null = null;
  private curvesCost = { milliseconds: 0, how: '' };
  private mc: MonteCarloState = emptyMonteCarlo('');
  /** Bumped to stop a progressive run (Cancel, a new medium, a lost device). */
  private mcToken = 0;
  private running = false;
  private readonly backends = new BackendChooser<DipoleProfileGpu>(
    (gpu) => {
      if (!this.discCanvas) throw new Error('no canvas');
      return new DipoleProfileGpu(gpu, this.discCanvas);
    },
    (reason) => this.fallBackToCpu(reason),
  );

  protected buildStage(stage: HTMLElement): void {
    const plotArea = document.createElement('div');
    plotArea.className = 'sb-plot sb-dp-profile';
    plotArea.setAttribute('role', 'img');
    plotArea.setAttribute(
      'aria-label',
      'Log–log plot of the diffuse reflectance profile Rd(r) per colour channel: dipole, better dipole, Christensen–Burley and Monte Carlo with error bars',
    );
    stage.append(plotArea, profileLegend());
    this.plot = new ProfilePlot(plotArea);

    const row = document.createElement('div');
    row.className = 'sb-dp-row';
    const discFigure = document.createElement('figure');
    discFigure.className = 'sb-dp-disc';
    this.discCanvas = this.createCanvas();
    const caption = document.createElement('figcaption');
    caption.textContent =
      'The material seen from above, lit by a thin beam at the centre (classic dipole, exposure tone curve).';
    discFigure.append(this.discCanvas, caption);

    const errorArea = document.createElement('div');
    errorArea.className = 'sb-dp-errors';
    this.errorHint = document.createElement('p');
    this.errorHint.className = 'sb-sweep-hint';
    this.errorHint.textContent =
      'Relative error of the total Rd (mean of R, G, B) against the Monte Carlo’s time: the Monte Carlo’s standard error falls as t^−½, while each model’s difference from it levels off at the model’s own error.';
    const errorPlotArea = document.createElement('div');
    errorPlotArea.className = 'sb-plot';
    errorPlotArea.setAttribute('role', 'img');
    errorPlotArea.setAttribute(
      'aria-label',
      'Log plot of the Monte Carlo’s relative standard error and of the dipole models’ relative differences from the Monte Carlo against Monte Carlo time',
    );
    errorArea.append(this.errorHint, errorPlotArea);
    this.errorPlot = new LinePlot(errorPlotArea, {
      xLabel: 'log₁₀ Monte Carlo time (ms)',
      yLabel: 'error of total Rd (%)',
      yLog: true,
      height: 200,
    });
    row.append(discFigure, errorArea);
    stage.appendChild(row);

    const controls = document.createElement('div');
    controls.className = 'sb-sweep sb-dp-mc';
    this.moreButton = document.createElement('button');
    this.moreButton.type = 'button';
    this.moreButton.className = 'sb-button';
    this.moreButton.textContent = 'More photons';
    this.moreButton.addEventListener('click', () => void this.runMore());
    this.cancelButton = document.createElement('button');
    this.cancelButton.type = 'button';
    this.cancelButton.className = 'sb-button';
    this.cancelButton.textContent = 'Cancel';
    this.cancelButton.disabled = true;
    this.cancelButton.addEventListener('click', () => this.cancelRun('cancelled'));
    this.progress = document.createElement('progress');
    this.progress.max = 1;
    this.progress.value = 0;
    this.progress.setAttribute('aria-label', 'Monte Carlo progress');
    this.status = document.createElement('span');
    this.status.className = 'sb-dp-status';
    this.status.setAttribute('role', 'status');
    controls.append(this.moreButton, this.cancelButton, this.progress, this.status);
    stage.appendChild(controls);
  }

  private createCanvas(): HTMLCanvasElement {
    const canvas = document.createElement('canvas');
    canvas.className = 'sb-canvas';
    canvas.setAttribute('role', 'img');
    canvas.setAttribute('aria-label', 'Disc of the material lit by a thin beam at its centre');
    canvas.width = DISC_SIZE;
    canvas.height = DISC_SIZE;
    return canvas;
  }

  protected buildReadout(readout: HTMLElement): void {
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
        this.totalCells.set(`${key}-${channel}`, td);
      });
      body.appendChild(tr);
    }
    table.append(caption, head, body);
    readout.appendChild(table);
    this.readouts = new ReadoutList(readout, READOUT_ROWS);
  }

  /** Editing a coefficient by hand leaves the preset; choosing a preset fills in its coefficients. */
  protected override setValue(name: string, raw: string): void {
    if (name === 'material') {
      super.setValue(name, raw);
      const values = materialValues(String(this.values['material']));
      if (values)
        for (const [key, value] of Object.entries(values)) super.setValue(key, String(value));
      return;
    }
    if (
      (MATERIAL_PARAMETERS as readonly string[]).includes(name) &&
      this.values['material'] !== 'manual'
    )
      super.setValue('material', 'manual');
    super.setValue(name, raw);
  }

  /** A link that names a preset but not its coefficients shows the preset's numbers in the controls. */
  private syncMaterialControls(): void {
    const values = materialValues(String(this.values['material']));
    if (!values) return;
    for (const [key, value] of Object.entries(values))
      if (this.values[key] !== value) super.setValue(key, String(value));
  }

  private fallBackToCpu(reason: string): void {
    this.cancelRun('stopped: the GPU was lost');
    if (this.discCanvas) {
      const fresh = this.createCanvas();
      this.discCanvas.replaceWith(fresh);
      this.discCanvas = fresh;
    }
    this.mc = emptyMonteCarlo('');
    this.backends.useCpu(reason);
    this.scheduleRender();
  }

  protected async render(): Promise<void> {
    this.syncMaterialControls();
    const inputs = inputsFrom(this.values);
    const backend = await this.backends.choose();
    let frameMs: number;
    let how: string;
    try {
      if (backend.kind === 'gpu') {
        const result = await backend.renderer.curves(inputs);
        await backend.renderer.drawDisc(inputs);
        this.curves = result.curves;
        frameMs = result.milliseconds;
        how = timingLabel(result.timing);
      } else {
        const result = curvesCpu(inputs);
        if (this.discCanvas) paintDiscCpu(this.discCanvas, inputs);
        this.curves = result.curves;
        frameMs = result.milliseconds;
        how = timingLabel('cpu');
      }
    } catch (error) {
      if (backend.kind === 'cpu') throw error;
      this.fallBackToCpu(gpuFailureReason(error));
      return;
    }
    this.curvesCost = { milliseconds: frameMs, how };
    if (backend.kind === 'gpu') this.clearNotice('backend');
    else
      this.showCpuFallbackNotice(
        backend.reason,
        `Showing the float64 CPU twins: the same profiles and Monte Carlo walks, the disc at ${CPU_DISC_SIZE}×${CPU_DISC_SIZE} pixels.`,
      );
    const key = monteCarloKey(inputs);
    if (this.mc.key !== key) {
      this.cancelRun('');
      this.mc = emptyMonteCarlo(key);
      const step = await this.monteCarloStep(
        backend,
        inputs,
        firstRunPhotons(inputs),
        this.mcToken,
      );
      if (step) frameMs += step.milliseconds;
    }
    this.recordFrameCost(frameMs, how);
    this.show(inputs, backend);
  }

  /**
   * One Monte Carlo run of `photons` per channel, appended to the accumulation if the
   * medium is still the same and the run was not cancelled. Returns its cost.
   */
  private async monteCarloStep(
    backend: Backend<DipoleProfileGpu>,
    inputs: ProfileInputs,
    photons: number,
    token: number,
  ): Promise<{ milliseconds: number } | null> {
    const key = this.mc.key;
    const run = slabRunFor(inputs, photons, this.mc.nextOffset);
    let batches: SlabBatches;
    let milliseconds: number;
    let timing: GpuTiming | 'cpu';
    if (backend.kind === 'gpu') {
      const result = await backend.renderer.monteCarlo(run);
      batches = result.batches;
      milliseconds = result.gpuMs ?? result.wallMs;
      timing = result.gpuMs === null ? 'gpu-wall' : 'gpu-timestamp';
    } else {
      const result = await monteCarloCpu(run, () => token !== this.mcToken);
      batches = result.batches;
      milliseconds = result.milliseconds;
      timing = 'cpu';
    }
    if (this.mc.key !== key) return null;
    const done = batches.channels[0]?.walks.length ?? 0;
    if (done === 0) return null;
    this.mc.template ??= run;
    this.mc.batches = this.mc.batches ? appendBatches(this.mc.batches, batches) : batches;
    this.mc.nextOffset += done * 64;
    this.mc.photons += batches.channels[0]!.walks.reduce((a, b) => a + b, 0);
    this.mc.milliseconds += milliseconds;
    this.mc.timing = timingLabel(timing);
    const estimates = this.estimates();
    if (estimates && this.curves) {
      // Relative errors in per cent, averaged over the channels.
      const relative = (totals: number[]): number =>
        100 * meanAbsolute(estimates.map((e, c) => compareTotal(totals[c]!, e).relative));
      this.mc.history.push({
        milliseconds: this.mc.milliseconds,
        se:
          100 *
          meanAbsolute(
            estimates.map(
              (e) => e.diffuseReflectance.se / Math.max(e.diffuseReflectance.mean, 1e-12),
            ),
          ),
        dipole: relative(this.curves.dipoleTotal),
        better: relative(this.curves.betterTotal),
      });
    }
    return { milliseconds };
  }

  private estimates(): ChannelEstimate[] | null {
    if (!this.mc.batches || !this.mc.template) return null;
    return summarize(this.mc.template, this.mc.batches);
  }

  /** "More photons": doubles the Monte Carlo (steps of ≈ STEP_BUDGET_MS) up to the target. */
  private async runMore(): Promise<void> {
    if (this.running) return;
    const token = ++this.mcToken;
    const inputs = inputsFrom(this.values);
    const backend = await this.backends.choose();
    if (this.mc.key !== monteCarloKey(inputs)) return;
    const target = inputs.photonTarget;
    const start = this.mc.photons;
    this.setRunning(true);
    try {
      while (token === this.mcToken && this.mc.photons < target) {
        const perPhoton = this.mc.milliseconds / Math.max(this.mc.photons, 1);
        const affordable = perPhoton > 0 ? STEP_BUDGET_MS / perPhoton : this.mc.photons;
        const photons = Math.max(
          256,
          Math.min(this.mc.photons, target - this.mc.photons, affordable),
        );
        this.setStatus(`${count(this.mc.photons)} of ${count(target)} photons per channel…`);
        const step = await this.monteCarloStep(backend, inputs, photons, token);
        if (!step) break;
        if (this.progress)
          this.progress.value = Math.min(
            (this.mc.photons - start) / Math.max(target - start, 1),
            1,
          );
        this.show(inputs, backend);
        await new Promise((resolve) => requestAnimationFrame(resolve));
      }
      if (token === this.mcToken)
        this.setStatus(
          `Done: ${count(this.mc.photons)} photons per channel in ${formatMilliseconds(this.mc.milliseconds)}.`,
        );
    } catch (error) {
      this.setStatus(`Failed: ${error instanceof Error ? error.message : String(error)}`);
    } finally {
      if (token === this.mcToken) this.setRunning(false);
    }
  }

  private cancelRun(message: string): void {
    this.mcToken += 1;
    if (this.running) {
      this.setRunning(false);
      if (message)
        this.setStatus(`Monte Carlo ${message} at ${count(this.mc.photons)} photons per channel.`);
    }
  }

  private setRunning(on: boolean): void {
    this.running = on;
    if (this.moreButton) this.moreButton.disabled = on;
    if (this.cancelButton) this.cancelButton.disabled = !on;
    if (this.progress && on) this.progress.value = 0;
  }

  private setStatus(text: string): void {
    if (this.status) this.status.textContent = text;
  }

  private setTotal(row: string, channel: number, text: string): void {
    const cell = this.totalCells.get(`${row}-${CHANNEL_NAMES[channel]}`);
    if (cell) cell.textContent = text;
  }

  /** Plot, totals, readouts and the cost line from the current curves and Monte Carlo. */
  private show(inputs: ProfileInputs, backend: Backend<DipoleProfileGpu>): void {
    const curves = this.curves;
    if (!curves) return;
    const estimates = this.estimates();
    this.plot?.update({ curves, monteCarlo: estimates?.map((e) => e.profile) ?? null });
    const set = (key: string, text: string, state?: 'ok' | 'bad'): void =>
      this.readouts?.set(key, text, state);
    // Totals to five decimals: the columns line up, and ketchup's 0.00183 keeps three digits.
    const total = (x: number): string => x.toFixed(5);
    for (let c = 0; c < 3; c++) {
      this.setTotal('dipole', c, total(curves.dipoleTotal[c]!));
      this.setTotal('better', c, total(curves.betterTotal[c]!));
      this.setTotal('burley', c, total(curves.dipoleTotal[c]!));
      const e = estimates?.[c];
      this.setTotal(
        'mc',
        c,
        e
          ? `${total(e.diffuseReflectance.mean)} ± ${formatNumber(e.diffuseReflectance.se, 2)}`
          : '…',
      );
    }
    if (estimates) {
      const joined = (f: (e: ChannelEstimate, c: number) => string): string =>
        estimates.map(f).join(' · ');
      const batches = estimates[0]!.batches;
      set('mc-photons', `${count(this.mc.photons)} per channel (${batches} batches)`);
      set('mc-time', `${formatMilliseconds(this.mc.milliseconds)} (${this.mc.timing})`);
      set(
        'mc-se',
        joined((e) => formatNumber(e.diffuseReflectance.se, 2)),
      );
      const modelError = (totals: number[]): string =>
        joined((e, c) => {
          const comparison = compareTotal(totals[c]!, e);
          return `${percent(comparison.relative)} (${signed(comparison.z, 2)}σ)`;
        });
      set('dipole-error', modelError(curves.dipoleTotal));
      set('better-error', modelError(curves.betterTotal));
      set(
        'collisions',
        joined((e) => formatNumber(e.collisionsPerPhoton, 3)),
      );
      const capped = estimates.reduce((sum, e) => sum + e.capped, 0);
      const cappedWeight = Math.max(...estimates.map((e) => e.cappedWeight));
      set(
        'capped',
        capped === 0
          ? `0 (cap ${MC_MAX_COLLISIONS} flights)`
          : `${capped}, holding up to ${formatNumber(100 * cappedWeight, 2)}% of the light`,
        capped === 0 ? 'ok' : 'bad',
      );
      if (capped > 0)
        this.showNotice(
          'capped',
          'warning',
          `${capped} Monte Carlo walks reached the cap of ${MC_MAX_COLLISIONS} flights with light still inside (up to ${formatNumber(100 * cappedWeight, 2)}% of the incident light per channel): the Monte Carlo Rd is low by about that much. Nearly conservative media (σa → 0) have very long walks.`,
        );
      else this.clearNotice('capped');
    }
    set(
      'curves-time',
      `${formatMilliseconds(this.curvesCost.milliseconds)} (${this.curvesCost.how})`,
    );
    const history = this.mc.history;
    if (history.length > 0) {
      this.errorPlot?.update(
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
    const where =
      backend.kind === 'gpu'
        ? `WebGPU (${backend.gpu.adapterDescription})`
        : 'CPU fallback (float64 twins)';
    const cost = this.readouts?.cost;
    if (cost)
      cost.textContent = `${where}: 3 models × 3 channels × ${GRID_COUNT} radii in ${formatMilliseconds(this.curvesCost.milliseconds)}; Monte Carlo ${count(this.mc.photons)} photons per channel in ${formatMilliseconds(this.mc.milliseconds)} (${this.mc.timing || '—'}), half-space, ${inputs.g > 0 ? `HG g = ${inputs.g}` : 'isotropic scattering'}, η = ${inputs.eta}.`;
    if (this.discCanvas)
      this.discCanvas.setAttribute(
        'aria-label',
        `Disc of ${findMaterial(inputs.material)?.label ?? 'the material'} lit by a thin beam: total Rd (dipole) ${curves.dipoleTotal.map((v) => formatNumber(v, 3)).join(', ')} in R, G, B`,
      );
  }
}

export function defineDipoleProfile(): void {
  if (!customElements.get('sb-dipole-profile'))
    customElements.define('sb-dipole-profile', DipoleProfileElement);
}
