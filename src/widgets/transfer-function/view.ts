// The drawing of <sb-transfer-function>: the volume image (the GPU kernel read back,
// or the float64 twin at CPU_SIZE², painted into 2D canvases) with its camera orbit,
// the error or steps image, the fine-step reference (band by band, cancellable), the
// saving of early termination measured after the frame, the transfer-function editor
// with its preset buttons, and the sweep over the step size. Readouts, backends and
// fallback: widget.ts and the base element.
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import type { Backend } from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import {
  gradientCss,
  imageCanvas,
  imageFigure,
  imagePanel,
  niceScale,
} from '../base/imagePanel.ts';
import {
  CPU_FIRST_PICTURE_MS,
  GPU_FIRST_PICTURE_MS,
  Ladder,
  type FrameRequest,
  type Refinement,
} from '../base/refinement.ts';
import { SweepControls, logLogSlope } from '../base/sweep.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import {
  CpuRenderer,
  GpuRenderer,
  paintImage,
  renderFrame,
  type FrameRenderer,
  type RowsCost,
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
import { CONTROL_POINTS } from './schema.ts';
import { terminationSaving, type TerminationTimes } from './saving.ts';
import { formatCount, type TransferFrame } from './widget.ts';

/** Degrees the camera turns per CSS pixel of drag, and per arrow key press. */
const DRAG_DEGREES_PER_PIXEL = 0.5;
const KEY_DEGREES = 5;
/** Quiet time after a change before the reference starts (ms). */
const REFERENCE_DELAY_MS = 350;

const wrapDegrees = (a: number): number => ((((a + 180) % 360) + 360) % 360) - 180;
const clampElevation = (e: number): number => Math.min(Math.max(e, -85), 85);

/** The GPU renderer, created once the device exists (it compiles the kernel). */
type Renderer = Promise<GpuRenderer>;

interface ReferenceJob {
  key: string;
  cancelled: boolean;
  /** Stopped by the reader's input rather than cancelled: its bands are kept to resume. */
  paused?: boolean;
  promise: Promise<VolumeImage | null>;
  /** Aborted with `cancelled`: drops the band's rows still queued in the compute worker. */
  controller: AbortController;
}

/** A reference stopped by an input: the bands done, to go on from if its scene is shown again. */
interface PartialReference {
  key: string;
  image: VolumeImage;
  band: number;
  milliseconds: number;
}

/** A rendered frame with what the reference and the saving need: its scene key and renderer. */
interface Frame extends TransferFrame {
  key: string;
  renderer: FrameRenderer;
  /** Which stage of the progressive refinement it is (a preview has fewer rays). */
  refinement: Refinement;
}

/**
 * Image sides of the progressive refinement (issue 23): a quarter, a half and all of the
 * full side, one sixteenth, a quarter and all of the rays; on the GPU also an eighth of
 * the side first (40×40 rays took 58–61 ms on SwiftShader, past the preview's share of the
 * budget). The ladder starts on the largest that its measured cost fits into the
 * preview's share of the first-picture budget.
 */
function sizeLadder(full: number, firstBudgetMs: number, eighth: boolean): Ladder<number> {
  const rung = (side: number) => ({
    value: side,
    work: (side * side) / (full * full),
    label: `${side}×${side} rays`,
  });
  const sides = [...(eighth ? [full / 8] : []), full / 4, full / 2, full];
  return new Ladder(sides.map(rung), firstBudgetMs);
}

