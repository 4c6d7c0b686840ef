// The element built from a widget definition: the shell of WidgetElement (controls,
// URL state, presentation, presets, notices, errors) plus what every widget used to
// write for itself: the backend choice (GPU or the CPU twin, `?backend=cpu`, device
// loss), the CPU-fallback notice, fresh canvases where a WebGPU context was lost,
// the readouts filled from the definition's rows, the recorded frame cost, and the
// lifecycle (a widget moved in the DOM draws again; one removed for good releases
// its GPU resources and its device-loss subscription).
import type { GpuContext } from '../../gpu/device.ts';
import { BackendChooser, gpuFailureReason, type Backend } from './backend.ts';
import { tagName, type FrameBackend, type Readouts, type WidgetDefinition } from './definition.ts';
import { timingLabel } from './timing.ts';
import { ReadoutList } from './readoutList.ts';
import {
  firstPictureBudget,
  RefinementState,
  showsWhenStale,
  whenIdle,
  type FrameRequest,
} from './refinement.ts';
import type {
  CanvasOptions,
  ManagedCanvas,
  ViewContext,
  WidgetModule,
  WidgetView,
} from './view.ts';
import { WidgetElement } from './widgetElement.ts';
import { context2d } from './canvas2d.ts';

/**
 * A first picture still drawing this many first-picture budgets after it started is
 * dropped on the next input (onInput). Not 1: on a loaded machine a preview that takes
 * somewhat longer than the budget would be aborted at every input, and the aborted render
 * teaches its ladder nothing, so the drag would freeze again.
 */
const OVERDUE_FACTOR = 3;

/**
 * How long a disconnected widget waits before it releases its resources. A move is a
 * disconnect and a connect in the same task; a widget put back later is built anew.
 */
const RELEASE_DELAY_MS = 1000;

class Canvas implements ManagedCanvas {
  element: HTMLCanvasElement;
  constructor(private readonly options: CanvasOptions) {
    this.element = this.create();
  }

  create(): HTMLCanvasElement {
    const canvas = document.createElement('canvas');
    canvas.className = this.options.className ?? 'sb-canvas';
    canvas.setAttribute('role', 'img');
    canvas.setAttribute('aria-label', this.options.label ?? 'Picture (being drawn)');
    canvas.width = this.options.width;
    canvas.height = this.options.height;
    return canvas;
  }

  /**
   * A canvas whose context is WebGPU cannot give a 2D context (getContext returns
   * null), so the CPU path gets a fresh one in its place, keeping its description.
   */
  replaceIfWebGpu(): void {
    if (context2d(this.element) !== null) return;
    const fresh = this.create();
    const label = this.element.getAttribute('aria-label');
    if (label !== null) fresh.setAttribute('aria-label', label);
    this.element.replaceWith(fresh);
    this.element = fresh;
  }
}

/** The element class of a definition whose module provides a view. */
export function definedElementClass<Frame>(
  definition: WidgetDefinition<Frame>,
  module: Extract<WidgetModule<Frame>, { createView: unknown }>,
): CustomElementConstructor {
  return class extends DefinedWidgetElement<Frame> {
    protected readonly definition = definition;
    protected readonly entry = definition.entry;
    protected override presets = definition.presets ?? [];
    protected createView(context: ViewContext): WidgetView<Frame> {
      return module.createView(context) as WidgetView<Frame>;
    }
  };
}

/** Defines `sb-<name>` from a definition's loaded module (old element or view); once per page. */
export function defineFromModule<Frame>(
  definition: WidgetDefinition<Frame>,
  module: WidgetModule<Frame>,
): void {
  const name = tagName(definition);
  if (customElements.get(name)) return;
  customElements.define(
    name,
    'element' in module ? module.element : definedElementClass(definition, module),
  );
}

export abstract class DefinedWidgetElement<Frame> extends WidgetElement {
  protected abstract readonly definition: WidgetDefinition<Frame>;
  protected abstract createView(context: ViewContext): WidgetView<Frame>;

  private view: WidgetView<Frame> | null = null;
  private readouts: ReadoutList | null = null;
  private canvases: Canvas[] = [];
  private aborter = new AbortController();
  private releaseTimer: ReturnType<typeof setTimeout> | null = null;
  private readonly backends = new BackendChooser<unknown>(
    (gpu) => this.makeRenderer(gpu),
    (reason) => this.fallBackToCpu(reason),
  );
  private renderer: unknown = null;

