// The 3D view of <sb-hg-lobe>: a canvas that shows the lobe r(θ)·ω in space, drawn
// by the GPU (lobe3dGpu.ts) or, on the CPU fallback, as the twin's wireframe
// (lobe3dCpu.ts), in a worker on the canvas's OffscreenCanvas where the browser
// has one (wireframeWorker.ts), else in the page. It turns with a pointer drag or the arrow keys (Home resets),
// follows its CSS size and the device pixel ratio, and redraws only when the
// lobe, the view or the size changed. Labels for the beam and the forward
// direction are laid over the canvas where the camera projects them.
import type { GpuContext } from '../../gpu/device.ts';
import { formatNumber } from '../base/format.ts';
import { hgEval } from '../../reference/phase.ts';
import {
  DEFAULT_ORBIT,
  clampOrbit,
  orbitCamera,
  packView,
  project,
  sceneBounds,
  type Orbit,
  type Vec3,
} from './lobe3d.ts';
import { drawLobeWireframe } from './lobe3dCpu.ts';
import { HgLobe3dGpu } from './lobe3dGpu.ts';
import { WireframeWorker } from './wireframeWorker.ts';
import type { HgLobeInputs } from './model.ts';

/** Radians per CSS pixel of drag, and per arrow-key press (10°). */
const DRAG_RATE = 0.01;
const KEY_STEP = (10 * Math.PI) / 180;
/** Largest backing store, so presentation mode on a 4K screen stays cheap. */
const MAX_PIXELS = 2400 * 1400;

const COMPARE_NAMES = { none: '', isotropic: 'isotropic sphere', rayleigh: 'Rayleigh peanut' };

export interface LobeScene {
  inputs: HgLobeInputs;
  /** The polar plot's log floor, so both pictures share one radius mapping. */
  logFloor: number;
}

export class LobeView {
  /** The figure to put in the stage: the canvas and its labels. */
  readonly figure: HTMLElement;
  private canvas: HTMLCanvasElement;
  private readonly labels: HTMLElement;
  private orbit: Orbit = DEFAULT_ORBIT;
  private scene: LobeScene | null = null;
  private gpu: HgLobe3dGpu | null = null;
  /** The CPU wireframe's worker, which owns the canvas once handed over (null: drawn in the page). */
  private wireframe: WireframeWorker | null = null;
  /** The backing store's size: a canvas handed to the worker cannot be resized from the page. */
  private size = { width: 960, height: 540 };
  /** The canvas's CSS width, from the resize observer (0 until it has reported). */
  private cssWidth = 0;
  private destroyed = false;
  /** No backend yet: nothing is drawn, so the canvas can still take either context. */
  private mode: 'none' | 'gpu' | 'cpu' = 'none';
  private frameRequested = false;
  private drawing = false;
  private redraw = false;
  private visible = false;
  /** A change arrived while off screen: draw when the figure scrolls into view. */
  private stale = false;
  private readonly visibility: IntersectionObserver;
  private drag: { id: number; x: number; y: number } | null = null;
  private readonly resizeObserver: ResizeObserver;

  /** @param onError called when a GPU draw fails (the widget then falls back to the CPU). */
  constructor(private readonly onError: (error: unknown) => void) {
    this.figure = document.createElement('div');
    this.figure.className = 'sb-hg-figure sb-hg-3d-figure';
    this.figure.dataset['drawn'] = '0';
    this.canvas = this.createCanvas();
    this.labels = document.createElement('div');
    this.labels.className = 'sb-hg-labels';
    this.labels.setAttribute('aria-hidden', 'true');
    this.figure.append(this.canvas, this.labels);
    this.resizeObserver = new ResizeObserver((entries) => this.onResize(entries));
    this.observe();
    this.visibility = new IntersectionObserver((entries) => {
      this.visible = entries.some((entry) => entry.isIntersecting);
      if (this.visible && this.stale) this.schedule();
    });
    this.visibility.observe(this.figure);
    // Listeners on the figure survive the canvas being replaced (device loss).
    this.figure.addEventListener('pointerdown', (event) => this.onPointerDown(event));
    this.figure.addEventListener('pointermove', (event) => this.onPointerMove(event));
    this.figure.addEventListener('pointerup', (event) => this.onPointerUp(event));
    this.figure.addEventListener('pointercancel', (event) => this.onPointerUp(event));
    this.figure.addEventListener('keydown', (event) => this.onKey(event));
  }

