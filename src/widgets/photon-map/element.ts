// <sb-photon-map>: photon mapping versus path tracing on a volume caustic (chapter 10).
// A glass ball focuses a small sun into a fog box. Each render traces N photons,
// sorts them into a uniform grid (cell = gather radius) and renders the volume
// radiance estimate along camera rays; path tracing then gets the same time
// (passes of PT_PASS_SPP paths per pixel until its accumulated time reaches the photon
// map's). Both images show their RMSE against a converged path-traced reference
// (public/photon-map/reference.bin, scripts/photon-map-reference.ts). The sweep plots
// error against time for three series: photon mapping over N = 4096·n at the current
// radius (its error stops falling once the bias of the radius dominates, so it gets
// no power law, only its plateau: the error at the largest N and its change over the
// last 4× N), progressive photon mapping with r = r₀ (N/N₀)^(−1/7) through the
// current (N₀, r₀) (chapter 10, "Bias versus variance": RMSE ∝ N^(−2/7), fitted vs N
// and vs time), and path tracing over 4·n paths per pixel (fitted vs time, t^−½).
// Without WebGPU the float64 twin renders a 32×24 image with at most
// CPU_MAX_PHOTONS photons and says so.
import type { GpuContext } from '../../gpu/device.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import { BackendChooser, type Backend, gpuFailureReason } from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { timingLabel } from '../base/imageKernel.ts';
import { imageCanvas, imageFigure, imagePanel, niceScale } from '../base/imagePanel.ts';
import { ReadoutList } from '../base/readoutList.ts';
import { SweepControls, type SweepPoint } from '../base/sweep.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import { pathTraceGpu, renderPhotonMapGpu } from './gpuBackend.ts';
import {
  CPU_SIZE,
  DEFAULT_INPUTS,
  GPU_SIZE,
  SCENE,
  add,
  buildGridCpu,
  cameraFrame,
  dot,
  downsample,
  gridFor,
  parseReference,
  pathTraceCpu,
  photonMapImageCpu,
  progressiveRadius,
  rmse,
  scale,
  sub,
  tracePhotonsCpu,
  type PhotonInputs,
  type PhotonReference,
} from './model.ts';
import { PHOTON_MAP } from './schema.ts';
import { summariseSweep } from './summary.ts';
import { siteUrl } from '../base/siteUrl.ts';

const READOUT_ROWS = [
  ['stored', 'Photons stored in the fog'],
  ['pm-time', 'Photon mapping time (trace, sort, gather)'],
  ['pm-error', 'Photon mapping RMSE vs reference (W/(m²·sr))'],
  ['pt-spp', 'Path tracing, paths per pixel in equal time'],
  ['pt-time', 'Path tracing time'],
  ['pt-error', 'Path tracing RMSE vs reference (W/(m²·sr))'],
  ['plateau', 'Sweep, fixed r: plateau'],
  ['progressive', 'Sweep, progressive r ∝ N^−1/7: RMSE ∝ N^p'],
  ['pt-rate', 'Sweep, path tracing: RMSE ∝ time^p'],
] as const;
const SWEEP_ROWS = ['plateau', 'progressive', 'pt-rate'] as const;

const VIEW_SIZE = { width: 256, height: 192 } as const;
const VIEW_PHOTONS = 16384;
const PT_PASS_SPP = 4;
/** The photon-map image's jittered rays per pixel. */
const GATHER_SAMPLES = 1;
const CPU_MAX_PHOTONS = 8192;
/** Paths per pixel the CPU path tracer stops at even if it has time left. */
const CPU_MAX_SPP = 4096;
const SWEEP_POINTS = [1, 2, 4, 8, 16, 32, 64] as const;
/** Mid-tone colours that read on the light and the dark page; the progressive curve is also dashed. */
const COLOURS = { pm: '#d9822b', ppm: '#9b72e0', pt: '#5b8def' } as const;
/** Photons per sweep step: N = SWEEP_PHOTONS·n. */
const SWEEP_PHOTONS = 4096;

