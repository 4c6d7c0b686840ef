// The drawing of <sb-photon-map>: the stored photons projected into the camera, the
// photon-mapped and the equal-time path-traced images (grey, square-root scale with a
// labelled top), and the error-vs-time sweep, which writes its own three rows.
// Readouts, backends and fallback: widget.ts and the base element.
import { abortError } from '../../gpu/bands.ts';
import type { GpuContext } from '../../gpu/device.ts';
import { linkLibraryKernel } from '../../gpu/link.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import type { Backend } from '../base/backend.ts';
import { Ladder, firstPictureBudget, type FrameRequest } from '../base/refinement.ts';
import { formatNumber } from '../base/format.ts';
import { imageCanvas, imageFigure, imagePanel, niceScale } from '../base/imagePanel.ts';
import { siteUrl } from '../base/siteUrl.ts';
import { SweepControls, type SweepPoint } from '../base/sweep.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import { pathTraceGpu, renderPhotonMapGpu } from './gpuBackend.ts';
import {
  CPU_SIZE,
  DEFAULT_INPUTS,
  GPU_SIZE,
  SCENE,
  add,
  cameraFrame,
  dot,
  downsample,
  gridFor,
  parseReference,
  progressiveRadius,
  rmse,
  scale,
  sub,
  type PhotonInputs,
  type PhotonReference,
} from './model.ts';
import type { jobs } from './jobs.ts';
import { summariseSweep } from './summary.ts';
import { workerJobs } from '../../workers/compute.ts';
import { CPU_MAX_PHOTONS, SWEEP_ROWS, type PhotonFrame, type PhotonImages } from './widget.ts';
import { context2d } from '../base/canvas2d.ts';

const VIEW_SIZE = { width: 256, height: 192 } as const;
const VIEW_PHOTONS = 16384;
const PT_PASS_SPP = 4;
/** GPU time one path-tracing pass of a frame may take (ms): an input waits for the pass in flight. */
const PT_PASS_BUDGET_MS = 20;
/** Path-tracing passes submitted before the first of them is read back. */
const PT_PASSES_IN_FLIGHT = 2;
/** The photon-map image's jittered rays per pixel. */
const GATHER_SAMPLES = 1;
/** Paths per pixel the CPU path tracer stops at even if it has time left. */
const CPU_MAX_SPP = 4096;
const SWEEP_POINTS = [1, 2, 4, 8, 16, 32, 64] as const;
/** Mid-tone colours that read on the light and the dark page; the progressive curve is also dashed. */
const COLOURS = { pm: '#d9822b', ppm: '#9b72e0', pt: '#5b8def' } as const;
/** Photons per sweep step: N = SWEEP_PHOTONS·n. */
const SWEEP_PHOTONS = 4096;
/**
 * The rungs: a fraction of the reader's photons (at least PREVIEW_MIN_PHOTONS) at a
 * pixel scale (2: half the resolution, its error against the reference averaged 2×2),
 * and their work relative to the full picture. The gather over the image costs about
 * as much as the tracing (4,096 of 65,536 photons at full resolution took a third of
 * the full time on SwiftShader), hence the half resolution of the first rung.
 */
const RUNGS = [
  // The smallest rungs for a slow machine: on SwiftShader the preview of 1/16 (with path
  // tracing in the same time) took 95–110 ms, past the first-picture budget, and 1/64 at
  // half resolution about 80 ms (the gather's march over the pixels and the path tracing
  // that matches its time are most of a small preview's cost).
  {
    fraction: 1 / 64,
    pixelScale: 4,
    work: 0.015,
    label: '1/64 of the photons, quarter resolution',
  },
  { fraction: 1 / 64, pixelScale: 2, work: 0.04, label: '1/64 of the photons, half resolution' },
  { fraction: 1 / 16, pixelScale: 2, work: 0.1, label: '1/16 of the photons, half resolution' },
  { fraction: 1 / 4, pixelScale: 1, work: 0.4, label: '¼ of the photons' },
  { fraction: 1, pixelScale: 1, work: 1, label: 'all photons' },
] as const;
type PhotonRung = (typeof RUNGS)[number];
/** What a preview's stage line says of its pixel scale. */
const RESOLUTION_NAMES: Readonly<Record<number, string>> = {
  2: ', half resolution',
  4: ', quarter resolution',
};
const PREVIEW_MIN_PHOTONS = 1024;

/** The reference as the cost line names it (student-facing: no repository paths). */
function referenceNote(ref: PhotonReference): string {
  return `${ref.width}×${ref.height} pixels, ${ref.samples.toLocaleString('en-US')} paths per pixel, computed ahead of time`;
}

