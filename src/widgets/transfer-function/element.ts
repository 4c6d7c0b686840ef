// <sb-transfer-function>: direct volume rendering of a CT head phantom (chapter 7).
// The GPU ray casts the volume with emission–absorption compositing through a
// transfer function edited over the data's histogram; the camera orbits by drag or
// arrow keys. Next to the picture: the GPU time per frame, the error against a
// fine-step reference (computed once per transfer function and view, band by band,
// with progress, cancellable), the steps early ray termination takes and saves,
// its bias bound, and a cancellable sweep of RMSE against time over the step size.
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import { BackendChooser, type Backend, gpuFailureReason } from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import {
  gradientCss,
  imageCanvas,
  imageFigure,
  imagePanel,
  niceScale,
} from '../base/imagePanel.ts';
import { ReadoutList } from '../base/readoutList.ts';
import { SweepControls, logLogSlope } from '../base/sweep.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import {
  CpuRenderer,
  GpuRenderer,
  paintImage,
  renderFrame,
  type FrameRenderer,
} from './cpuBackend.ts';
import { TransferEditor } from './editor.ts';
import { VolumeRendererGpu } from './gpuBackend.ts';
import {
  COLOUR_MAPS,
  colourAt,
  colourDomain,
  CPU_SIZE,
  errorColour,
  IMAGE_SIZE,
  inputsFrom,
  maxError,
  phantomGrid,
  pixelColour,
  pixelErrors,
  presetValues,
  REFERENCE_BAND_ROWS,
  REFERENCE_EPSILON,
  REFERENCE_STEP_VOXELS,
  rmse,
  sceneKey,
  SWEEP_SAMPLES_PER_VOXEL,
  terminationBiasBound,
  thresholdOf,
  TRANSFER_PRESETS,
  VOXEL,
  type FrameInputs,
  type VolumeImage,
} from './model.ts';
import { histogram, phantomVolume } from './phantom.ts';
import { CONTROL_POINTS, TRANSFER_FUNCTION } from './schema.ts';

const READOUT_ROWS = [
  ['time', 'Time per frame'],
  ['rmse', 'RMSE against the fine-step reference'],
  ['max-error', 'Largest pixel error'],
  ['steps', 'Steps taken / without early termination'],
  ['saving', 'Early termination saves'],
  ['bias', 'Termination bias bound ε·L_max'],
  ['slope', 'Sweep: fitted order, RMSE ∝ Δs^q'],
] as const;

/** Degrees the camera turns per CSS pixel of drag, and per arrow key press. */
const DRAG_DEGREES_PER_PIXEL = 0.5;
const KEY_DEGREES = 5;
/** Quiet time after a change before the reference starts (ms). */
const REFERENCE_DELAY_MS = 350;

const wrapDegrees = (a: number): number => ((((a + 180) % 360) + 360) % 360) - 180;
const clampElevation = (e: number): number => Math.min(Math.max(e, -85), 85);

function formatCount(n: number): string {
  if (n >= 1e6) return `${formatNumber(n / 1e6, 3)} M`;
  if (n >= 1e4) return `${formatNumber(n / 1e3, 3)} k`;
  return String(n);
}

function formatStep(voxels: number): string {
  return `${formatNumber(voxels, 4)} voxel${voxels === 1 ? '' : 's'} (${formatNumber(voxels * VOXEL * 1000, 3)} mm)`;
}

interface ReferenceJob {
  key: string;
  cancelled: boolean;
  promise: Promise<VolumeImage | null>;
}

interface Frame {
  inputs: FrameInputs;
  key: string;
  image: VolumeImage;
  milliseconds: number;
  how: string;
  renderer: FrameRenderer;
}

export class TransferFunctionElement extends WidgetElement {
  protected readonly entry = TRANSFER_FUNCTION;
  protected override presets: readonly Preset[] = TRANSFER_PRESETS.map((preset) => ({
    label: preset.label,
    values: presetValues(preset),
  }));