  /** Input versions, stages and settledness (refinement.ts). */
  private readonly refinement = new RefinementState();
  /** Aborted on the next input (ViewContext.inputSignal; FrameRequest.signal after stage 0). */
  private inputAborter = new AbortController();
  /** The first picture being drawn (FrameRequest.signal of stage 0) and when it started. */
  private firstPicture: { aborter: AbortController; started: number } | null = null;
  /** The signal of the latest frame requested (ViewContext.frameSignal). */
  private frameSignal: AbortSignal | null = null;

  /** The children the element had before its first shell (see ViewContext.content). */
  private content: readonly Element[] | null = null;

  override connectedCallback(): void {
    if (this.releaseTimer !== null) clearTimeout(this.releaseTimer);
    this.releaseTimer = null;
    this.content ??= [...this.children];
    super.connectedCallback();
  }

  override disconnectedCallback(): void {
    super.disconnectedCallback();
    this.view?.onDisconnected?.();
    if (this.releaseTimer !== null) clearTimeout(this.releaseTimer);
    this.releaseTimer = setTimeout(() => {
      this.releaseTimer = null;
      if (!this.isConnected) this.destroy();
    }, RELEASE_DELAY_MS);
  }

  /**
   * Releases the GPU renderer, the device-loss subscription and the view's own work, and
   * forgets the shell: connected again, the widget is built anew (from its attributes and
   * the URL).
   */
  destroy(): void {
    this.aborter.abort();
    this.firstPicture?.aborter.abort();
    this.releaseRenderer();
    this.backends.reset();
    this.view?.destroy?.();
    this.view = null;
    this.readouts = null;
    this.canvases = [];
    this.forgetShell();
    this.aborter = new AbortController();
  }

  protected buildStage(stage: HTMLElement): void {
    this.view = this.createView(this.viewContext());
    this.view.build(stage);
  }

  protected buildReadout(area: HTMLElement): void {
    const rows = this.definition.readouts?.rows ?? [];
    this.readouts = new ReadoutList(
      area,
      rows.map((row) => [row.key, row.label] as const),
    );
    for (const row of rows) if (row.initial !== undefined) this.readouts.set(row.key, row.initial);
    this.view?.buildReadoutExtras?.(area);
  }

  /** A preset, keeping the parameters the definition says presets keep (presetKeeps). */
  protected override applyPreset(index: number): void {
    const kept = (this.definition.presetKeeps ?? []).map(
      (name) => [name, this.values[name]] as const,
    );
    super.applyPreset(index);
    for (const [name, value] of kept)
      if (value !== undefined && this.values[name] !== value) super.setValue(name, String(value));
  }

  /**
   * New parameters: the stale stage's signal aborts, and so does a first picture in flight
   * that started more than OVERDUE_FACTOR first-picture budgets ago (a rung that cost more
   * than its ladder predicted: transfer-function's CPU preview at the drag's smallest step
   * took 1.3 s and held the drag's pictures back); the next frame is stage 0.
   */
  protected override onInput(): void {
    this.refinement.input();
    this.inputAborter.abort();
    this.inputAborter = new AbortController();
    const first = this.firstPicture;
    const overdue = OVERDUE_FACTOR * firstPictureBudget(this.drawnOnGpu ? 'gpu' : 'cpu');
    if (first && performance.now() - first.started > overdue) first.aborter.abort();
    this.dataset['settled'] = 'false';
  }

  /** A reader's input through a control, then the view's linked parameters (valueChanged). */
  protected override setValue(name: string, raw: string): void {
    super.setValue(name, raw);
    this.view?.valueChanged?.(name);
  }

  /** Whether the last render drew on WebGPU (startsRightAfterRender). */
  private drawnOnGpu = false;

  /**
   * On WebGPU the next render starts as soon as the last ends (first pictures 10–30 ms
   * sooner on SwiftShader); the CPU twin keeps the animation frame's pacing: chained
   * right after each other its renders made long tasks of 150–360 ms during a drag
   * (bench/interaction.ts, dipole-profile, transfer-function, chromatic-media).
   */
  protected override startsRightAfterRender(): boolean {
    return this.drawnOnGpu;
  }

  protected override async drawForPrint(): Promise<void> {
    await this.view?.drawForPrint?.();
  }