interface Images {
  width: number;
  height: number;
  photonMap: Float64Array;
  pathTraced: Float64Array;
  pmMs: number;
  ptMs: number;
  ptSpp: number;
  stored: number;
  overflow: number;
  view: Float32Array;
  how: string;
  reference: Float64Array;
}

export function inputsFrom(values: Record<string, number | string>): PhotonInputs {
  return {
    ...DEFAULT_INPUTS,
    photons: Math.round(Number(values['photons'] ?? DEFAULT_INPUTS.photons)),
    radius: Number(values['radius'] ?? DEFAULT_INPUTS.radius),
  };
}

export class PhotonMapElement extends WidgetElement {
  protected readonly entry = PHOTON_MAP;
  protected override presets: readonly Preset[] = [
    { label: 'few photons, wide radius', values: { photons: 8192, radius: 0.1 } },
    { label: 'many photons, narrow radius', values: { photons: 262144, radius: 0.02 } },
    { label: 'default (N = 65536, r = 4 cm)', values: { photons: 65536, radius: 0.04 } },
  ];

  private viewCanvas: HTMLCanvasElement | null = null;
  private pmCanvas: HTMLCanvasElement | null = null;
  private ptCanvas: HTMLCanvasElement | null = null;
  private scaleTop: HTMLElement | null = null;
  private readouts: ReadoutList | null = null;
  private sweep: SweepControls | null = null;
  private reference: Promise<PhotonReference> | null = null;
  private code: Promise<string> | null = null;
  private readonly backends = new BackendChooser(
    (gpu: GpuContext) => gpu,
    () => {
      this.sweep?.cancel('stopped: the GPU was lost');
      this.scheduleRender();
    },
  );

  protected buildStage(stage: HTMLElement): void {
    this.viewCanvas = imageCanvas(
      'Stored photons projected into the camera',
      VIEW_SIZE.width,
      VIEW_SIZE.height,
    );
    this.viewCanvas.dataset['view'] = 'photons';
    this.pmCanvas = imageCanvas('Photon-mapped image', GPU_SIZE.width, GPU_SIZE.height);
    this.pmCanvas.dataset['view'] = 'photon-map';
    this.ptCanvas = imageCanvas('Path-traced image in equal time', GPU_SIZE.width, GPU_SIZE.height);
    this.ptCanvas.dataset['view'] = 'path-trace';
    // The images map radiance v to grey √(v/top), so the bar's midpoint is top/4.
    const greyScale = {
      gradient: 'linear-gradient(to right, #000, #fff)',
      low: '0 (square-root scale)',
      top: { readout: 'radiance-scale' },
    };
    const pm = imagePanel(this.pmCanvas, 'Photon mapping (volume radiance estimate)', greyScale);
    this.scaleTop = pm.top;
    stage.appendChild(
      imageFigure(
        imagePanel(
          this.viewCanvas,
          'Stored photons (orange: through the glass; blue: fog only). All carry ΔΦ = E·A/N.',
        ).panel,
        pm.panel,
        imagePanel(this.ptCanvas, 'Path tracing, same time').panel,
      ),
    );
    this.sweep = new SweepControls(
      stage,
      this,
      {
        name: 'n',
        buttonText: 'Run error-vs-time sweep',
        hint: 'Run the sweep to plot RMSE against time: photon mapping with N = 4096·n photons at the current radius, progressive photon mapping with the radius shrinking as N^(−1/7) from the current N and r, and path tracing with 4·n paths per pixel, n = 1 … 64.',
        color: COLOURS.pm,
        points: SWEEP_POINTS,
      },
      () => void this.runSweep(),
    );
  }

  protected buildReadout(readout: HTMLElement): void {
    this.readouts = new ReadoutList(readout, READOUT_ROWS);
    for (const key of SWEEP_ROWS) this.readouts.set(key, 'run the sweep');
  }

  private set(key: string, text: string, state?: 'ok' | 'bad'): void {
    this.readouts?.set(key, text, state);
  }

  private loadReference(): Promise<PhotonReference> {
    this.reference ??= (async () => {
      const response = await fetch(siteUrl('photon-map/reference.bin'));
      if (!response.ok) throw new Error(`reference: HTTP ${response.status}`);
      return parseReference(await response.arrayBuffer());
    })();
    return this.reference;
  }

