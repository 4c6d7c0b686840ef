// <sb-translucent-render>: a translucent sphere rendered three ways (chapter 11). Left, a
// Lambertian surface with the material's total diffuse reflectance R_d; middle, the dipole
// BSSRDF by Jensen & Buhler's two-pass hierarchical integration (irradiance samples on the
// sphere, an octree built in TypeScript, the gather on the GPU with the threshold ε); right,
// volumetric path tracing of the same sphere as the reference, accumulated progressively
// within a time budget per step, cancellable, with its per-pixel standard error. Each picture
// shows its GPU time and its error against the reference, with the reference's noise variance
// subtracted so that a young reference does not inflate it; an ε sweep plots the gather's error
// against its time; the middle picture can show the irradiance samples or the octree cut of a
// selected pixel (click it, or focus the picture and use the arrow keys). Without WebGPU the
// float64 twins draw the first two at reduced size and the reference is not run.
import { BackendChooser, gpuFailureReason, type Backend } from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel, type GpuTiming } from '../base/imageKernel.ts';
import { imageFigure, imagePanel } from '../base/imagePanel.ts';
import { ReadoutList } from '../base/readoutList.ts';
import { SweepControls, type SweepPoint } from '../base/sweep.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { findMaterial } from '../../subsurface/materials.ts';
import {
  buildOctree,
  dipolesOf,
  gatherCpu,
  imageError,
  interiorMask,
  irradianceSamples,
  renderDiffuseCpu,
  renderGatherCpu,
  visiblePoint,
  type Octree,
  type OctreeNode,
  type TranslucentScene,
} from '../../subsurface/translucent.ts';
import { PathAccumulator, TranslucentKernels } from '../../subsurface/translucentKernels.ts';
import { TRANSLUCENT_RENDER } from './schema.ts';
import {
  epsilonOf,
  errorAgainstNoisyReference,
  paintImage,
  referenceKey,
  sampleCountOf,
  sceneFromValues,
  type NoisyReferenceError,
} from './model.ts';

/** A progressive step of the path tracer aims at this much GPU time. */
const STEP_BUDGET_MS = 120;
/** Largest image side the CPU fallback draws. */
const CPU_SIZE = 40;

const READOUT_ROWS = [
  ['diffuse-time', 'Lambert: time'],
  ['diffuse-error', 'Lambert: relative RMSE (noise-corrected) · mean error'],
  ['gather-time', 'BSSRDF gather: time'],
  ['gather-error', 'BSSRDF: relative RMSE (noise-corrected) · mean error'],
  ['gather-exact', 'BSSRDF gather vs direct sum (ε = 0)'],
  ['nodes-visited', 'Nodes visited per pixel (mean)'],
  ['octree', 'Irradiance samples · octree nodes'],
  ['pixel', 'Selected pixel: nodes visited · cut'],
  ['pixel-values', 'Selected pixel: Lambert · BSSRDF · reference ± SE (mean of R, G, B)'],
  ['path-spp', 'Path tracing: samples per pixel'],
  ['path-time', 'Path tracing: time'],
  ['path-se', 'Reference noise (RMS standard error)'],
  ['path-capped', 'Walks stopped by the cap'],
] as const;

function preset(name: string, extra: Record<string, number> = {}): Preset {
  return { label: findMaterial(name)!.label, values: { material: name, ...extra } };
}

const percent = (x: number): string =>
  Number.isFinite(x) ? `${x >= 0 ? '+' : '−'}${formatNumber(Math.abs(100 * x), 3)}%` : '—';
/**
 * An error against the path-traced reference, its noise variance subtracted (model.ts,
 * errorAgainstNoisyReference). While the subtracted noise is not small next to the error
 * (over ¼ of it) the estimate is itself noisy, so it is marked ≈ and the noise that was
 * subtracted is named; the label says "noise-corrected".
 */
const errorText = (e: NoisyReferenceError | null): string => {
  if (!e) return '— (no reference yet)';
  const noise = `±${formatNumber(100 * e.referenceNoise, 2)}%`;
  if (e.belowNoise) return `below the reference noise (${noise}) · ${percent(e.meanError)}`;
  const young = e.referenceNoise > e.relativeRmse / 4;
  const value = `${formatNumber(100 * e.relativeRmse, 3)}% · ${percent(e.meanError)}`;
  return young ? `≈ ${value} (ref. noise ${noise})` : value;
};