  private viewContext(): ViewContext {
    // eslint-disable-next-line @typescript-eslint/no-this-alias -- the context reads live state
    const element = this;
    return {
      get values() {
        return element.values;
      },
      get widgetId() {
        return element.widgetId;
      },
      get signal() {
        return element.aborter.signal;
      },
      get inputSignal() {
        return element.inputAborter.signal;
      },
      get frameSignal() {
        return element.frameSignal ?? element.inputAborter.signal;
      },
      host: this,
      backend: () => this.backends.choose(),
      useCpu: (reason) => this.fallBackToCpu(reason),
      setReadout: (key, text, state) => this.readouts?.set(key, text, state),
      setCost: (text) => {
        if (this.readouts) this.readouts.cost.textContent = text;
      },
      recordFrameCost: (milliseconds, timer) => this.recordFrameCost(milliseconds, timer),
      cpuFallbackNotice: (reason, what) => this.showCpuFallbackNotice(reason, what),
      get content() {
        return element.content ?? [];
      },
      canvas: (options) => {
        const canvas = new Canvas(options);
        this.canvases.push(canvas);
        return canvas;
      },
      scheduleRender: () => this.scheduleRender(),
      setValue: (name, raw) => super.setValue(name, raw),
      applyPreset: (index) => this.applyPreset(index),
      report: (frame, backend) => this.report(frame as Frame, backend),
      showNotice: (key, kind, message, timeoutMs) => this.showNotice(key, kind, message, timeoutMs),
      clearNotice: (key) => this.clearNotice(key),
    };
  }

  private makeRenderer(gpu: GpuContext): unknown {
    const view = this.view;
    if (!view?.createRenderer || !view.renderGpu) throw new Error('this figure draws on the CPU');
    this.renderer = view.createRenderer(gpu);
    return this.renderer;
  }

  private releaseRenderer(): void {
    if (this.renderer !== null) this.view?.destroyRenderer?.(this.renderer);
    this.renderer = null;
  }

  /** After a device loss or a failed GPU frame: fresh canvases and the CPU twin, for good. */
  private fallBackToCpu(reason: string): void {
    this.view?.onCpuFallback?.(reason);
    this.releaseRenderer();
    for (const canvas of this.canvases) canvas.replaceIfWebGpu();
    this.backends.useCpu(reason);
    this.refinement.cancelNext();
    this.scheduleRender();
  }

  /**
   * The request of this render: the next stage (or background frame) if the last frame
   * asked for one and the inputs are the same; otherwise (an input, a move, a redraw)
   * stage 0 of a new picture, which unsettles the widget until it reports.
   */
  private nextRequest(): FrameRequest & { version: number } {
    const { stage, version, background } = this.refinement.request();
    this.dataset['settled'] = String(this.refinement.settled);
    const inputsChanged = this.inputAborter.signal;
    let signal = inputsChanged;
    if (showsWhenStale({ stage, background })) {
      // A first picture runs to its end and is shown even when inputs came meanwhile,
      // unless it is overdue (onInput) or the widget is destroyed.
      const aborter = new AbortController();
      this.firstPicture = { aborter, started: performance.now() };
      signal = aborter.signal;
    }
    this.frameSignal = signal;
    return { stage, background, version, signal, inputsChanged };
  }

  /**
   * Asks for a background frame once the page is idle, unless an input (or a restart)
   * came meanwhile: background refinement never delays a reader's input, and the
   * render itself still waits for an animation frame with the widget on screen.
   */
  private scheduleBackground(version: number): void {
    const destroyed = this.aborter.signal;
    whenIdle(() => {
      if (!destroyed.aborted && this.refinement.wantsBackground(version)) this.scheduleRender();
    });
  }

  /**
   * Whether a render that threw was for inputs that changed meanwhile: it gave up (a later
   * stage aborted, or a first picture whose job listened to the live input signal,
   * ViewContext.inputSignal), and the render for the new inputs draws next. Not a failure.
   */
  private gaveUp(request: FrameRequest & { version: number }): boolean {
    return request.signal.aborted || request.version !== this.refinement.inputVersion;
  }

  protected async render(): Promise<void> {
    const view = this.view;
    if (!view) return;
    if (view.renderWithoutBackend) {
      const frame = await view.renderWithoutBackend();
      if (frame !== null) this.report(frame, { kind: 'cpu', reason: 'no backend' });
      return;
    }
    const request = this.nextRequest();
    try {
      await this.renderRequest(view, request);
    } finally {
      if (this.firstPicture?.aborter.signal === request.signal) this.firstPicture = null;
    }
  }