  private volumeCanvas: HTMLCanvasElement | null = null;
  private errorCanvas: HTMLCanvasElement | null = null;
  private errorTop: HTMLElement | null = null;
  private rightCaption: HTMLElement | null = null;
  private referenceProgress: HTMLProgressElement | null = null;
  private referenceStatus: HTMLElement | null = null;
  private referenceButton: HTMLButtonElement | null = null;
  private editor: TransferEditor | null = null;
  private readouts: ReadoutList | null = null;
  private sweep: SweepControls | null = null;

  private lastFrame: Frame | null = null;
  private reference: { key: string; image: VolumeImage } | null = null;
  private referenceJob: ReferenceJob | null = null;
  private referenceTimer: ReturnType<typeof setTimeout> | null = null;
  /** Time and steps with the other termination setting, per scene, step and ε. */
  private readonly otherMode = new Map<
    string,
    { current: number; other: number; otherSteps: number }
  >();
  private otherModeRunning = '';

  private readonly backends = new BackendChooser(
    (gpu) =>
      VolumeRendererGpu.create(gpu.device, STATIC_KERNELS, phantomGrid()).then(
        (renderer) => new GpuRenderer(renderer),
      ),
    () => {
      this.sweep?.cancel('stopped: the GPU was lost');
      this.dropReference();
      this.scheduleRender();
    },
  );

  /** Settings a preset keeps: the presets are transfer functions, not views. */
  private static readonly KEPT_BY_PRESETS = [
    'step',
    'termination',
    'epsilon',
    'panel',
    'azimuth',
    'elevation',
  ] as const;

  /** A preset replaces the transfer function and keeps the camera, the step and the rest. */
  protected override applyPreset(index: number): void {
    const kept = TransferFunctionElement.KEPT_BY_PRESETS.map(
      (name) => [name, this.values[name]] as const,
    );
    super.applyPreset(index);
    for (const [name, value] of kept)
      if (value !== undefined && this.values[name] !== value) this.setValue(name, String(value));
  }

  protected buildStage(stage: HTMLElement): void {
    this.volumeCanvas = imageCanvas(
      'Volume rendering of the CT head phantom. Drag, or use the arrow keys, to orbit the camera.',
      IMAGE_SIZE,
      IMAGE_SIZE,
    );
    this.volumeCanvas.tabIndex = 0;
    this.volumeCanvas.classList.add('sb-tf-volume');
    this.errorCanvas = imageCanvas(
      'Error image: |image − fine-step reference|, largest channel',
      IMAGE_SIZE,
      IMAGE_SIZE,
    );
    const error = imagePanel(this.errorCanvas, 'Error |L − L_ref| against Δs = ⅛ voxel', {
      gradient: gradientCss((x) => errorColour(x, 1)),
      low: '0',
      top: { readout: 'error-scale' },
    });
    this.errorTop = error.top;
    this.rightCaption = error.panel.querySelector('figcaption');
    const figure = imageFigure(
      imagePanel(this.volumeCanvas, 'Emission–absorption rendering (drag or ←↑→↓ to orbit)').panel,
      error.panel,
    );
    figure.classList.add('sb-tf-images');
    stage.appendChild(figure);
    this.attachOrbit(this.volumeCanvas);

    const status = document.createElement('div');
    status.className = 'sb-tf-reference';
    this.referenceProgress = document.createElement('progress');
    this.referenceProgress.max = 1;
    this.referenceProgress.value = 0;
    this.referenceProgress.setAttribute('aria-label', 'Reference progress');
    this.referenceStatus = document.createElement('span');
    this.referenceStatus.setAttribute('aria-live', 'polite');
    this.referenceStatus.textContent = 'Reference: not computed yet.';
    this.referenceButton = document.createElement('button');
    this.referenceButton.type = 'button';
    this.referenceButton.className = 'sb-button';
    this.referenceButton.textContent = 'Cancel reference';
    this.referenceButton.addEventListener('click', () => this.toggleReference());
    status.append(this.referenceProgress, this.referenceStatus, this.referenceButton);
    stage.appendChild(status);

    const editorSection = document.createElement('div');
    editorSection.className = 'sb-tf-editor';
    const header = document.createElement('div');
    header.className = 'sb-tf-editor-header';
    const title = document.createElement('p');
    title.className = 'sb-tf-editor-title';
    title.textContent =
      'Transfer function: opacity over the histogram of the data (drag a point, or Tab to it and use the arrow keys)';
    const presets = document.createElement('div');
    presets.className = 'sb-tf-presets';
    presets.setAttribute('role', 'group');
    presets.setAttribute('aria-label', 'Transfer-function presets');
    TRANSFER_PRESETS.forEach((preset, index) => {
      const button = document.createElement('button');
      button.type = 'button';
      button.className = 'sb-button';
      button.textContent = `${index + 1} ${preset.label}`;
      button.addEventListener('click', () => this.applyPreset(index));
      presets.appendChild(button);
    });
    header.append(title, presets);
    const plot = document.createElement('div');
    plot.className = 'sb-plot sb-tf-plot';
    plot.setAttribute('role', 'group');
    plot.setAttribute(
      'aria-label',
      'Histogram of the phantom in Hounsfield units (log counts) with the opacity curve and its control points',
    );
    editorSection.append(header, plot);
    stage.appendChild(editorSection);
    const volume = phantomVolume();
    this.editor = new TransferEditor(plot, histogram(volume.hounsfield), {
      move: (index, hu, opacity) => {
        this.setValue(`hu-${index}`, String(hu));
        this.setValue(`opacity-${index}`, String(opacity));
      },
    });

    this.sweep = new SweepControls(
      stage,
      this,
      {
        name: '1/Δs',
        buttonText: 'Run sweep Δs = 4 … ½ voxel',
        hint: 'Run the sweep to plot the RMSE against the time per frame for Δs = 4, 2, 1 and ½ voxel and fit the order of convergence.',
        color: '#d9822b',
        statusClass: 'sb-tf-sweep-status',
        points: SWEEP_SAMPLES_PER_VOXEL,
      },
      () => void this.runSweep(),
    );
  }