interface OctreeState {
  key: string;
  octree: Octree;
  buildMs: number;
}

interface ReferenceState {
  key: string;
  accumulator: PathAccumulator;
  target: number;
  timing: string;
}

export class TranslucentRenderElement extends WidgetElement {
  protected readonly entry = TRANSLUCENT_RENDER;
  protected override presets: readonly Preset[] = [
    preset('skin1'),
    preset('marble'),
    preset('ketchup'),
    preset('wholemilk'),
    preset('skin1', { radius: 2 }),
    preset('apple'),
  ];

  private canvases: HTMLCanvasElement[] = [];
  private overlay: SVGSVGElement | null = null;
  private readouts: ReadoutList | null = null;
  private sweep: SweepControls | null = null;
  private runButton: HTMLButtonElement | null = null;
  private cancelButton: HTMLButtonElement | null = null;
  private progress: HTMLProgressElement | null = null;
  private status: HTMLElement | null = null;
  private octreeState: OctreeState | null = null;
  private reference: ReferenceState | null = null;
  private referenceToken = 0;
  private running = false;
  /** Whether the last render ran on the CPU twins, where no reference is ever traced. */
  private cpuOnly = false;
  private lastGather: {
    image: Float32Array;
    visited: Float32Array;
    exact: Float32Array | null;
  } | null = null;
  private lastDiffuse: Float32Array | null = null;
  private scene: TranslucentScene | null = null;
  private exact: { key: string; image: Float32Array; milliseconds: number } | null = null;
  /** The selected pixel (column, row) of the BSSRDF picture. */
  private selected: [number, number] | null = null;
  private readonly backends = new BackendChooser<TranslucentKernels>(
    (gpu: GpuContext) => new TranslucentKernels(gpu.device, STATIC_KERNELS),
    (reason) => {
      this.cancelReference(`stopped: ${reason}`);
      this.sweep?.cancel('stopped: the GPU was lost');
      this.scheduleRender();
    },
  );