export function createView(context: ViewContext<Renderer>): WidgetView<TransferFrame, Renderer> {
  const volumeCanvas = imageCanvas(
    'Volume rendering of the CT head phantom. Drag, or use the arrow keys, to orbit the camera.',
    IMAGE_SIZE,
    IMAGE_SIZE,
  );
  const errorCanvas = imageCanvas(
    'Error image: |image − fine-step reference|, largest channel',
    IMAGE_SIZE,
    IMAGE_SIZE,
  );
  let errorTop: HTMLElement | null = null;
  let rightCaption: HTMLElement | null = null;
  const referenceProgress = document.createElement('progress');
  const referenceStatus = document.createElement('span');
  const referenceButton = document.createElement('button');
  let editor: TransferEditor | null = null;
  let sweep: SweepControls | null = null;

  let lastFrame: Frame | null = null;
  let reference: { key: string; image: VolumeImage } | null = null;
  let referenceJob: ReferenceJob | null = null;
  let referenceTimer: ReturnType<typeof setTimeout> | null = null;
  let partialReference: PartialReference | null = null;
  /** Time and steps with the other termination setting, per scene, step and ε. */
  const otherMode = new Map<string, TerminationTimes>();
  let otherModeRunning = '';
  const ladders = {
    gpu: sizeLadder(IMAGE_SIZE, GPU_FIRST_PICTURE_MS, true),
    cpu: sizeLadder(CPU_SIZE, CPU_FIRST_PICTURE_MS, false),
  };

  const set = (key: string, text: string, state?: 'ok' | 'bad'): void =>
    context.setReadout(key, text, state);

  const orbitTo = (azimuth: number, elevation: number): void => {
    const round = (x: number): string => String(Math.round(x));
    if (round(azimuth) !== String(context.values['azimuth']))
      context.setValue('azimuth', round(azimuth));
    if (round(elevation) !== String(context.values['elevation']))
      context.setValue('elevation', round(elevation));
  };

  const attachOrbit = (canvas: HTMLCanvasElement): void => {
    let drag: { x: number; y: number; azimuth: number; elevation: number } | null = null;
    canvas.addEventListener('pointerdown', (event) => {
      canvas.setPointerCapture(event.pointerId);
      drag = {
        x: event.clientX,
        y: event.clientY,
        azimuth: Number(context.values['azimuth']),
        elevation: Number(context.values['elevation']),
      };
      event.preventDefault();
    });
    canvas.addEventListener('pointermove', (event) => {
      if (!drag || !canvas.hasPointerCapture(event.pointerId)) return;
      const azimuth = wrapDegrees(drag.azimuth - (event.clientX - drag.x) * DRAG_DEGREES_PER_PIXEL);
      const elevation = clampElevation(
        drag.elevation + (event.clientY - drag.y) * DRAG_DEGREES_PER_PIXEL,
      );
      orbitTo(azimuth, elevation);
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
      orbitTo(
        wrapDegrees(Number(context.values['azimuth']) + turn[0] * scale),
        clampElevation(Number(context.values['elevation']) + turn[1] * scale),
      );
    });
  };

  /** Moves the twelve control-point inputs the shell generated into one collapsible group. */
  const groupPointControls = (): void => {
    const form = context.host.querySelector<HTMLFormElement>('.sb-controls');
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
  };

  const setReferenceStatus = (text: string, progress: number): void => {
    referenceStatus.textContent = text;
    referenceProgress.value = progress;
    const running = referenceJob !== null && !referenceJob.cancelled;
    referenceButton.textContent = running ? 'Cancel reference' : 'Compute reference';
    referenceButton.disabled = reference?.key === lastFrame?.key;
  };

  const cancelReference = (byUser: boolean): void => {
    if (referenceTimer) {
      clearTimeout(referenceTimer);
      referenceTimer = null;
    }
    if (referenceJob) {
      referenceJob.cancelled = true;
      referenceJob.controller.abort();
    }
    referenceJob = null;
    if (byUser) {
      sweep?.cancel('stopped: the reference was cancelled');
      set('rmse', 'reference cancelled');
      setReferenceStatus('Reference cancelled: press Compute reference to finish it.', 0);
    }
  };

  const dropReference = (): void => {
    cancelReference(false);
    reference = null;
    otherMode.clear();
  };

  /** The right-hand image in its "steps taken per ray" mode, on a linear scale. */
  const showSteps = (image: VolumeImage): void => {
    let most = 0;
    for (const n of image.plannedPerPixel) most = Math.max(most, n);
    const scale = niceScale(most);
    paintImage(errorCanvas, image.size, (i) =>
      errorColour((image.stepsPerPixel[i]! / scale) ** 2, 1),
    );
    if (errorTop) errorTop.textContent = String(scale);
    if (rightCaption)
      rightCaption.textContent = 'Steps taken per ray (black: the ray misses the volume)';
  };

  const showError = (frame: Frame, referenceImage: VolumeImage | null): void => {
    const { image } = frame;
    const pixels = image.size * image.size;
    const stepsMode = frame.inputs.panel === 'steps';
    if (stepsMode) showSteps(image);
    else if (rightCaption) rightCaption.textContent = 'Error |L − L_ref| against Δs = ⅛ voxel';
    if (!referenceImage) {
      if (!stepsMode) {
        paintImage(errorCanvas, image.size, () => [4, 6, 16]);
        if (errorTop) errorTop.textContent = '…';
      }
      set('max-error', 'waiting for the reference');
      if (!referenceJob) set('rmse', 'waiting for the reference');
      return;
    }
    const errors = pixelErrors(image.rgb, referenceImage.rgb, pixels);
    const largest = maxError(image.rgb, referenceImage.rgb);
    const scale = niceScale(largest);
    if (!stepsMode) {
      paintImage(errorCanvas, image.size, (i) => errorColour(errors[i]!, scale));
      if (errorTop) errorTop.textContent = formatNumber(scale, 2);
    }
    set('rmse', formatNumber(rmse(image.rgb, referenceImage.rgb), 3));
    set('max-error', formatNumber(largest, 3));
    setReferenceStatus(referenceStatus.textContent ?? '', 1);
  };

  /** The key of a full-quality frame's termination timing: its scene, step and ε. */
  const savingKey = (frame: Frame): string =>
    `${frame.key}|${frame.inputs.step}|${frame.inputs.epsilon}`;

  /** The saving row of a full-quality frame (saving.ts), with its timing if measured. */
  const showSaving = (frame: Frame): void =>
    set('saving', terminationSaving(frame, otherMode.get(savingKey(frame))));

  /**
   * Measures a full-quality frame's cost with and without early termination, for the
   * saving readout: the other setting twice and the current one once more, alternating.
   * On a CPU shared with other work (SwiftShader) single timings vary by tens of percent,
   * so the readout compares the best of each pair and names the spread. Stops (and
   * caches nothing) when the inputs change: a new frame measures again.
   */
  const measureOtherMode = (frame: Frame): void => {
    const { inputs } = frame;
    const key = savingKey(frame);
    showSaving(frame);
    if (otherMode.has(key) || otherModeRunning === key) return;
    otherModeRunning = key;
    const signal = context.inputSignal;
    const otherInputs = { ...inputs, termination: !inputs.termination };
    const run = async (which: FrameInputs) => {
      signal.throwIfAborted();
      return renderFrame(
        frame.renderer,
        which,
        which.step,
        thresholdOf(which),
        frame.renderer.size,
        signal,
        true,
        // One band at a time beside the frames, as the reference: an input waits for one.
        1,
      );
    };
    void (async () => {
      const first = await run(otherInputs);
      const again = await run(inputs);
      const second = await run(otherInputs);
      const result: TerminationTimes = {
        current: [frame.milliseconds, again.milliseconds],
        other: [first.milliseconds, second.milliseconds],
        otherSteps: first.image.steps,
      };
      if (otherMode.size > 64) otherMode.clear();
      otherMode.set(key, result);
      if (lastFrame === frame) showSaving(frame);
    })()
      .catch(() => {
        if (!signal.aborted) set('saving', 'not measured (the render failed)', 'bad');
      })
      .finally(() => {
        if (otherModeRunning === key) otherModeRunning = '';
      });
  };

  const computeReference = async (frame: Frame, job: ReferenceJob): Promise<VolumeImage | null> => {
    const { renderer, inputs } = frame;
    const resume =
      partialReference?.key === job.key && partialReference.image.size === renderer.size
        ? partialReference
        : null;
    partialReference = null;
    const image = resume?.image ?? renderer.blank();
    const bandRows = REFERENCE_BAND_ROWS;
    const bands = Math.ceil(renderer.size / bandRows);
    referenceButton.textContent = 'Cancel reference';
    let milliseconds = resume?.milliseconds ?? 0;
    for (let band = resume?.band ?? 0; band < bands; band++) {
      if (job.cancelled) {
        if (job.paused) partialReference = { key: job.key, image, band, milliseconds };
        return null;
      }
      setReferenceStatus(`Reference: Δs = ⅛ voxel, band ${band + 1} of ${bands}…`, band / bands);
      set('rmse', `computing the reference… ${Math.round((100 * band) / bands)}%`);
      let cost: RowsCost;
      try {
        // Aborted by a cancel or an input: nothing of the band is written (renderInto
        // copies its rows only once all are back), so a resumed reference redoes it.
        cost = await renderer.renderInto(
          image,
          inputs,
          REFERENCE_STEP_VOXELS,
          REFERENCE_EPSILON,
          band * bandRows,
          (band + 1) * bandRows,
          job.controller.signal,
          false,
          // One band at a time beside the frames: an input waits for one of them at most
          // (firstPictureProbe: two reference bands and a frame's, 80 ms, were in flight).
          1,
        );
      } catch (error) {
        if (!job.cancelled) throw error;
        if (job.paused) partialReference = { key: job.key, image, band, milliseconds };
        return null;
      }
      milliseconds += cost.milliseconds;
      // Let the page breathe between bands: input, painting and Cancel stay live.
      await new Promise((resolve) => setTimeout(resolve, 0));
    }
    if (job.cancelled) return null;
    reference = { key: job.key, image };
    if (referenceJob === job) referenceJob = null;
    setReferenceStatus(
      `Reference ready: Δs = ⅛ voxel, ${formatCount(image.steps)} steps in ${formatMilliseconds(milliseconds)}.`,
      1,
    );
    const latest = lastFrame;
    if (latest?.key === job.key) showError(latest, image);
    return image;
  };

  /** The reference of the frame's scene: cached, running, or started now. */
  const ensureReference = (frame: Frame): Promise<VolumeImage | null> => {
    if (reference?.key === frame.key) return Promise.resolve(reference.image);
    if (referenceJob?.key === frame.key && !referenceJob.cancelled) return referenceJob.promise;
    if (referenceTimer) {
      clearTimeout(referenceTimer);
      referenceTimer = null;
    }
    const job: ReferenceJob = {
      key: frame.key,
      cancelled: false,
      promise: Promise.resolve(null),
      controller: new AbortController(),
    };
    referenceJob = job;
    job.promise = computeReference(frame, job);
    return job.promise;
  };

  const analyse = (frame: Frame): void => {
    if (reference?.key === frame.key) {
      showError(frame, reference.image);
      return;
    }
    showError(frame, null);
    if (referenceJob && referenceJob.key !== frame.key) cancelReference(false);
    if (referenceJob?.key === frame.key) return;
    if (referenceTimer) clearTimeout(referenceTimer);
    setReferenceStatus('Reference: waiting for the view to settle…', 0);
    // An input before the delay is over cancels the start: lastFrame is still this frame
    // while the input's preview renders (only full-quality frames replace it), and a
    // reference started then ran its bands under the preview (firstPictureProbe).
    const settledSignal = context.inputSignal;
    referenceTimer = setTimeout(() => {
      referenceTimer = null;
      if (settledSignal.aborted || lastFrame?.key !== frame.key) return;
      void ensureReference(frame);
      // The next input's first picture must not queue behind the reference's bands: it
      // pauses (keeping its bands) and goes on once the new picture has settled.
      const job = referenceJob;
      context.inputSignal.addEventListener(
        'abort',
        () => {
          if (!job || referenceJob !== job || job.cancelled) return;
          job.paused = true;
          job.cancelled = true;
          job.controller.abort();
          referenceJob = null;
        },
        { once: true },
      );
    }, REFERENCE_DELAY_MS);
  };

  const toggleReference = (): void => {
    if (referenceJob && !referenceJob.cancelled) cancelReference(true);
    else if (lastFrame) void ensureReference(lastFrame);
  };

  /** The inputs of this frame, with the notice of reordered points and the editor brought up to date. */
  const prepare = (): FrameInputs => {
    const inputs = inputsFrom(context.values);
    if (inputs.reordered) {
      context.showNotice(
        'reordered',
        'warning',
        'The control points in this link were not in increasing order of value; they are used sorted.',
      );
    } else {
      context.clearNotice('reordered');
    }
    const map = COLOUR_MAPS[inputs.colormap] ?? COLOUR_MAPS['tissue']!;
    const domain = colourDomain(inputs.points);
    editor?.update({ points: inputs.points, colourAt: (v) => colourAt(map, domain, v) });
    return inputs;
  };

  /**
   * One stage of the picture: a preview with fewer rays first (the ladder's rung), then
   * the full image. Only a full-quality frame becomes `lastFrame`, which the reference,
   * the error image and the termination saving compare against.
   */
  const frameOn = async (
    renderer: FrameRenderer,
    inputs: FrameInputs,
    request: FrameRequest,
  ): Promise<Frame> => {
    const ladder = ladders[renderer.kind];
    const choice = ladder.pick(request);
    const start = performance.now();
    const { image, milliseconds, how, timing } = await renderFrame(
      renderer,
      inputs,
      inputs.step,
      thresholdOf(inputs),
      choice.rung.value,
      request.signal,
    );
    // The latency a reader sees (dispatch, read-back and all), not only the GPU pass.
    ladder.record(choice.index, performance.now() - start);
    const frame: Frame = {
      inputs,
      image,
      milliseconds,
      how,
      timing,
      biasBound: terminationBiasBound(inputs),
      voxel: VOXEL,
      key: `${renderer.kind}|${sceneKey(inputs)}`,
      renderer,
      refinement: ladder.refinement(choice),
    };
    // A frame of a drag's earlier inputs (shown, refinement.ts showsWhenStale) is not the
    // one the reference, the error image and the saving compare against.
    if (choice.final && !request.inputsChanged.aborted) lastFrame = frame;
    return frame;
  };

  const frameRenderer = async (backend: Backend<Renderer>): Promise<FrameRenderer> =>
    backend.kind === 'gpu' ? backend.renderer : new CpuRenderer();

  const runSweep = (controls: SweepControls): Promise<void> =>
    controls.run(async () => {
      const inputs = inputsFrom(context.values);
      const renderer = await frameRenderer(await context.backend());
      const key = `${renderer.kind}|${sceneKey(inputs)}`;
      set('slope', 'sweeping…');
      const label = `${inputs.termination ? `early termination ε = ${formatNumber(inputs.epsilon, 3)}` : 'no early termination'}`;
      return {
        label,
        measure: async (samplesPerVoxel) => {
          const referenceImage = await ensureReference({
            inputs,
            key,
            renderer,
            image: renderer.blank(),
            milliseconds: 0,
            how: '',
            timing: 'cpu',
            biasBound: 0,
            voxel: VOXEL,
            refinement: { label: 'sweep', pending: null },
          });
          if (!referenceImage) throw new Error('the reference was cancelled');
          const frame = await renderFrame(
            renderer,
            inputs,
            1 / samplesPerVoxel,
            thresholdOf(inputs),
          );
          return {
            rmse: rmse(frame.image.rgb, referenceImage.rgb),
            milliseconds: frame.milliseconds,
          };
        },
        finish: (points) => {
          const slope = logLogSlope(
            points.map((p) => p.n),
            points.map((p) => p.rmse),
          );
          set(
            'slope',
            slope === null
              ? 'no fit'
              : `q = ${formatNumber(-slope, 3)} (RMSE ∝ Δs^${formatNumber(-slope, 3)})`,
          );
          return `${label}, ${renderer.kind === 'gpu' ? 'GPU' : 'CPU fallback'}`;
        },
        failed: () => set('slope', 'failed', 'bad'),
      };
    });

  return {
    cpuNotice: `Showing the float64 CPU twin: the same rays and marches, at ${CPU_SIZE}×${CPU_SIZE} pixels.`,
    build(stage) {
      volumeCanvas.tabIndex = 0;
      volumeCanvas.classList.add('sb-tf-volume');
      const error = imagePanel(errorCanvas, 'Error |L − L_ref| against Δs = ⅛ voxel', {
        gradient: gradientCss((x) => errorColour(x, 1)),
        low: '0',
        top: { readout: 'error-scale' },
      });
      errorTop = error.top;
      rightCaption = error.panel.querySelector('figcaption');
      const figure = imageFigure(
        imagePanel(volumeCanvas, 'Emission–absorption rendering (drag or ←↑→↓ to orbit)').panel,
        error.panel,
      );
      figure.classList.add('sb-tf-images');
      stage.appendChild(figure);
      attachOrbit(volumeCanvas);

      const status = document.createElement('div');
      status.className = 'sb-tf-reference';
      referenceProgress.max = 1;
      referenceProgress.value = 0;
      referenceProgress.setAttribute('aria-label', 'Reference progress');
      referenceStatus.setAttribute('aria-live', 'polite');
      referenceStatus.textContent = 'Reference: not computed yet.';
      referenceButton.type = 'button';
      referenceButton.className = 'sb-button';
      referenceButton.textContent = 'Cancel reference';
      referenceButton.addEventListener('click', toggleReference);
      status.append(referenceProgress, referenceStatus, referenceButton);
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
        button.addEventListener('click', () => context.applyPreset(index));
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
      editor = new TransferEditor(plot, histogram(volume.hounsfield), {
        move: (index, hu, opacity) => {
          context.setValue(`hu-${index}`, String(hu));
          context.setValue(`opacity-${index}`, String(opacity));
        },
      });

      const controls = new SweepControls(
        stage,
        context.host,
        {
          name: '1/Δs',
          buttonText: 'Run sweep Δs = 4 … ½ voxel',
          hint: 'Run the sweep to plot the RMSE against the time per frame for Δs = 4, 2, 1 and ½ voxel and fit the order of convergence.',
          color: '#d9822b',
          statusClass: 'sb-tf-sweep-status',
          points: SWEEP_SAMPLES_PER_VOXEL,
        },
        () => void runSweep(controls),
      );
      sweep = controls;
    },
    buildReadoutExtras: () => groupPointControls(),
    createRenderer: (gpu) =>
      VolumeRendererGpu.create(gpu.device, STATIC_KERNELS, phantomGrid()).then(
        (renderer) => new GpuRenderer(renderer),
      ),
    async renderGpu(renderer, _gpu, request) {
      const inputs = prepare();
      return frameOn(await renderer, inputs, request);
    },
    renderCpu(request) {
      const inputs = prepare();
      return frameOn(new CpuRenderer(), inputs, request);
    },
    refinement: (frame) => (frame as Frame).refinement,
    onCpuFallback: () => {
      sweep?.cancel('stopped: the GPU was lost');
      dropReference();
    },
    destroy: () => {
      sweep?.cancel('stopped');
      dropReference();
    },
    show(shown) {
      const { image, inputs } = shown;
      const frame = shown as Frame;
      const pixels = image.size * image.size;
      paintImage(volumeCanvas, image.size, (i) => pixelColour(image.rgb, pixels, i));
      if (image.cappedRays > 0) {
        context.showNotice(
          'capped',
          'warning',
          `${image.cappedRays} rays needed more than 8192 steps and were marched with longer ones.`,
        );
      } else {
        context.clearNotice('capped');
      }
      volumeCanvas.setAttribute(
        'aria-label',
        `Volume rendering of the CT head phantom, azimuth ${inputs.azimuth}°, elevation ${inputs.elevation}°, step ${formatNumber(inputs.step, 4)} voxel. Drag, or use the arrow keys, to orbit the camera.`,
      );
      if (frame.refinement.pending !== null) {
        // A preview: the error against the reference and the saving are for the full image.
        if (inputs.panel === 'steps') showSteps(image);
        else paintImage(errorCanvas, image.size, () => [4, 6, 16]);
        for (const key of ['rmse', 'max-error', 'saving']) set(key, 'after the preview…');
        return;
      }
      if (frame !== lastFrame) {
        // Stale (a drag's earlier inputs): the analysis is for the newest inputs' frame.
        for (const key of ['rmse', 'max-error', 'saving']) set(key, 'after the drag…');
        return;
      }
      analyse(frame);
      measureOtherMode(frame);
    },
  };
}