  protected buildReadout(readout: HTMLElement): void {
    this.readouts = new ReadoutList(readout, READOUT_ROWS);
    this.set('slope', 'run the sweep');
    this.groupPointControls();
  }

  /** Moves the twelve control-point inputs the shell generated into one collapsible group. */
  private groupPointControls(): void {
    const form = this.querySelector<HTMLFormElement>('.sb-controls');
    if (!form) return;
    const details = document.createElement('details');
    details.className = 'sb-tf-points';
    const summary = document.createElement('summary');
    summary.textContent = 'Control points as numbers (HU, opacity per voxel)';
    const grid = document.createElement('div');
    grid.className = 'sb-tf-point-grid';
    for (let k = 1; k <= CONTROL_POINTS; k++) {
      for (const name of [`hu-${k}`, `opacity-${k}`]) {
        const control = form.querySelector(`[name="${name}"]`)?.closest('.sb-control');
        if (control) grid.appendChild(control);
      }
    }
    details.append(summary, grid);
    const hint = form.querySelector('.sb-preset-hint');
    form.insertBefore(details, hint);
  }

  private set(key: string, text: string, state?: 'ok' | 'bad'): void {
    this.readouts?.set(key, text, state);
  }

  private attachOrbit(canvas: HTMLCanvasElement): void {
    let drag: { x: number; y: number; azimuth: number; elevation: number } | null = null;
    canvas.addEventListener('pointerdown', (event) => {
      canvas.setPointerCapture(event.pointerId);
      drag = {
        x: event.clientX,
        y: event.clientY,
        azimuth: Number(this.values['azimuth']),
        elevation: Number(this.values['elevation']),
      };
      event.preventDefault();
    });
    canvas.addEventListener('pointermove', (event) => {
      if (!drag || !canvas.hasPointerCapture(event.pointerId)) return;
      const azimuth = wrapDegrees(drag.azimuth - (event.clientX - drag.x) * DRAG_DEGREES_PER_PIXEL);
      const elevation = clampElevation(
        drag.elevation + (event.clientY - drag.y) * DRAG_DEGREES_PER_PIXEL,
      );
      this.orbitTo(azimuth, elevation);
    });
    const end = (): void => {
      drag = null;
    };
    canvas.addEventListener('pointerup', end);
    canvas.addEventListener('pointercancel', end);
    canvas.addEventListener('keydown', (event) => {
      const turns: Record<string, [number, number]> = {
        ArrowLeft: [KEY_DEGREES, 0],
        ArrowRight: [-KEY_DEGREES, 0],
        ArrowUp: [0, KEY_DEGREES],
        ArrowDown: [0, -KEY_DEGREES],
      };
      const turn = turns[event.key];
      if (!turn) return;
      event.preventDefault();
      const scale = event.shiftKey ? 3 : 1;
      this.orbitTo(
        wrapDegrees(Number(this.values['azimuth']) + turn[0] * scale),
        clampElevation(Number(this.values['elevation']) + turn[1] * scale),
      );
    });
  }