  protected buildStage(stage: HTMLElement): void {
    const make = (label: string): HTMLCanvasElement => {
      const canvas = document.createElement('canvas');
      canvas.className = 'sb-canvas';
      canvas.setAttribute('role', 'img');
      canvas.setAttribute('aria-label', label);
      canvas.width = 64;
      canvas.height = 64;
      return canvas;
    };
    this.canvases = [
      make('The sphere as a Lambertian surface'),
      make('The sphere with the dipole BSSRDF, Jensen–Buhler gather'),
      make('The sphere by volumetric path tracing (reference)'),
    ];
    const diffuse = imagePanel(this.canvases[0]!, 'Lambert, albedo = dipole Rd');
    const bssrdf = imagePanel(this.canvases[1]!, 'Dipole BSSRDF, octree gather');
    const path = imagePanel(this.canvases[2]!, 'Path tracing (reference)');
    // The BSSRDF picture holds an SVG overlay (samples or cut) and takes clicks and arrow keys.
    const holder = document.createElement('div');
    holder.className = 'sb-tr-holder';
    holder.tabIndex = 0;
    holder.setAttribute('role', 'group');
    holder.setAttribute(
      'aria-label',
      'Dipole BSSRDF picture: click a pixel or use the arrow keys to show the octree cut that pixel uses',
    );
    this.overlay = document.createElementNS('http://www.w3.org/2000/svg', 'svg');
    this.overlay.classList.add('sb-tr-overlay');
    this.overlay.setAttribute('aria-hidden', 'true');
    bssrdf.panel.insertBefore(holder, bssrdf.panel.firstChild);
    holder.append(this.canvases[1]!, this.overlay);
    holder.addEventListener('click', (event) => {
      const rect = holder.getBoundingClientRect();
      const size = this.scene?.size ?? 64;
      const i = Math.floor(((event.clientX - rect.left) / rect.width) * size);
      const j = Math.floor(((event.clientY - rect.top) / rect.height) * size);
      this.selectPixel(i, j);
    });
    holder.addEventListener('keydown', (event) => {
      const step: Record<string, [number, number]> = {
        ArrowLeft: [-1, 0],
        ArrowRight: [1, 0],
        ArrowUp: [0, -1],
        ArrowDown: [0, 1],
      };
      const move = step[event.key];
      if (!move) return;
      event.preventDefault();
      const size = this.scene?.size ?? 64;
      const [i, j] = this.selected ?? [Math.floor(size / 2), Math.floor(size / 2)];
      const stride = event.shiftKey ? 8 : 1;
      this.selectPixel(i + stride * move[0], j + stride * move[1]);
    });
    stage.appendChild(imageFigure(diffuse.panel, bssrdf.panel, path.panel));

    const controls = document.createElement('div');
    controls.className = 'sb-sweep sb-tr-path';
    this.runButton = document.createElement('button');
    this.runButton.type = 'button';
    this.runButton.className = 'sb-button';
    this.runButton.textContent = 'Continue path tracing';
    this.runButton.addEventListener('click', () => void this.continueReference());
    this.cancelButton = document.createElement('button');
    this.cancelButton.type = 'button';
    this.cancelButton.className = 'sb-button';
    this.cancelButton.textContent = 'Cancel';
    this.cancelButton.disabled = true;
    this.cancelButton.addEventListener('click', () => this.cancelReference('cancelled'));
    this.progress = document.createElement('progress');
    this.progress.max = 1;
    this.progress.value = 0;
    this.progress.setAttribute('aria-label', 'Path tracing progress');
    this.status = document.createElement('span');
    this.status.className = 'sb-tr-status';
    this.status.setAttribute('role', 'status');
    controls.append(this.runButton, this.cancelButton, this.progress, this.status);
    stage.appendChild(controls);

    this.sweep = new SweepControls(
      stage,
      this,
      {
        name: '1/ε',
        buttonText: 'Sweep ε',
        hint: 'Sweep ε from 1 to 1/256: the gather’s error against the direct sum (ε = 0) falls as its time grows, while its error against the path-traced reference levels off at the dipole’s own model error.',
        color: '#3d6fd6',
        points: [1, 2, 4, 8, 16, 32, 64, 128, 256],
        errorName: 'relative RMSE',
      },
      () => void this.runSweep(),
    );
  }

  protected buildReadout(readout: HTMLElement): void {
    this.readouts = new ReadoutList(readout, READOUT_ROWS);
  }

  private set(key: string, text: string, state?: 'ok' | 'bad'): void {
    this.readouts?.set(key, text, state);
  }

  private octreeFor(scene: TranslucentScene, count: number): OctreeState {
    const key = [scene.radius, scene.eta, ...scene.toLight, ...scene.sigmaA, count].join('|');
    if (this.octreeState?.key === key) return this.octreeState;
    const start = performance.now();
    const octree = buildOctree(irradianceSamples(scene, count), scene.radius);
    this.octreeState = { key, octree, buildMs: performance.now() - start };
    return this.octreeState;
  }