export function inputsFrom(values: Record<string, number | string>): PhotonInputs {
  return {
    ...DEFAULT_INPUTS,
    photons: Math.round(Number(values['photons'] ?? DEFAULT_INPUTS.photons)),
    radius: Number(values['radius'] ?? DEFAULT_INPUTS.radius),
  };
}

/** The CPU twin's renders, in the compute worker (jobs.ts). */
const cpuJobs = workerJobs<typeof jobs>('photon-map');

export function createView(context: ViewContext<GpuContext>): WidgetView<PhotonFrame, GpuContext> {
  // 2D canvases on either backend (the GPU work reads back into them), so never swapped.
  const viewCanvas = imageCanvas(
    'Stored photons projected into the camera',
    VIEW_SIZE.width,
    VIEW_SIZE.height,
  );
  viewCanvas.dataset['view'] = 'photons';
  const pmCanvas = imageCanvas('Photon-mapped image', GPU_SIZE.width, GPU_SIZE.height);
  pmCanvas.dataset['view'] = 'photon-map';
  const ptCanvas = imageCanvas('Path-traced image in equal time', GPU_SIZE.width, GPU_SIZE.height);
  ptCanvas.dataset['view'] = 'path-trace';
  let scaleTop: HTMLElement | null = null;
  let sweep: SweepControls | null = null;
  let reference: Promise<PhotonReference> | null = null;
  let code: Promise<string> | null = null;

  const loadReference = (): Promise<PhotonReference> => {
    reference ??= (async () => {
      const response = await fetch(siteUrl('photon-map/reference.bin'));
      if (!response.ok) throw new Error(`reference: HTTP ${response.status}`);
      return parseReference(await response.arrayBuffer());
    })();
    return reference;
  };

  const kernel = (): Promise<string> => {
    code ??= linkLibraryKernel(STATIC_KERNELS, 'kernels/photon-map.wesl');
    return code;
  };

  /** Photon map at the inputs, then path tracing until it has used as much time. */
  /** GPU ms per path sample (one pixel, one sample) of the last pass: sizes the next passes. */
  let ptMsPerSample: number | null = null;
  const renderBoth = async (
    backend: Backend<GpuContext>,
    inputs: PhotonInputs,
    ptSppTarget?: number,
    cpuPhotonCap = CPU_MAX_PHOTONS,
    signal?: AbortSignal,
    /** Pixels per side of one image pixel (2: a preview at half the resolution). */
    pixelScale = 1,
  ): Promise<PhotonImages> => {
    const ref = await loadReference();
    if (backend.kind === 'gpu') {
      const device = backend.gpu.device;
      const linked = await kernel();
      const width = GPU_SIZE.width / pixelScale;
      const height = GPU_SIZE.height / pixelScale;
      const pm = await renderPhotonMapGpu(device, linked, inputs, width, height, GATHER_SAMPLES, {
        viewCount: VIEW_PHOTONS,
        ...(signal ? { signal } : {}),
      });
      const sum = new Float64Array(width * height);
      const pixels = width * height;
      let ptMs = 0;
      let spp = 0;
      // Passes in flight and what they are expected to add (ms from the last pass's cost).
      const inFlight: Promise<{ sum: Float32Array; milliseconds: number; spp: number }>[] = [];
      let plannedMs = 0;
      let plannedSpp = 0;
      let pass = 0;
      const enough = (extraMs: number, extraSpp: number): boolean =>
        ptSppTarget !== undefined
          ? spp + extraSpp >= ptSppTarget
          : ptMs + extraMs >= pm.milliseconds;
      for (;;) {
        // Up to PT_PASSES_IN_FLIGHT passes are submitted before the first is read back (a
        // read-back is a round trip of 10–20 ms in Chrome on SwiftShader), once a pass has
        // been timed; while more are still needed to match the photon map's time.
        while (
          inFlight.length < (ptMsPerSample === null ? 1 : PT_PASSES_IN_FLIGHT) &&
          !(inFlight.length > 0 && enough(plannedMs, plannedSpp))
        ) {
          // An input stops the path tracer between passes: the next picture would otherwise
          // queue behind every pass still to come on the GPU (issue 23).
          if (signal?.aborted) {
            await Promise.allSettled(inFlight);
            throw abortError('the rest of this frame');
          }
          // Equal time: passes of PT_PASS_SPP, or, once a pass has been timed, as many
          // PT_PASS_SPP as fit the time still to match, at most PT_PASS_BUDGET_MS of it (each
          // pass is a read-back: 4 spp at a time cost a preview 5 of them).
          const perSample = ptMsPerSample;
          // The last pass takes what is left (rounded up to whole PT_PASS_SPP: equal time
          // at least), earlier ones PT_PASS_BUDGET_MS each (rounded down).
          const remainingMs = pm.milliseconds - ptMs - plannedMs;
          const unitMs = perSample === null ? 0 : PT_PASS_SPP * perSample * pixels;
          const units =
            unitMs <= 0
              ? 1
              : remainingMs <= PT_PASS_BUDGET_MS
                ? Math.ceil(remainingMs / unitMs)
                : Math.floor(PT_PASS_BUDGET_MS / unitMs);
          const passSpp =
            ptSppTarget === undefined && perSample !== null
              ? PT_PASS_SPP * Math.max(1, units)
              : PT_PASS_SPP;
          const expectedMs = perSample === null ? 0 : passSpp * perSample * pixels;
          plannedMs += expectedMs;
          plannedSpp += passSpp;
          inFlight.push(
            pathTraceGpu(
              device,
              linked,
              inputs,
              width,
              height,
              passSpp,
              inputs.seed + 7919 * pass,
            ).then((r) => {
              plannedMs -= expectedMs;
              plannedSpp -= passSpp;
              return { ...r, spp: passSpp };
            }),
          );
          pass += 1;
        }
        if (inFlight.length === 0) break;
        const r = await inFlight.shift()!.catch(async (error: unknown) => {
          // The passes still in flight are waited for: their buffers go back to the pool.
          await Promise.allSettled(inFlight);
          throw error;
        });
        for (let i = 0; i < sum.length; i++) sum[i]! += r.sum[i]!;
        ptMs += r.milliseconds;
        spp += r.spp;
        ptMsPerSample = r.milliseconds / (r.spp * pixels);
        if (inFlight.length === 0 && enough(0, 0)) break;
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
        timing: pm.timing,
        reference:
          ref.width === width
            ? Float64Array.from(ref.mean)
            : downsample(ref.mean, ref.width, ref.height, ref.width / width),
      };
    }
    const width = CPU_SIZE.width / pixelScale;
    const height = CPU_SIZE.height / pixelScale;
    const cpuInputs = { ...inputs, photons: Math.min(inputs.photons, cpuPhotonCap) };
    // The float64 twin runs in the compute worker: the page stays responsive.
    const cpu = await cpuJobs.run(
      'renderCpuImages',
      [cpuInputs, width, height, GATHER_SAMPLES, ptSppTarget ?? null, CPU_MAX_SPP, VIEW_PHOTONS],
      signal ? { signal } : {},
    );
    return {
      width,
      height,
      ...cpu,
      timing: 'cpu',
      reference: downsample(ref.mean, ref.width, ref.height, ref.width / width),
    };
  };

  /**
   * Ladders over the photon count per backend: the first picture after an input traces
   * the largest fraction of the reader's photons whose measured cost fits the
   * first-picture budget (with path tracing in the same time), later stages the rest.
   */
  const ladders = new Map<'gpu' | 'cpu', Ladder<PhotonRung>>();
  const ladderFor = (kind: 'gpu' | 'cpu'): Ladder<PhotonRung> => {
    let ladder = ladders.get(kind);
    if (!ladder) {
      // The quarter-resolution rung is the GPU's (on SwiftShader): the CPU twin's picture is
      // 32×24, which a quarter would make 8×6, and its first picture takes a few ms anyway.
      ladder = new Ladder(
        RUNGS.filter((rung) => kind === 'gpu' || rung.pixelScale < 4).map((rung) => ({
          value: rung,
          work: rung.work,
          label: rung.label,
        })),
        firstPictureBudget(kind),
      );
      ladders.set(kind, ladder);
    }
    return ladder;
  };

  const frameOf = async (
    backend: Backend<GpuContext>,
    request: FrameRequest,
  ): Promise<PhotonFrame | null> => {
    const inputs = inputsFrom(context.values);
    const ladder = ladderFor(backend.kind);
    const choice = ladder.pick(request);
    const photons = choice.final
      ? inputs.photons
      : Math.min(
          inputs.photons,
          Math.max(PREVIEW_MIN_PHOTONS, Math.round(inputs.photons * choice.rung.value.fraction)),
        );
    // A rung that traces as many photons as the full picture (the CPU twin's cap) is it.
    const traced = (n: number): number =>
      backend.kind === 'gpu' ? n : Math.min(n, CPU_MAX_PHOTONS);
    const final = choice.final || traced(photons) === traced(inputs.photons);
    const start = performance.now();
    const images = await renderBoth(
      backend,
      { ...inputs, photons },
      undefined,
      CPU_MAX_PHOTONS,
      request.signal,
      final ? 1 : choice.rung.value.pixelScale,
    );
    ladder.record(choice.index, performance.now() - start);
    if (request.signal.aborted) return null;
    const grid = gridFor(inputs.radius);
    const ref = await loadReference();
    return {
      inputs: { ...inputs, photons },
      images,
      pmError: rmse(images.photonMap, images.reference),
      ptError: rmse(images.pathTraced, images.reference),
      grid: { dims: grid.dims, cellSize: grid.cellSize },
      referenceNote: referenceNote(ref),
      stage: final
        ? { label: `${inputs.photons.toLocaleString('en-US')} photons`, pending: null }
        : {
            label: `Preview: ${photons.toLocaleString('en-US')} of ${inputs.photons.toLocaleString('en-US')} photons${RESOLUTION_NAMES[choice.rung.value.pixelScale] ?? ''}, path tracing in the same time`,
            pending: 'frame',
          },
    };
  };

  const runSweep = (controls: SweepControls): Promise<void> =>
    controls.runSeries(async () => {
      const inputs = inputsFrom(context.values);
      const backend = await context.backend();
      for (const key of SWEEP_ROWS) context.setReadout(key, 'sweeping…');
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
            const r = await renderBoth(
              backend,
              { ...inputs, photons, radius },
              PT_PASS_SPP,
              Infinity,
            );
            return { rmse: rmse(r.photonMap, r.reference), milliseconds: r.pmMs };
          }
          const r = await renderBoth(
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
          context.setReadout('plateau', summary.plateau);
          context.setReadout('progressive', summary.progressive);
          context.setReadout('pt-rate', summary.pathTracing);
          return `photon mapping (fixed and progressive radius) and path tracing, ${backend.kind === 'gpu' ? 'GPU' : 'CPU fallback'}`;
        },
        failed: () => {
          for (const key of SWEEP_ROWS) context.setReadout(key, 'failed', 'bad');
        },
      };
    });

  return {
    cpuNotice: `Showing the float64 CPU twin at ${CPU_SIZE.width}×${CPU_SIZE.height} pixels with at most ${CPU_MAX_PHOTONS} photons; the reference is the GPU reference averaged 2×2.`,
    build(stage) {
      // The images map radiance v to grey √(v/top), so the bar's midpoint is top/4. The
      // legend keeps to "0 ▬ top" (a longer label wrapped into the bar in a narrow
      // panel); the caption says the scale is a square root.
      const greyScale = {
        gradient: 'linear-gradient(to right, #000, #fff)',
        low: '0',
        top: { readout: 'radiance-scale' },
      };
      const pm = imagePanel(
        pmCanvas,
        'Photon mapping (volume radiance estimate); grey ∝ √radiance, scale below',
        greyScale,
      );
      scaleTop = pm.top;
      stage.appendChild(
        imageFigure(
          imagePanel(
            viewCanvas,
            'Stored photons (orange: through the glass; blue: fog only). All carry ΔΦ = E·A/N.',
          ).panel,
          pm.panel,
          imagePanel(ptCanvas, 'Path tracing, same time').panel,
        ),
      );
      const controls = new SweepControls(
        stage,
        context.host,
        {
          name: 'n',
          buttonText: 'Run error-vs-time sweep',
          hint: 'Run the sweep to plot RMSE against time: photon mapping with N = 4096·n photons at the current radius, progressive photon mapping with the radius shrinking as N^(−1/7) from the current N and r, and path tracing with 4·n paths per pixel, n = 1 … 64.',
          color: COLOURS.pm,
          points: SWEEP_POINTS,
        },
        () => void runSweep(controls),
      );
      sweep = controls;
    },
    // The GPU functions take the device; the kernel is linked once (kernel()).
    createRenderer: (gpu: GpuContext) => gpu,
    renderGpu: (renderer, gpu, request) => frameOf({ kind: 'gpu', gpu, renderer }, request),
    renderCpu: (request) => frameOf({ kind: 'cpu', reason: '' }, request),
    refinement: (shown) => shown.stage,
    onCpuFallback: () => sweep?.cancel('stopped: the GPU was lost'),
    destroy: () => sweep?.cancel('stopped'),
    show({ inputs, images, pmError, ptError }) {
      const top = niceScale(percentile(images.reference, 0.995));
      if (scaleTop) scaleTop.textContent = `${formatNumber(top, 2)} W/(m²·sr)`;
      paintGrey(pmCanvas, images.photonMap, images.width, images.height, top);
      paintGrey(ptCanvas, images.pathTraced, images.width, images.height, top);
      paintPhotons(viewCanvas, images.view);
      pmCanvas.setAttribute(
        'aria-label',
        `Photon-mapped image, N = ${inputs.photons}, r = ${formatNumber(inputs.radius, 3)} m, RMSE ${formatNumber(pmError, 3)}`,
      );
      ptCanvas.setAttribute(
        'aria-label',
        `Path-traced image, ${images.ptSpp} paths per pixel, RMSE ${formatNumber(ptError, 3)}`,
      );
    },
  };
}

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
  const context = context2d(canvas);
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
  const context = context2d(canvas);
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