  private async renderRequest(
    view: WidgetView<Frame>,
    request: FrameRequest & { version: number },
  ): Promise<void> {
    const { version } = request;
    const backend: Backend<unknown> = await this.backends.choose();
    this.drawnOnGpu = backend.kind === 'gpu' && view.renderGpu !== undefined;
    if (backend.kind === 'gpu' && view.renderGpu) {
      let frame: Frame | null;
      try {
        frame = await view.renderGpu(backend.renderer, backend.gpu, request);
      } catch (error) {
        if (this.gaveUp(request)) return;
        this.fallBackToCpu(gpuFailureReason(error));
        return;
      }
      this.clearNotice('backend');
      // A later stage drawn for inputs that changed meanwhile is not reported (its picture
      // and readouts would be older than the first picture the input scheduled next). A
      // first picture is (showsWhenStale): its report neither settles nor continues.
      if (request.signal.aborted) return;
      if (frame !== null)
        this.report(
          frame,
          { kind: 'gpu', adapterDescription: backend.gpu.adapterDescription },
          version,
        );
      else this.settleWithoutFrame(version);
      return;
    }
    const reason = backend.kind === 'cpu' ? backend.reason : 'this figure draws on the CPU';
    // Said before drawing: a CPU frame can be a long job (the comparison of estimators).
    this.showCpuFallbackNotice(reason, view.cpuNotice ?? '');
    let frame: Frame | null;
    try {
      frame = (await view.renderCpu?.(request)) ?? null;
    } catch (error) {
      if (this.gaveUp(request)) return;
      throw error;
    }
    if (request.signal.aborted) return; // stale, as above
    if (frame !== null) this.report(frame, { kind: 'cpu', reason }, version);
    else this.settleWithoutFrame(version);
  }

  /**
   * A render that drew by itself and returned no frame (delta-tracking's comparison
   * fills its own readouts): a view without refinement has nothing more to come, so the
   * widget is settled once the render is done; a view with refinement reports when it is.
   */
  private settleWithoutFrame(version: number): void {
    if (this.view?.refinement) return;
    this.refinement.settleWithoutFrame(version);
    this.dataset['settled'] = String(this.refinement.settled);
  }

  /**
   * Fills the readouts and the cost line, records the cost, lets the view draw the rest,
   * and follows the frame's refinement: data-frames counts every frame shown,
   * data-stage and the stage line say what it is, data-settled whether the picture is
   * complete (RefinementState's rules). A frame rendered for the current inputs
   * (`version`) that asks for more schedules the next stage now, or a background frame
   * when the page is idle; a job's report (no version) is the job's own business.
   */
  private report(frame: Frame, backend: FrameBackend, version?: number): void {
    // data-frames counts the frames of the current inputs, so that "the next frame after
    // an input" is that input's (tests, bench/interaction.ts); a first picture of a drag's
    // earlier inputs (showsWhenStale) counts in data-stale-frames.
    const counter =
      version !== undefined && version !== this.refinement.inputVersion ? 'staleFrames' : 'frames';
    this.dataset[counter] = String(Number(this.dataset[counter] ?? '0') + 1);
    const refinement = this.view?.refinement?.(frame);
    const pending = refinement?.pending ?? null;
    this.dataset['stage'] = refinement?.label ?? 'full';
    const next = this.refinement.report(pending, version);
    this.dataset['settled'] = String(this.refinement.settled);
    this.readouts?.setStage(refinement?.label ?? '', pending);
    if (next === 'frame') this.scheduleRender();
    else if (next === 'background') this.scheduleBackground(this.refinement.inputVersion);
    const readouts: Readouts<Frame> | undefined = this.definition.readouts;
    if (readouts) {
      for (const row of readouts.rows) {
        if (!row.format) continue;
        const value = row.format(frame, backend);
        if (typeof value === 'string') this.readouts?.set(row.key, value);
        else this.readouts?.set(row.key, value.text, value.state);
      }
      const cost = readouts.cost?.(frame);
      if (cost) {
        const how = timingLabel(cost.timing);
        this.recordFrameCost(cost.milliseconds, how);
        const where =
          backend.kind === 'gpu' ? `WebGPU (${backend.adapterDescription})` : 'CPU fallback';
        const line = readouts.costLine?.(frame, how, backend);
        if (this.readouts && line !== undefined)
          this.readouts.cost.textContent = `${where}: ${line}`;
      }
    }
    this.view?.show?.(frame, backend);
  }
}