  protected async render(): Promise<void> {
    const backend = await this.backends.choose();
    const values = this.values;
    const scene = sceneFromValues(values);
    this.cpuOnly = backend.kind === 'cpu';
    if (backend.kind === 'cpu') scene.size = Math.min(scene.size, CPU_SIZE);
    this.scene = scene;
    const state = this.octreeFor(scene, sampleCountOf(values));
    const epsilon = epsilonOf(values);
    const exposure = Number(values['exposure']);
    let cost: string;
    if (backend.kind === 'gpu') {
      try {
        const diffuse = await backend.renderer.diffuse(scene);
        const gather = await backend.renderer.gather(scene, state.octree, epsilon);
        // The direct sum does not depend on ε: computed once per octree and image size.
        const exactKey = `${state.key}|${scene.size}`;
        if (this.exact?.key !== exactKey)
          this.exact = {
            key: exactKey,
            ...(await backend.renderer.gather(scene, state.octree, 0)),
          };
        const exact = this.exact;
        this.lastDiffuse = diffuse.image;
        this.lastGather = { image: gather.image, visited: gather.visited, exact: exact.image };
        this.set(
          'diffuse-time',
          `${formatMilliseconds(diffuse.milliseconds)} (${timingLabel(diffuse.timing as GpuTiming)})`,
        );
        this.set(
          'gather-time',
          `${formatMilliseconds(gather.milliseconds)} (ε = ${formatNumber(epsilon, 3)}; direct sum ${formatMilliseconds(exact.milliseconds)})`,
        );
        this.recordFrameCost(gather.milliseconds, gather.timing);
        cost = `WebGPU (${backend.gpu.adapterDescription}): ${scene.size}² pixels; octree of ${state.octree.nodes.length} nodes built on the CPU in ${formatMilliseconds(state.buildMs)}.`;
      } catch (error) {
        this.backends.useCpu(gpuFailureReason(error));
        this.cancelReference('stopped: the GPU path failed');
        this.scheduleRender();
        return;
      }
      this.clearNotice('backend');
    } else {
      const start = performance.now();
      this.lastDiffuse = renderDiffuseCpu(scene);
      const middle = performance.now();
      const gather = renderGatherCpu(scene, state.octree, epsilon);
      const end = performance.now();
      this.lastGather = { image: gather.image, visited: gather.visited, exact: null };
      this.set('diffuse-time', `${formatMilliseconds(middle - start)} (CPU wall time)`);
      this.set('gather-time', `${formatMilliseconds(end - middle)} (CPU wall time)`);
      this.recordFrameCost(end - middle, 'cpu');
      this.showCpuFallbackNotice(
        backend.reason,
        `Showing the float64 twins of the Lambertian and BSSRDF pictures at ${scene.size}² pixels; the path-traced reference needs WebGPU and is not run.`,
      );
      cost = `CPU fallback (float64 twin): ${scene.size}² pixels, octree of ${state.octree.nodes.length} nodes built in ${formatMilliseconds(state.buildMs)}.`;
    }
    paintImage(this.canvases[0]!, this.lastDiffuse, scene.size, exposure);
    paintImage(this.canvases[1]!, this.lastGather.image, scene.size, exposure);
    const mask = interiorMask(scene);
    let visitedSum = 0;
    let visitedCount = 0;
    mask.forEach((inside, p) => {
      if (!inside) return;
      visitedSum += this.lastGather!.visited[p]!;
      visitedCount += 1;
    });
    this.set('nodes-visited', formatNumber(visitedSum / Math.max(visitedCount, 1), 4));
    this.set('octree', `${state.octree.samples.count} · ${state.octree.nodes.length}`);
    if (this.lastGather.exact) {
      const e = imageError(this.lastGather.image, this.lastGather.exact, mask);
      this.set('gather-exact', `${formatNumber(100 * e.relativeRmse, 3)}% RMSE`);
    } else {
      this.set('gather-exact', '—');
    }
    if (this.readouts) this.readouts.cost.textContent = cost;

    if (backend.kind === 'gpu') {
      const key = referenceKey(values);
      const target = 2 ** Number(values['spp']);
      if (this.reference?.key !== key) {
        this.cancelReference('restarted');
        this.reference = {
          key,
          accumulator: new PathAccumulator(scene.size * scene.size),
          target,
          timing: '',
        };
        void this.continueReference();
      } else if (this.reference.target !== target) {
        this.reference.target = target;
        if (!this.running && this.reference.accumulator.samples < target)
          void this.continueReference();
      }
    } else {
      this.set('path-spp', 'needs WebGPU');
      if (this.status) this.status.textContent = 'The path-traced reference needs WebGPU.';
      if (this.runButton) this.runButton.disabled = true;
    }
    this.showReference();
    this.drawOverlay();
  }