  private createCanvas(): HTMLCanvasElement {
    const canvas = document.createElement('canvas');
    canvas.className = 'sb-canvas sb-hg-3d';
    canvas.tabIndex = 0;
    canvas.setAttribute('role', 'img');
    canvas.setAttribute('aria-label', '3D view of the phase function lobe');
    canvas.width = this.size.width;
    canvas.height = this.size.height;
    return canvas;
  }

  private observe(): void {
    try {
      this.resizeObserver.observe(this.canvas, { box: 'device-pixel-content-box' });
    } catch {
      this.resizeObserver.observe(this.canvas);
    }
  }

  /** Draws with the GPU from now on. */
  useGpu(gpu: GpuContext): void {
    if (this.mode === 'gpu') return;
    this.mode = 'gpu';
    this.gpu = new HgLobe3dGpu(gpu, this.canvas);
  }

  /** Draws the CPU wireframe from now on, on a fresh canvas (a WebGPU canvas cannot become 2D). */
  useCpu(): void {
    // Every CPU frame of the widget says so; only the switch draws (a refinement stage
    // of the histogram does not change the lobe).
    if (this.mode === 'cpu') return;
    if (this.mode === 'gpu') {
      this.gpu?.destroy();
      this.gpu = null;
      this.replaceCanvas();
    }
    this.mode = 'cpu';
    // Drawn and rasterised in a worker: in the page a picture took 20–120 ms of its
    // thread on a loaded two-core machine, the longest tasks of a slider drag (issue 23).
    this.wireframe = WireframeWorker.start(this.canvas);
    this.schedule();
  }

  /** A fresh canvas in the old one's place (one with a context cannot take another). */
  private replaceCanvas(): void {
    const fresh = this.createCanvas();
    const focused = document.activeElement === this.canvas;
    this.resizeObserver.unobserve(this.canvas);
    this.canvas.replaceWith(fresh);
    this.canvas = fresh;
    this.observe();
    if (focused) fresh.focus();
  }

  get backend(): 'none' | 'gpu' | 'cpu' {
    return this.mode;
  }

  /** Shows a new lobe (g, scale or comparison changed). */
  show(scene: LobeScene): void {
    this.scene = scene;
    this.schedule();
  }

  private onResize(entries: ResizeObserverEntry[]): void {
    const entry = entries[0];
    if (!entry) return;
    const device = entry.devicePixelContentBoxSize?.[0];
    let width = device ? device.inlineSize : Math.round(entry.contentRect.width * devicePixelRatio);
    let height = device
      ? device.blockSize
      : Math.round(entry.contentRect.height * devicePixelRatio);
    if (width < 2 || height < 2) return;
    this.cssWidth = entry.contentRect.width;
    const shrink = Math.min(1, Math.sqrt(MAX_PIXELS / (width * height)));
    width = Math.max(1, Math.floor(width * shrink));
    height = Math.max(1, Math.floor(height * shrink));
    if (width === this.size.width && height === this.size.height) return;
    this.size = { width, height };
    // A canvas handed to the worker is resized there, with the next picture.
    if (!this.wireframe) {
      this.canvas.width = width;
      this.canvas.height = height;
    }
    this.schedule();
  }

  private turn(yaw: number, pitch: number): void {
    this.orbit = clampOrbit({ yaw: this.orbit.yaw + yaw, pitch: this.orbit.pitch + pitch });
    this.schedule();
  }

  private onPointerDown(event: PointerEvent): void {
    if (event.target !== this.canvas || event.button !== 0) return;
    this.drag = { id: event.pointerId, x: event.clientX, y: event.clientY };
    this.canvas.setPointerCapture(event.pointerId);
    this.canvas.focus({ preventScroll: true });
    event.preventDefault();
  }

