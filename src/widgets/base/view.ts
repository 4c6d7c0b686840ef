// The part of a widget that is specific to it, loaded lazily by its definition
// (widget.ts → load()): building its canvases and plots, a GPU render and a CPU
// render that each produce a frame, and what to draw from a frame besides the
// readouts. Everything else (controls, URL state, presentation, presets, the
// backend choice and its fallback, notices, errors, frame cost, readouts and the
// lifecycle) is the base element's (definedElement.ts).
import type { GpuContext } from '../../gpu/device.ts';
import type { Backend } from './backend.ts';
import type { ParameterValues } from '../parameters.ts';
import type { FrameBackend } from './definition.ts';
import type { NoticeKind } from './widgetElement.ts';
import type { FrameRequest, Refinement } from './refinement.ts';

/**
 * A canvas owned by the base element. After a device loss or a failed GPU frame the
 * base replaces it with a fresh one if it holds a WebGPU context (a canvas cannot
 * change its context type), so read `element` each frame rather than keeping it.
 */
export interface ManagedCanvas {
  readonly element: HTMLCanvasElement;
}

export interface CanvasOptions {
  width: number;
  height: number;
  /** Class of the canvas element; default `sb-canvas`. */
  className?: string;
  /**
   * Its text alternative until the view describes what it drew (a canvas with
   * role="img" and no name fails WCAG 1.1.1 while the first picture is on its way).
   */
  label?: string;
}

/** What the base element offers a view. */
export interface ViewContext<Renderer = unknown> {
  /** The widget's current, validated parameter values. */
  readonly values: ParameterValues;
  /** The element (for controls that mark it, e.g. SweepControls' data-sweeping). */
  readonly host: HTMLElement;
  /** The backend in use (the same choice render() gets), for the view's own jobs. */
  backend(): Promise<Backend<Renderer>>;
  /** Switches to the CPU for good, as a failed GPU frame does (a job's GPU work failed). */
  useCpu(reason: string): void;
  /** Writes a readout row the view owns (a row without `format`). */
  setReadout(key: string, text: string, state?: 'ok' | 'bad'): void;
  /** Writes the cost line (for a definition whose readouts have no costLine). */
  setCost(text: string): void;
  /** Records the cost of work outside frames (data-frame-ms, data-frame-timer). */
  recordFrameCost(milliseconds: number, timer: string): void;
  /** The notice "WebGPU is not available (reason). what", for a view that checks WebGPU itself. */
  cpuFallbackNotice(reason: string, what: string): void;
  /**
   * The element's children before the shell replaced them: content the build rendered
   * inside the tag (the exercise's statement), for the view to place.
   */
  readonly content: readonly Element[];
  /** A canvas (role="img") the base can swap for a fresh one when the GPU goes away. */
  canvas(options: CanvasOptions): ManagedCanvas;
  /** Draws again on the next frame while on screen (after the view's own input, or a job step). */
  scheduleRender(): void;
  /**
   * Sets a parameter as its control would (validated, shown in the control, saved in the
   * URL, drawn again), from the view's own input (an editor drag, an orbit). It does not
   * call the view's `valueChanged`, so a view can set linked parameters from there.
   */
  setValue(name: string, raw: string): void;
  /** Recalls preset `index` (0-based), as its number key does (for the view's own preset buttons). */
  applyPreset(index: number): void;
  /**
   * Fills the readouts and the cost line from a frame outside render(), e.g. from each
   * step of a long job (the escape hatch: render() starts the job and returns null).
   */
  report(frame: unknown, backend: FrameBackend): void;
  showNotice(key: string, kind: NoticeKind, message: string, timeoutMs?: number): void;
  clearNotice(key: string): void;
  /** The element's id, unique on the page (for ids of the view's own controls). */
  readonly widgetId: string;
  /** Aborted when the widget is destroyed: long jobs stop on it. */
  readonly signal: AbortSignal;
  /**
   * Aborted when the parameters change again (a stale stage or job step may stop early).
   * A frame's own work listens to frameSignal instead: a first picture's runs on through a
   * drag and is shown (refinement.ts showsWhenStale).
   */
  readonly inputSignal: AbortSignal;
  /**
   * The signal of the frame being drawn (its FrameRequest.signal), for work a render
   * hands on, such as a CPU pass in the compute worker; the input signal before any frame.
   */
  readonly frameSignal: AbortSignal;
}

export interface WidgetView<Frame, Renderer = unknown> {
  /** Builds the drawing area: canvases (through context.canvas), plots, extra DOM. */
  build(stage: HTMLElement): void;
  /** Extra DOM under the readout list (buttons, tables); optional. */
  buildReadoutExtras?(area: HTMLElement): void;
  /** Builds the GPU renderer once the device exists. Absent: the widget always draws on the CPU. */
  createRenderer?(gpu: GpuContext): Renderer;
  /**
   * One frame on the GPU. Throwing switches the widget to the CPU for good (with the
   * reason in its notice); null means the frame reports itself later (context.report).
   */
  renderGpu?(renderer: Renderer, gpu: GpuContext, request: FrameRequest): Promise<Frame | null>;
  /** One frame with the float64 CPU twin (no WebGPU, ?backend=cpu, or after a loss). */
  renderCpu?(request: FrameRequest): Promise<Frame | null> | Frame | null;
  /**
   * Which stage of the progressive refinement a frame is (refinement.ts). Absent, or
   * undefined for a frame: the frame is full quality and nothing more follows.
   */
  refinement?(frame: Frame): Refinement | undefined;
  /**
   * For a widget that does not draw with the page's shared device (the exercise grades
   * on a device of its own and checks WebGPU itself): the base calls this instead of
   * choosing a backend, and shows no backend notice of its own.
   */
  renderWithoutBackend?(): Promise<Frame | null>;
  /** The sentence after "WebGPU is not available (reason)." while drawing on the CPU. */
  readonly cpuNotice?: string;
  /** Draws what the readouts do not: plots, accessible descriptions of the canvases. */
  show?(frame: Frame, backend: FrameBackend): void;
  /** Draws the parts that draw on their own schedule before printing (see WidgetElement.drawForPrint). */
  drawForPrint?(): Promise<void>;
  /**
   * Called after the reader set a parameter through its control (not by a preset or a
   * link): a view whose parameters are linked sets the others with context.setValue
   * (e.g. choosing a material fills in its coefficients; editing one makes it "manual").
   */
  valueChanged?(name: string): void;
  /** Called when the widget switches to the CPU (device loss, a failed GPU frame): stop GPU jobs. */
  onCpuFallback?(reason: string): void;
  /** Releases the GPU renderer's resources (device loss, destroy). */
  destroyRenderer?(renderer: Renderer): void;
  /** The widget left the page (it may come back: a move); save what must not be lost. */
  onDisconnected?(): void;
  /** Stops the view's own work when the widget is destroyed (timers, workers, listeners). */
  destroy?(): void;
}

/**
 * What a widget.ts load() resolves to: a view factory (the widget is built by the
 * base from its definition), or, while a widget is being ported, its old element
 * class (it keeps its own shell code and is defined under the definition's name).
 */
export type WidgetModule<Frame> =
  { createView(context: ViewContext): WidgetView<Frame> } | { element: CustomElementConstructor };

/** Parameter values as a view reads them (re-exported for views' convenience). */
export type { ParameterValues };