  /** Paints the reference and updates every error readout from the current accumulation. */
  private showReference(): void {
    const scene = this.scene;
    const reference = this.reference;
    if (!scene) return;
    const exposure = Number(this.values['exposure']);
    const mask = interiorMask(scene);
    if (
      !reference ||
      reference.accumulator.samples === 0 ||
      reference.accumulator.pixels !== scene.size * scene.size
    ) {
      const blank = this.canvases[2]!.getContext('2d');
      if (blank) {
        this.canvases[2]!.width = scene.size;
        this.canvases[2]!.height = scene.size;
        blank.fillStyle = '#000';
        blank.fillRect(0, 0, scene.size, scene.size);
      }
      const missing = this.cpuOnly ? '— (the reference needs WebGPU)' : errorText(null);
      this.set('diffuse-error', missing);
      this.set('gather-error', missing);
      if (!reference) return;
    }
    const acc = reference.accumulator;
    if (acc.samples === 0) return;
    const mean = acc.mean();
    const se = acc.standardError();
    paintImage(this.canvases[2]!, mean, scene.size, exposure);
    if (acc.samples < 2) {
      // One sample per pixel has no standard error, so its noise can be neither
      // subtracted nor shown: an error against it would be mostly that noise.
      const young = '— (waiting for a second reference sample per pixel)';
      this.set('diffuse-error', young);
      this.set('gather-error', young);
    } else if (this.lastDiffuse)
      this.set(
        'diffuse-error',
        errorText(errorAgainstNoisyReference(this.lastDiffuse, mean, se, mask)),
      );
    if (acc.samples >= 2 && this.lastGather)
      this.set(
        'gather-error',
        errorText(errorAgainstNoisyReference(this.lastGather.image, mean, se, mask)),
      );
    let squares = 0;
    let sum = 0;
    let n = 0;
    mask.forEach((inside, p) => {
      if (!inside) return;
      for (let c = 0; c < 3; c++) {
        squares += Number.isFinite(se[3 * p + c]!) ? se[3 * p + c]! ** 2 : 0;
        sum += mean[3 * p + c]!;
        n += 1;
      }
    });
    this.set('path-spp', `${acc.samples} of ${reference.target}`);
    this.set(
      'path-time',
      `${formatMilliseconds(acc.milliseconds)} (${reference.timing ? timingLabel(reference.timing as GpuTiming) : '…'})`,
    );
    this.set(
      'path-se',
      acc.samples > 1
        ? `${formatNumber((100 * Math.sqrt(squares / n)) / (sum / n), 3)}% of the mean`
        : '—',
    );
    this.set('path-capped', String(acc.capped), acc.capped > 0 ? 'bad' : 'ok');
    if (this.selected) this.showPixelValues(this.selected[1] * scene.size + this.selected[0]);
    if (this.progress) this.progress.value = Math.min(acc.samples / reference.target, 1);
  }

  /** Runs the path tracer until the target, in steps of about STEP_BUDGET_MS, yielding between. */
  private async continueReference(): Promise<void> {
    const reference = this.reference;
    if (!reference || this.running) return;
    const backend = await this.backends.choose();
    if (backend.kind !== 'gpu') return;
    const token = ++this.referenceToken;
    this.running = true;
    this.setRunning(true);
    let perStep = 1;
    try {
      while (reference.accumulator.samples < reference.target) {
        if (token !== this.referenceToken || reference !== this.reference) return;
        const scene = this.scene;
        if (!scene || scene.size * scene.size !== reference.accumulator.pixels) return;
        const samples = Math.min(perStep, reference.target - reference.accumulator.samples);
        const batch = await backend.renderer.pathBatch(scene, {
          samples,
          offset: reference.accumulator.samples,
          seed: Number(this.values['seed']),
        });
        if (token !== this.referenceToken || reference !== this.reference) return;
        reference.accumulator.add(batch);
        reference.timing = batch.timing;
        // Aim the next step at the budget from this one's time per sample.
        const perSample = batch.milliseconds / samples;
        perStep = Math.max(
          1,
          Math.min(256, Math.floor(STEP_BUDGET_MS / Math.max(perSample, 1e-3))),
        );
        if (this.status)
          this.status.textContent = `Path tracing: ${reference.accumulator.samples} of ${reference.target} samples per pixel…`;
        this.showReference();
        await new Promise((resolve) => setTimeout(resolve, 0));
      }
      if (this.status)
        this.status.textContent = `Path tracing done: ${reference.accumulator.samples} samples per pixel.`;
    } catch (error) {
      if (this.status)
        this.status.textContent = `Path tracing failed: ${error instanceof Error ? error.message : String(error)}`;
    } finally {
      if (token === this.referenceToken) {
        this.running = false;
        this.setRunning(false);
      }
    }
  }