  private kernel(): Promise<string> {
    this.code ??= linkLibraryKernel(STATIC_KERNELS, 'kernels/photon-map.wesl');
    return this.code;
  }

  /** Photon map at the inputs, then path tracing until it has used as much time. */
  private async renderBoth(
    backend: Backend<GpuContext>,
    inputs: PhotonInputs,
    ptSppTarget?: number,
    cpuPhotonCap = CPU_MAX_PHOTONS,
  ): Promise<Images> {
    const ref = await this.loadReference();
    if (backend.kind === 'gpu') {
      const device = backend.gpu.device;
      const code = await this.kernel();
      const { width, height } = GPU_SIZE;
      const pm = await renderPhotonMapGpu(device, code, inputs, width, height, GATHER_SAMPLES, {
        viewCount: VIEW_PHOTONS,
      });
      const sum = new Float64Array(width * height);
      let ptMs = 0;
      let spp = 0;
      for (let pass = 0; ; pass++) {
        const r = await pathTraceGpu(
          device,
          code,
          inputs,
          width,
          height,
          PT_PASS_SPP,
          inputs.seed + 7919 * pass,
        );
        for (let i = 0; i < sum.length; i++) sum[i]! += r.sum[i]!;
        ptMs += r.milliseconds;
        spp += PT_PASS_SPP;
        if (ptSppTarget !== undefined ? spp >= ptSppTarget : ptMs >= pm.milliseconds) break;
      }
      return {
        width,
        height,
        photonMap: Float64Array.from(pm.image),
        pathTraced: sum.map((s) => s / spp),
        pmMs: pm.milliseconds,
        ptMs,
        ptSpp: spp,
        stored: pm.stored,
        overflow: pm.overflow,
        view: pm.view,
        how: timingLabel(pm.timing),
        reference: Float64Array.from(ref.mean),
      };
    }
    const { width, height } = CPU_SIZE;
    const cpuInputs = { ...inputs, photons: Math.min(inputs.photons, cpuPhotonCap) };
    const start = performance.now();
    const set = tracePhotonsCpu(cpuInputs);
    const sorted = buildGridCpu(set, gridFor(cpuInputs.radius));
    const image = photonMapImageCpu(
      cpuInputs,
      set,
      sorted,
      width,
      height,
      GATHER_SAMPLES,
      inputs.seed,
    );
    const pmMs = performance.now() - start;
    const sum = new Float64Array(width * height);
    let ptMs = 0;
    let spp = 0;
    for (let pass = 0; ; pass++) {
      const t0 = performance.now();
      const r = pathTraceCpu(cpuInputs, width, height, 1, inputs.seed + 7919 * pass);
      ptMs += performance.now() - t0;
      for (let i = 0; i < sum.length; i++) sum[i]! += r.sum[i]!;
      spp += 1;
      if (ptSppTarget !== undefined ? spp >= ptSppTarget : ptMs >= pmMs || spp >= CPU_MAX_SPP)
        break;
    }
    const view = new Float32Array(Math.min(set.count, VIEW_PHOTONS) * 4);
    for (let i = 0; i < view.length / 4; i++) {
      view.set(
        [
          set.positions[3 * i]!,
          set.positions[3 * i + 1]!,
          set.positions[3 * i + 2]!,
          set.glass[i]!,
        ],
        4 * i,
      );
    }
    return {
      width,
      height,
      photonMap: image,
      pathTraced: sum.map((s) => s / spp),
      pmMs,
      ptMs,
      ptSpp: spp,
      stored: set.count,
      overflow: set.overflow,
      view,
      how: timingLabel('cpu'),
      reference: downsample(ref.mean, ref.width, ref.height, ref.width / width),
    };
  }