  private orbitTo(azimuth: number, elevation: number): void {
    const round = (x: number): string => String(Math.round(x));
    if (round(azimuth) !== String(this.values['azimuth'])) this.setValue('azimuth', round(azimuth));
    if (round(elevation) !== String(this.values['elevation']))
      this.setValue('elevation', round(elevation));
  }

  private async renderer(backend: Backend<Promise<GpuRenderer>>): Promise<FrameRenderer> {
    if (backend.kind === 'gpu') return backend.renderer;
    return new CpuRenderer();
  }

  protected async render(): Promise<void> {
    const inputs = inputsFrom(this.values);
    if (inputs.reordered) {
      this.showNotice(
        'reordered',
        'warning',
        'The control points in this link were not in increasing order of value; they are used sorted.',
      );
    } else {
      this.clearNotice('reordered');
    }
    this.updateEditor(inputs);
    const backend = await this.backends.choose();
    let renderer: FrameRenderer;
    let frame: Awaited<ReturnType<typeof renderFrame>>;
    try {
      renderer = await this.renderer(backend);
      frame = await renderFrame(renderer, inputs, inputs.step, thresholdOf(inputs));
    } catch (error) {
      if (backend.kind === 'cpu') throw error;
      this.backends.useCpu(gpuFailureReason(error));
      this.sweep?.cancel('stopped: the GPU was lost');
      this.dropReference();
      this.scheduleRender();
      return;
    }
    if (backend.kind === 'gpu') {
      this.clearNotice('backend');
    } else {
      this.showCpuFallbackNotice(
        backend.reason,
        `Showing the float64 CPU twin: the same rays and marches, at ${CPU_SIZE}×${CPU_SIZE} pixels.`,
      );
    }
    const key = `${renderer.kind}|${sceneKey(inputs)}`;
    this.lastFrame = { inputs, key, renderer, ...frame };
    this.showFrame(this.lastFrame, backend);
    this.analyse(this.lastFrame);
  }

  private updateEditor(inputs: FrameInputs): void {
    const map = COLOUR_MAPS[inputs.colormap] ?? COLOUR_MAPS['tissue']!;
    const domain = colourDomain(inputs.points);
    this.editor?.update({
      points: inputs.points,
      colourAt: (v) => colourAt(map, domain, v),
    });
  }