  private cancelReference(message: string): void {
    this.referenceToken += 1;
    if (this.running && this.status) this.status.textContent = `Path tracing ${message}.`;
    this.running = false;
    this.setRunning(false);
  }

  private setRunning(on: boolean): void {
    if (this.cancelButton) this.cancelButton.disabled = !on;
    if (this.runButton) this.runButton.disabled = on;
    this.toggleAttribute('data-path-tracing', on);
  }

  private selectPixel(i: number, j: number): void {
    const size = this.scene?.size ?? 64;
    this.selected = [Math.min(Math.max(i, 0), size - 1), Math.min(Math.max(j, 0), size - 1)];
    this.drawOverlay();
  }

  /** The irradiance samples (coloured by E) or the selected pixel's octree cut, over the BSSRDF picture. */
  private drawOverlay(): void {
    const svg = this.overlay;
    const scene = this.scene;
    const state = this.octreeState;
    if (!svg || !scene || !state) return;
    const size = scene.size;
    svg.setAttribute('viewBox', `0 0 ${size} ${size}`);
    svg.replaceChildren();
    const toPixel = (p: readonly number[]): [number, number] => [
      ((p[0]! / scene.view + 1) / 2) * size,
      ((1 - p[1]! / scene.view) / 2) * size,
    ];
    const circle = (x: number, y: number, r: number, cls: string, fill?: string): void => {
      const c = document.createElementNS('http://www.w3.org/2000/svg', 'circle');
      c.setAttribute('cx', x.toFixed(2));
      c.setAttribute('cy', y.toFixed(2));
      c.setAttribute('r', r.toFixed(2));
      c.setAttribute('class', cls);
      if (fill) c.setAttribute('fill', fill);
      svg.appendChild(c);
    };
    const overlay = String(this.values['overlay']);
    const { samples } = state.octree;
    if (overlay === 'samples') {
      let largest = 0;
      samples.irradiance.forEach((e) => (largest = Math.max(largest, e)));
      for (let k = 0; k < samples.count; k++) {
        const z = samples.positions[3 * k + 2]!;
        if (z <= 0) continue; // the far side is hidden
        const [x, y] = toPixel([samples.positions[3 * k]!, samples.positions[3 * k + 1]!]);
        const e = samples.irradiance[k]! / (largest || 1);
        circle(
          x,
          y,
          Math.max(0.35, size / 220),
          'sb-tr-sample',
          `rgb(${Math.round(40 + 215 * e)}, ${Math.round(60 + 160 * e)}, ${Math.round(200 - 170 * e)})`,
        );
      }
      this.set('pixel', `${samples.count} samples (dots, colour = E; far side hidden)`);
      return;
    }
    const [i, j] = this.selected ?? this.defaultPixel(scene);
    this.selected = [i, j];
    const x = visiblePoint(scene, i, j);
    if (!x) {
      this.set('pixel', `(${i}, ${j}) is off the sphere`);
      circle(i + 0.5, j + 0.5, 1.2, 'sb-tr-pixel');
      return;
    }
    const cut: OctreeNode[] = [];
    const result = gatherCpu(state.octree, dipolesOf(scene), x, epsilonOf(this.values), cut);
    const leafTerms = result.terms - cut.length;
    if (overlay === 'cut') {
      for (const node of cut) {
        if (node.centroid[2] <= 0) continue;
        const [cx, cy] = toPixel(node.centroid);
        const r = (Math.sqrt(node.area / Math.PI) / (2 * scene.view)) * size;
        circle(cx, cy, r, 'sb-tr-node');
      }
    }
    circle(i + 0.5, j + 0.5, Math.max(1.2, size / 60), 'sb-tr-pixel');
    this.set(
      'pixel',
      `(${i}, ${j}): ${result.visited} nodes visited · ${cut.length} whole + ${leafTerms} single samples`,
    );
    this.dataset['pixelVisited'] = String(result.visited);
    this.showPixelValues(j * size + i);
  }