  protected async render(): Promise<void> {
    const inputs = inputsFrom(this.values);
    const backend = await this.backends.choose();
    let images: Images;
    try {
      images = await this.renderBoth(backend, inputs);
    } catch (error) {
      if (backend.kind === 'cpu') throw error;
      this.backends.useCpu(gpuFailureReason(error));
      this.sweep?.cancel('stopped: the GPU was lost');
      this.scheduleRender();
      return;
    }
    if (backend.kind === 'gpu') this.clearNotice('backend');
    else
      this.showCpuFallbackNotice(
        backend.reason,
        `Showing the float64 CPU twin at ${CPU_SIZE.width}×${CPU_SIZE.height} pixels with at most ${CPU_MAX_PHOTONS} photons; the reference is the GPU reference averaged 2×2.`,
      );
    this.show(inputs, images, backend);
  }

  private show(inputs: PhotonInputs, images: Images, backend: Backend<GpuContext>): void {
    const top = niceScale(percentile(images.reference, 0.995));
    if (this.scaleTop) this.scaleTop.textContent = `${formatNumber(top, 2)} W/(m²·sr)`;
    if (this.pmCanvas) paintGrey(this.pmCanvas, images.photonMap, images.width, images.height, top);
    if (this.ptCanvas)
      paintGrey(this.ptCanvas, images.pathTraced, images.width, images.height, top);
    if (this.viewCanvas) paintPhotons(this.viewCanvas, images.view);
    const pmError = rmse(images.photonMap, images.reference);
    const ptError = rmse(images.pathTraced, images.reference);
    const better = pmError < ptError ? 'pm' : 'pt';
    this.set(
      'stored',
      `${images.stored.toLocaleString('en-US')} from ${Math.min(inputs.photons, backend.kind === 'gpu' ? inputs.photons : CPU_MAX_PHOTONS).toLocaleString('en-US')} emitted` +
        (images.overflow > 0 ? `, ${images.overflow} lost (buffer full)` : ''),
      images.overflow > 0 ? 'bad' : undefined,
    );
    this.set('pm-time', `${formatMilliseconds(images.pmMs)} (${images.how})`);
    this.set('pm-error', formatNumber(pmError, 3), better === 'pm' ? 'ok' : undefined);
    this.set('pt-spp', String(images.ptSpp));
    this.set('pt-time', formatMilliseconds(images.ptMs));
    this.set('pt-error', formatNumber(ptError, 3), better === 'pt' ? 'ok' : undefined);
    this.recordFrameCost(images.pmMs + images.ptMs, images.how);
    const grid = gridFor(inputs.radius);
    if (this.readouts)
      this.readouts.cost.textContent = `${backend.kind === 'gpu' ? `WebGPU (${backend.gpu.adapterDescription})` : 'CPU fallback (float64 twin)'}: ${images.width}×${images.height} pixels; grid ${grid.dims.join('×')} cells of ${formatNumber(grid.cellSize * 100, 3)} cm. Reference: path tracing, ${REFERENCE_NOTE}.`;
    this.pmCanvas?.setAttribute(
      'aria-label',
      `Photon-mapped image, N = ${inputs.photons}, r = ${formatNumber(inputs.radius, 3)} m, RMSE ${formatNumber(pmError, 3)}`,
    );
    this.ptCanvas?.setAttribute(
      'aria-label',
      `Path-traced image, ${images.ptSpp} paths per pixel, RMSE ${formatNumber(ptError, 3)}`,
    );
  }