  private showFrame(frame: Frame, backend: Backend<Promise<GpuRenderer>>): void {
    const { image, inputs } = frame;
    const pixels = image.size * image.size;
    if (this.volumeCanvas)
      paintImage(this.volumeCanvas, image.size, (i) => pixelColour(image.rgb, pixels, i));
    this.set('time', `${formatMilliseconds(frame.milliseconds)} (${frame.how})`);
    this.recordFrameCost(frame.milliseconds, frame.how);
    const share = image.plannedSteps > 0 ? image.steps / image.plannedSteps : 1;
    this.set(
      'steps',
      inputs.termination
        ? `${formatCount(image.steps)} of ${formatCount(image.plannedSteps)} (${formatNumber(100 * share, 3)}%), ${formatCount(image.terminatedRays)} rays stopped early`
        : `${formatCount(image.steps)} (every ray to its end)`,
    );
    const bound = terminationBiasBound(inputs);
    this.set(
      'bias',
      inputs.termination
        ? `≤ ${formatNumber(bound, 3)} (ε = ${formatNumber(inputs.epsilon, 3)})`
        : '0 (no termination)',
      'ok',
    );
    if (image.cappedRays > 0) {
      this.showNotice(
        'capped',
        'warning',
        `${image.cappedRays} rays needed more than 8192 steps and were marched with longer ones.`,
      );
    } else {
      this.clearNotice('capped');
    }
    const where =
      backend.kind === 'gpu'
        ? `WebGPU (${backend.gpu.adapterDescription}): ${image.size}×${image.size} rays`
        : `CPU fallback (float64 twin): ${image.size}×${image.size} rays`;
    if (this.readouts) {
      this.readouts.cost.textContent = `${where}, Δs = ${formatStep(inputs.step)}, ${formatMilliseconds(frame.milliseconds)} per frame (${frame.how}). Reference: Δs = ⅛ voxel, stopped at T < 10⁻⁶, once per transfer function and view.`;
    }
    this.volumeCanvas?.setAttribute(
      'aria-label',
      `Volume rendering of the CT head phantom, azimuth ${inputs.azimuth}°, elevation ${inputs.elevation}°, step ${formatNumber(inputs.step, 4)} voxel. Drag, or use the arrow keys, to orbit the camera.`,
    );
  }

  // ---- accuracy and savings, computed after the frame -------------------------

  private analyse(frame: Frame): void {
    if (this.reference?.key === frame.key) {
      this.showError(frame, this.reference.image);
      this.measureOtherMode(frame);
      return;
    }
    this.showError(frame, null);
    if (this.referenceJob && this.referenceJob.key !== frame.key) this.cancelReference(false);
    if (this.referenceJob?.key === frame.key) return;
    if (this.referenceTimer) clearTimeout(this.referenceTimer);
    this.setReferenceStatus('Reference: waiting for the view to settle…', 0);
    this.referenceTimer = setTimeout(() => {
      this.referenceTimer = null;
      if (this.lastFrame?.key === frame.key) void this.ensureReference(frame);
    }, REFERENCE_DELAY_MS);
  }

  /** The reference of the frame's scene: cached, running, or started now. */
  private ensureReference(frame: Frame): Promise<VolumeImage | null> {
    if (this.reference?.key === frame.key) return Promise.resolve(this.reference.image);
    if (this.referenceJob?.key === frame.key && !this.referenceJob.cancelled)
      return this.referenceJob.promise;
    if (this.referenceTimer) {
      clearTimeout(this.referenceTimer);
      this.referenceTimer = null;
    }
    const job: ReferenceJob = { key: frame.key, cancelled: false, promise: Promise.resolve(null) };
    this.referenceJob = job;
    job.promise = this.computeReference(frame, job);
    return job.promise;
  }

  private async computeReference(frame: Frame, job: ReferenceJob): Promise<VolumeImage | null> {
    const { renderer, inputs } = frame;
    const image = renderer.blank();
    const bandRows = renderer.kind === 'gpu' ? REFERENCE_BAND_ROWS : 4;
    const bands = Math.ceil(renderer.size / bandRows);
    if (this.referenceButton) this.referenceButton.textContent = 'Cancel reference';
    let milliseconds = 0;
    for (let band = 0; band < bands; band++) {
      if (job.cancelled) return null;
      this.setReferenceStatus(
        `Reference: Δs = ⅛ voxel, band ${band + 1} of ${bands}…`,
        band / bands,
      );
      this.set('rmse', `computing the reference… ${Math.round((100 * band) / bands)}%`);
      const cost = await renderer.renderInto(
        image,
        inputs,
        REFERENCE_STEP_VOXELS,
        REFERENCE_EPSILON,
        band * bandRows,
        (band + 1) * bandRows,
      );
      milliseconds += cost.milliseconds;
      // Let the page breathe between bands: input, painting and Cancel stay live.
      await new Promise((resolve) => setTimeout(resolve, 0));
    }
    if (job.cancelled) return null;
    this.reference = { key: job.key, image };
    if (this.referenceJob === job) this.referenceJob = null;
    this.setReferenceStatus(
      `Reference ready: Δs = ⅛ voxel, ${formatCount(image.steps)} steps in ${formatMilliseconds(milliseconds)}.`,
      1,
    );
    const latest = this.lastFrame;
    if (latest?.key === job.key) {
      this.showError(latest, image);
      this.measureOtherMode(latest);
    }
    return image;
  }