  /** The selected pixel in the three pictures, with the reference's standard error there. */
  private showPixelValues(p: number): void {
    const average = (image: ArrayLike<number> | null | undefined): number =>
      image ? (image[3 * p]! + image[3 * p + 1]! + image[3 * p + 2]!) / 3 : NaN;
    const acc = this.reference?.accumulator;
    const pixels = (this.scene?.size ?? 0) ** 2;
    let reference = '—';
    if (acc && acc.samples > 1 && acc.pixels === pixels) {
      const se = acc.standardError();
      const seMean = Math.hypot(se[3 * p]!, se[3 * p + 1]!, se[3 * p + 2]!) / 3;
      reference = `${formatNumber(average(acc.mean()), 3)} ± ${formatNumber(seMean, 2)}`;
    }
    this.set(
      'pixel-values',
      `${formatNumber(average(this.lastDiffuse), 3)} · ${formatNumber(average(this.lastGather?.image), 3)} · ${reference}`,
    );
  }

  /** The pixel where the light is strongest on the sphere, half-way to its rim. */
  private defaultPixel(scene: TranslucentScene): [number, number] {
    const l = scene.toLight;
    const planar = Math.hypot(l[0], l[1]) || 1;
    const x = (0.5 * scene.radius * l[0]) / planar;
    const y = (0.5 * scene.radius * l[1]) / planar;
    return [
      Math.floor(((x / scene.view + 1) / 2) * scene.size),
      Math.floor(((1 - y / scene.view) / 2) * scene.size),
    ];
  }

  private async runSweep(): Promise<void> {
    await this.sweep?.runSeries(async () => {
      const backend: Backend<TranslucentKernels> = await this.backends.choose();
      const scene = this.scene ?? sceneFromValues(this.values);
      const state = this.octreeFor(scene, sampleCountOf(this.values));
      const mask = interiorMask(scene);
      const exact =
        backend.kind === 'gpu'
          ? (await backend.renderer.gather(scene, state.octree, 0)).image
          : renderGatherCpu(scene, state.octree, 0).image;
      const measure = async (
        inverse: number,
      ): Promise<{ image: Float32Array; milliseconds: number }> => {
        if (backend.kind === 'gpu')
          return backend.renderer.gather(scene, state.octree, 1 / inverse);
        const start = performance.now();
        const image = renderGatherCpu(scene, state.octree, 1 / inverse).image;
        return { image, milliseconds: performance.now() - start };
      };
      const cache = new Map<number, { image: Float32Array; milliseconds: number }>();
      const run = async (
        inverse: number,
      ): Promise<{ image: Float32Array; milliseconds: number }> => {
        let r = cache.get(inverse);
        if (!r) {
          r = await measure(inverse);
          cache.set(inverse, r);
        }
        return r;
      };
      return {
        series: [
          { label: 'vs direct sum (ε = 0)', color: '#3d6fd6' },
          { label: 'vs path-traced reference', color: '#d9473f', dash: [6, 4] },
        ],
        measure: async (series: number, inverse: number): Promise<Omit<SweepPoint, 'n'>> => {
          const r = await run(inverse);
          if (series === 0)
            return {
              rmse: imageError(r.image, exact, mask).relativeRmse,
              milliseconds: r.milliseconds,
            };
          // Against the reference, as in the readouts: its noise variance subtracted.
          const acc = this.reference?.accumulator;
          const error =
            acc && acc.samples > 0 && acc.pixels === scene.size ** 2
              ? errorAgainstNoisyReference(r.image, acc.mean(), acc.standardError(), mask)
                  .relativeRmse
              : NaN;
          return { rmse: error, milliseconds: r.milliseconds };
        },
        finish: (points: readonly (readonly SweepPoint[])[]) => {
          const first = points[0]?.[0];
          const last = points[0]?.at(-1);
          return first && last
            ? `ε = 1: ${formatNumber(100 * first.rmse, 3)}% in ${formatMilliseconds(first.milliseconds)}; ε = 1/256: ${formatNumber(100 * last.rmse, 3)}% in ${formatMilliseconds(last.milliseconds)}`
            : 'no points';
        },
        failed: () => undefined,
      };
    });
  }
}

export function defineTranslucentRender(): void {
  if (!customElements.get('sb-translucent-render'))
    customElements.define('sb-translucent-render', TranslucentRenderElement);
}