  private onPointerMove(event: PointerEvent): void {
    if (!this.drag || event.pointerId !== this.drag.id) return;
    const dx = event.clientX - this.drag.x;
    const dy = event.clientY - this.drag.y;
    this.drag = { ...this.drag, x: event.clientX, y: event.clientY };
    // Dragging right turns the lobe right (the eye moves left); dragging up looks from higher.
    this.turn(-dx * DRAG_RATE, dy * DRAG_RATE);
  }

  private onPointerUp(event: PointerEvent): void {
    if (!this.drag || event.pointerId !== this.drag.id) return;
    this.drag = null;
    if (this.canvas.hasPointerCapture(event.pointerId))
      this.canvas.releasePointerCapture(event.pointerId);
  }

  private onKey(event: KeyboardEvent): void {
    if (event.target !== this.canvas || event.ctrlKey || event.metaKey || event.altKey) return;
    const steps: Record<string, [number, number]> = {
      ArrowLeft: [KEY_STEP, 0],
      ArrowRight: [-KEY_STEP, 0],
      ArrowUp: [0, KEY_STEP],
      ArrowDown: [0, -KEY_STEP],
    };
    const step = steps[event.key];
    if (step) {
      this.turn(step[0], step[1]);
    } else if (event.key === 'Home') {
      this.orbit = DEFAULT_ORBIT;
      this.schedule();
    } else {
      return;
    }
    event.preventDefault();
  }

  /** One draw on the next frame while visible; changes during a draw cause one more. */
  private schedule(): void {
    if (!this.scene || this.mode === 'none') return;
    if (!this.visible) {
      this.stale = true;
      return;
    }
    this.stale = false;
    if (this.drawing) {
      this.redraw = true;
      return;
    }
    if (this.frameRequested) return;
    this.frameRequested = true;
    requestAnimationFrame(() => {
      this.frameRequested = false;
      void this.draw();
    });
  }

  /**
   * Draws now, on screen or not, and waits for it (printing: a view that never
   * scrolled into view has no picture to copy yet).
   */
  async drawNow(): Promise<void> {
    if (!this.scene || this.mode === 'none') return;
    while (this.drawing) await new Promise((resolve) => requestAnimationFrame(resolve));
    await this.draw();
  }

  private async draw(): Promise<void> {
    const scene = this.scene;
    if (!scene) return;
    this.drawing = true;
    this.redraw = false;
    const { inputs, logFloor } = scene;
    const bounds = sceneBounds(inputs, logFloor);
    const aspect = this.size.width / this.size.height;
    try {
      if (this.mode === 'gpu' && this.gpu) {
        const camera = orbitCamera(bounds, this.orbit, aspect);
        await this.gpu.draw(packView(inputs, logFloor, bounds, camera), inputs.compare !== 'none');
      } else if (this.wireframe) {
        try {
          await this.wireframe.draw(this.size, inputs, logFloor, this.orbit, this.pixelScale());
        } catch (error) {
          if (this.destroyed) return;
          // The worker failed (or could not start): draw in the page from now on, on a
          // fresh canvas, since the old one belongs to the worker.
          console.warn('hg-lobe: the wireframe worker failed; drawing in the page', error);
          this.wireframe.destroy();
          this.wireframe = null;
          this.replaceCanvas();
          drawLobeWireframe(this.canvas, inputs, logFloor, this.orbit, this.pixelScale());
        }
      } else {
        drawLobeWireframe(this.canvas, inputs, logFloor, this.orbit, this.pixelScale());
      }
      this.drawLabels(scene, bounds, aspect);
      this.describe(scene);
      this.figure.dataset['drawn'] = String(Number(this.figure.dataset['drawn'] ?? '0') + 1);
    } catch (error) {
      this.onError(error);
    } finally {
      this.drawing = false;
      if (this.redraw) this.schedule();
    }
  }