  private setReferenceStatus(text: string, progress: number): void {
    if (this.referenceStatus) this.referenceStatus.textContent = text;
    if (this.referenceProgress) this.referenceProgress.value = progress;
    if (this.referenceButton) {
      const running = this.referenceJob !== null && !this.referenceJob.cancelled;
      this.referenceButton.textContent = running ? 'Cancel reference' : 'Compute reference';
      this.referenceButton.disabled = this.reference?.key === this.lastFrame?.key;
    }
  }

  private cancelReference(byUser: boolean): void {
    if (this.referenceTimer) {
      clearTimeout(this.referenceTimer);
      this.referenceTimer = null;
    }
    if (this.referenceJob) this.referenceJob.cancelled = true;
    this.referenceJob = null;
    if (byUser) {
      this.sweep?.cancel('stopped: the reference was cancelled');
      this.set('rmse', 'reference cancelled');
      this.setReferenceStatus('Reference cancelled: press Compute reference to finish it.', 0);
    }
  }

  private dropReference(): void {
    this.cancelReference(false);
    this.reference = null;
    this.otherMode.clear();
  }

  private toggleReference(): void {
    if (this.referenceJob && !this.referenceJob.cancelled) this.cancelReference(true);
    else if (this.lastFrame) void this.ensureReference(this.lastFrame);
  }

  /** The right-hand image in its "steps taken per ray" mode, on a linear scale. */
  private showSteps(image: VolumeImage): void {
    let most = 0;
    for (const n of image.plannedPerPixel) most = Math.max(most, n);
    const scale = niceScale(most);
    if (this.errorCanvas)
      paintImage(this.errorCanvas, image.size, (i) =>
        errorColour((image.stepsPerPixel[i]! / scale) ** 2, 1),
      );
    if (this.errorTop) this.errorTop.textContent = String(scale);
    if (this.rightCaption)
      this.rightCaption.textContent = 'Steps taken per ray (black: the ray misses the volume)';
  }

  private showError(frame: Frame, reference: VolumeImage | null): void {
    const { image } = frame;
    const pixels = image.size * image.size;
    const stepsMode = frame.inputs.panel === 'steps';
    if (stepsMode) this.showSteps(image);
    else if (this.rightCaption)
      this.rightCaption.textContent = 'Error |L − L_ref| against Δs = ⅛ voxel';
    if (!reference) {
      if (!stepsMode) {
        if (this.errorCanvas) paintImage(this.errorCanvas, image.size, () => [4, 6, 16]);
        if (this.errorTop) this.errorTop.textContent = '…';
      }
      this.set('max-error', 'waiting for the reference');
      if (!this.referenceJob) this.set('rmse', 'waiting for the reference');
      return;
    }
    const errors = pixelErrors(image.rgb, reference.rgb, pixels);
    const largest = maxError(image.rgb, reference.rgb);
    const scale = niceScale(largest);
    if (!stepsMode) {
      if (this.errorCanvas)
        paintImage(this.errorCanvas, image.size, (i) => errorColour(errors[i]!, scale));
      if (this.errorTop) this.errorTop.textContent = formatNumber(scale, 2);
    }
    this.set('rmse', formatNumber(rmse(image.rgb, reference.rgb), 3));
    this.set('max-error', formatNumber(largest, 3));
    this.setReferenceStatus(this.referenceStatus?.textContent ?? '', 1);
  }