  private runSweep(): Promise<void> {
    return this.sweep!.runSeries(async () => {
      const inputs = inputsFrom(this.values);
      const backend = await this.backends.choose();
      for (const key of SWEEP_ROWS) this.set(key, 'sweeping…');
      const radiusAt = (photons: number): number =>
        progressiveRadius(inputs.radius, inputs.photons, photons);
      return {
        series: [
          { label: `photon mapping, r = ${formatNumber(inputs.radius, 3)} m`, color: COLOURS.pm },
          {
            label: `progressive, r = ${formatNumber(inputs.radius, 3)} m·(N/${inputs.photons})^(−1/7)`,
            color: COLOURS.ppm,
            dash: [6, 4],
          },
          { label: 'path tracing', color: COLOURS.pt },
        ],
        measure: async (series: number, n: number) => {
          if (series < 2) {
            // The sweep runs the photon counts it names on the CPU fallback too.
            const photons = SWEEP_PHOTONS * n;
            const radius = series === 0 ? inputs.radius : radiusAt(photons);
            const r = await this.renderBoth(
              backend,
              { ...inputs, photons, radius },
              PT_PASS_SPP,
              Infinity,
            );
            return { rmse: rmse(r.photonMap, r.reference), milliseconds: r.pmMs };
          }
          const r = await this.renderBoth(
            backend,
            { ...inputs, photons: SWEEP_PHOTONS },
            backend.kind === 'gpu' ? PT_PASS_SPP * n : n,
          );
          return { rmse: rmse(r.pathTraced, r.reference), milliseconds: r.ptMs };
        },
        finish: (points: readonly (readonly SweepPoint[])[]) => {
          const summary = summariseSweep(
            points[0] ?? [],
            points[1] ?? [],
            points[2] ?? [],
            SWEEP_PHOTONS,
            radiusAt,
          );
          this.set('plateau', summary.plateau);
          this.set('progressive', summary.progressive);
          this.set('pt-rate', summary.pathTracing);
          return `photon mapping (fixed and progressive radius) and path tracing, ${backend.kind === 'gpu' ? 'GPU' : 'CPU fallback'}`;
        },
        failed: () => {
          for (const key of SWEEP_ROWS) this.set(key, 'failed', 'bad');
        },
      };
    });
  }
}

const REFERENCE_NOTE = `${GPU_SIZE.width}×${GPU_SIZE.height}, precomputed (scripts/photon-map-reference.ts)`;

function percentile(values: ArrayLike<number>, q: number): number {
  const sorted = Array.from(values).sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))] ?? 0;
}

/** Grey image with a square-root mapping of [0, top] (sRGB-ish, enough to compare). */
function paintGrey(
  canvas: HTMLCanvasElement,
  image: ArrayLike<number>,
  width: number,
  height: number,
  top: number,
): void {
  canvas.width = width;
  canvas.height = height;
  const context = canvas.getContext('2d');
  if (!context) return;
  const data = context.createImageData(width, height);
  for (let i = 0; i < width * height; i++) {
    const v = Math.round(255 * Math.sqrt(Math.min(Math.max(image[i]! / top, 0), 1)));
    data.data.set([v, v, v, 255], 4 * i);
  }
  context.putImageData(data, 0, 0);
}

/** Stored photons as dots, projected with the widget's pinhole camera. */
function paintPhotons(canvas: HTMLCanvasElement, view: Float32Array): void {
  const context = canvas.getContext('2d');
  if (!context) return;
  const { width, height } = canvas;
  context.fillStyle = '#000';
  context.fillRect(0, 0, width, height);
  const frame = cameraFrame(width, height);
  const right2 = dot(frame.right, frame.right);
  const up2 = dot(frame.up, frame.up);
  // The sphere's outline, for orientation.
  const centre = project(SCENE.sphereCenter);
  if (centre) {
    const edge = project(add(SCENE.sphereCenter, [SCENE.sphereRadius, 0, 0]));
    if (edge) {
      context.strokeStyle = '#888';
      context.beginPath();
      context.arc(centre[0], centre[1], Math.abs(edge[0] - centre[0]), 0, 2 * Math.PI);
      context.stroke();
    }
  }
  for (let i = 0; i < view.length / 4; i++) {
    const p = project([view[4 * i]!, view[4 * i + 1]!, view[4 * i + 2]!]);
    if (!p) continue;
    context.fillStyle =
      view[4 * i + 3]! > 0 ? 'rgba(255, 160, 40, 0.8)' : 'rgba(90, 150, 255, 0.5)';
    context.fillRect(p[0], p[1], 1, 1);
  }

  function project(point: readonly [number, number, number]): [number, number] | null {
    const d = sub(point, SCENE.cameraPosition);
    const z = dot(d, frame.forward);
    if (!(z > 0)) return null;
    const q = scale(d, 1 / z);
    const nx = dot(q, frame.right) / right2;
    const ny = dot(q, frame.up) / up2;
    return [((nx + 1) / 2) * width, ((1 - ny) / 2) * height];
  }
}

export function definePhotonMap(): void {
  if (!customElements.get('sb-photon-map'))
    customElements.define('sb-photon-map', PhotonMapElement);
}