  /** Backing pixels per CSS pixel (line widths of the CPU wireframe). */
  private pixelScale(): number {
    // The observer's width, not clientWidth: reading that in a draw forced a layout of
    // the page, 5–22 ms of a drag's tasks on a loaded two-core machine (dragProfile).
    return this.cssWidth > 0 ? this.size.width / this.cssWidth : devicePixelRatio;
  }

  /** The beam and forward labels where the camera puts their points, in per cent of the canvas. */
  private drawLabels(
    scene: LobeScene,
    bounds: ReturnType<typeof sceneBounds>,
    aspect: number,
  ): void {
    const camera = orbitCamera(bounds, this.orbit, aspect);
    const at = (p: Vec3): { x: number; y: number } => {
      const { x, y } = project(camera.viewProjection, p, 100, 100);
      return { x: Math.min(Math.max(x, 2), 98), y: Math.min(Math.max(y, 6), 96) };
    };
    const label = (text: string, x: number, y: number, className: string): HTMLElement => {
      const span = document.createElement('span');
      span.className = className;
      span.textContent = text;
      span.style.left = `${x}%`;
      span.style.top = `${y}%`;
      return span;
    };
    // The beam's label sits over the middle of its shaft, clear of the canvas edge.
    const shaft = at([0.5 * (bounds.arrow.tailX + bounds.arrow.headBaseX), 0, 0]);
    const tail = { x: Math.min(Math.max(shaft.x, 12), 88), y: shaft.y };
    const forward = at([bounds.forwardExtent, 0, 0]);
    const other = COMPARE_NAMES[scene.inputs.compare];
    this.labels.replaceChildren(
      label('incident beam', tail.x, tail.y - 2, 'sb-hg-label sb-hg-label--centre'),
      label('θ = 0°', forward.x, forward.y - 2, 'sb-hg-label sb-hg-label--centre'),
      label(
        this.mode === 'gpu'
          ? `solid: Henyey–Greenstein${other ? ` · wireframe: ${other}` : ''}`
          : `CPU wireframe: Henyey–Greenstein${other ? ` · blue: ${other}` : ''}`,
        2,
        96,
        'sb-hg-label sb-hg-label--note',
      ),
      label(
        scene.inputs.scale === 'log' ? 'radius ∝ log₁₀ p' : 'radius ∝ p',
        2,
        8,
        'sb-hg-label sb-hg-label--note',
      ),
      label('drag or arrow keys to turn', 98, 8, 'sb-hg-label sb-hg-label--end sb-hg-label--note'),
    );
  }

  /** The canvas's accessible name: what the lobe looks like and how to turn it. */
  private describe(scene: LobeScene): void {
    const { g, scale, compare } = scene.inputs;
    const degrees = (radians: number): string => `${Math.round((radians * 180) / Math.PI)}°`;
    const other = COMPARE_NAMES[compare];
    const shape =
      g > 0
        ? 'points forward, along the beam'
        : g < 0
          ? 'points back, toward the source'
          : 'is a sphere';
    this.canvas.setAttribute(
      'aria-label',
      `3D view of the Henyey–Greenstein lobe for g = ${formatNumber(g, 3)} ` +
        `(${scale === 'log' ? 'radius ∝ log₁₀ p' : 'radius ∝ p'}): it ${shape}, ` +
        `${formatNumber(hgEval(g, 1), 3)} sr⁻¹ forward and ${formatNumber(hgEval(g, -1), 3)} sr⁻¹ back` +
        `${other ? `, inside or around the ${other} drawn as a wireframe` : ''}. ` +
        `Seen from azimuth ${degrees(this.orbit.yaw)}, elevation ${degrees(this.orbit.pitch)}; ` +
        `drag, or focus it and press the arrow keys, to turn it (Home resets).` +
        (this.mode === 'cpu' ? ' Drawn as a wireframe by the CPU fallback.' : ''),
    );
  }

  destroy(): void {
    this.destroyed = true;
    this.wireframe?.destroy();
    this.resizeObserver.disconnect();
    this.visibility.disconnect();
    this.gpu?.destroy();
  }
}