  /**
   * Measures the frame's cost with and without early termination, for the saving
   * readout: the other setting twice and the current one once more, alternating, and
   * the faster of each pair. On a CPU shared with other work (SwiftShader) single
   * timings vary by tens of percent; the best of two is steadier.
   */
  private measureOtherMode(frame: Frame): void {
    const { inputs } = frame;
    const key = `${frame.key}|${inputs.step}|${inputs.epsilon}`;
    const measured = this.otherMode.get(key);
    if (measured) {
      this.showSaving(frame, measured);
      return;
    }
    this.set('saving', 'measuring…');
    if (this.otherModeRunning === key) return;
    this.otherModeRunning = key;
    const otherInputs = { ...inputs, termination: !inputs.termination };
    const run = (which: FrameInputs) =>
      renderFrame(frame.renderer, which, which.step, thresholdOf(which));
    void (async () => {
      const first = await run(otherInputs);
      const again = await run(inputs);
      const second = await run(otherInputs);
      const result = {
        current: Math.min(frame.milliseconds, again.milliseconds),
        other: Math.min(first.milliseconds, second.milliseconds),
        otherSteps: first.image.steps,
      };
      if (this.otherMode.size > 64) this.otherMode.clear();
      this.otherMode.set(key, result);
      if (this.lastFrame === frame) this.showSaving(frame, result);
    })()
      .catch(() => this.set('saving', 'not measured (the render failed)', 'bad'))
      .finally(() => {
        if (this.otherModeRunning === key) this.otherModeRunning = '';
      });
  }

  private showSaving(
    frame: Frame,
    measured: { current: number; other: number; otherSteps: number },
  ): void {
    const on = frame.inputs.termination
      ? { ms: measured.current, steps: frame.image.steps }
      : { ms: measured.other, steps: measured.otherSteps };
    const off = frame.inputs.termination
      ? { ms: measured.other, steps: measured.otherSteps }
      : { ms: measured.current, steps: frame.image.steps };
    const stepSaving = off.steps > 0 ? 1 - on.steps / off.steps : 0;
    const timeSaving = off.ms > 0 ? 1 - on.ms / off.ms : 0;
    this.set(
      'saving',
      `${formatNumber(100 * stepSaving, 3)}% of the steps; ${formatMilliseconds(on.ms)} with, ${formatMilliseconds(off.ms)} without (${formatNumber(100 * timeSaving, 2)}% of the time, best of 2 frames each)`,
    );
  }

  // ---- the sweep over the step size --------------------------------------------

  private runSweep(): Promise<void> {
    return this.sweep!.run(async () => {
      const inputs = inputsFrom(this.values);
      const backend = await this.backends.choose();
      const renderer = await this.renderer(backend);
      const key = `${renderer.kind}|${sceneKey(inputs)}`;
      this.set('slope', 'sweeping…');
      const label = `${inputs.termination ? `early termination ε = ${formatNumber(inputs.epsilon, 3)}` : 'no early termination'}`;
      return {
        label,
        measure: async (samplesPerVoxel) => {
          const reference = await this.ensureReference({
            inputs,
            key,
            renderer,
            image: renderer.blank(),
            milliseconds: 0,
            how: '',
          });
          if (!reference) throw new Error('the reference was cancelled');
          const frame = await renderFrame(
            renderer,
            inputs,
            1 / samplesPerVoxel,
            thresholdOf(inputs),
          );
          return { rmse: rmse(frame.image.rgb, reference.rgb), milliseconds: frame.milliseconds };
        },
        finish: (points) => {
          const slope = logLogSlope(
            points.map((p) => p.n),
            points.map((p) => p.rmse),
          );
          this.set(
            'slope',
            slope === null
              ? 'no fit'
              : `q = ${formatNumber(-slope, 3)} (RMSE ∝ Δs^${formatNumber(-slope, 3)})`,
          );
          return `${label}, ${renderer.kind === 'gpu' ? 'GPU' : 'CPU fallback'}`;
        },
        failed: () => this.set('slope', 'failed', 'bad'),
      };
    });
  }
}

export function defineTransferFunction(): void {
  if (!customElements.get('sb-transfer-function'))
    customElements.define('sb-transfer-function', TransferFunctionElement);
}
