// The drawing of <sb-translucent-room>: the path-traced reference and the dipole picture side
// by side. After an input a preview frame runs pass 1 of the dipole method (the irradiance
// samples) at IRRADIANCE_PREVIEW's size and one sample per pixel of each picture; the next
// frame runs pass 1 at full size and restarts the dipole picture on it; both then accumulate
// on their own schedule (steps of about STEP_BUDGET_MS, yielding between) up to the chosen
// samples per pixel, and write their rows and the error row themselves; the frame's rows
// are widget.ts's.
import type { GpuContext } from '../../gpu/device.ts';
import { STATIC_KERNELS } from '../../gpu/staticKernels.ts';
import {
  BACKGROUND_BAND_BUDGET_MS,
  PathAccumulator,
  type PathBatch,
} from '../../subsurface/translucentKernels.ts';
import { indirectShare, sphereMask, type RoomScene } from '../../subsurface/translucentRoom.ts';
import { RoomKernels } from '../../subsurface/translucentRoomKernels.ts';
import { workerJobs } from '../../workers/compute.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { imageFigure, imagePanel } from '../base/imagePanel.ts';
import type { FrameRequest } from '../base/refinement.ts';
import { timingLabel, type GpuTiming } from '../base/timing.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import { paintImage } from '../translucent-render/model.ts';
import type { jobs as roomJobTable } from './jobs.ts';
import {
  dipoleError,
  IRRADIANCE,
  IRRADIANCE_PASSES,
  IRRADIANCE_PREVIEW,
  pictureKey,
  sceneFromValues,
} from './model.ts';
import type { RoomFrame } from './widget.ts';

/**
 * A progressive step aims at this much GPU time per picture: an input's first picture
 * waits for the step in flight (GPU work is queued in order), so steps stay short (50 ms
 * gave a first picture of 209–220 ms after a radius change, 25 ms 123–200, two runs each).
 */
const STEP_BUDGET_MS = 25;
/** The CPU fallback's image side and samples per pixel. */
const CPU_SIZE = 24;
const CPU_SPP = 4;

const roomJobs = workerJobs<typeof roomJobTable>('translucent-room');

interface Pictures {
  key: string;
  scene: RoomScene;
  samples: Float32Array;
  irradianceMs: number;
  timing: string;
  reference: PathAccumulator;
  dipole: PathAccumulator;
  target: number;
  seed: number;
  /** Pass 1 was the preview's (IRRADIANCE_PREVIEW): the next frame runs the full one. */
  preview: boolean;
}

export function createView(context: ViewContext<RoomKernels>): WidgetView<RoomFrame, RoomKernels> {
  const canvas = (label: string) => context.canvas({ width: 64, height: 64, label });
  const canvases = [
    canvas('The translucent sphere in the room by volumetric path tracing (reference)'),
    canvas('The translucent sphere in the room with the dipole BSSRDF'),
  ] as const;
  const set = (key: string, text: string, state?: 'ok' | 'bad'): void =>
    context.setReadout(key, text, state);
  let status: HTMLElement | null = null;
  let pictures: Pictures | null = null;
  let token = 0;
  let running = false;

  const cancel = (why: string): void => {
    token += 1;
    if (running && status) status.textContent = `Accumulation ${why}.`;
    running = false;
    context.host.toggleAttribute('data-accumulating', false);
  };

  /** Paints both pictures and writes every row that changes as they accumulate. */
  const show = (): void => {
    const p = pictures;
    if (!p) return;
    const exposure = Number(context.values['exposure']);
    const mask = sphereMask(p.scene);
    const reference = p.reference.mean();
    const referenceSe = p.reference.standardError();
    paintImage(canvases[0].element, reference, p.scene.size, exposure);
    paintImage(canvases[1].element, p.dipole.mean(), p.scene.size, exposure);
    const timing = (t: string): string => (t ? timingLabel(t as GpuTiming) : timingLabel('cpu'));
    set('path-spp', `${p.reference.samples} of ${p.target}`);
    set('path-time', `${formatMilliseconds(p.reference.milliseconds)} (${timing(p.timing)})`);
    set('dipole-spp', `${p.dipole.samples} of ${p.target}`);
    set(
      'dipole-time',
      `${formatMilliseconds(p.irradianceMs + p.dipole.milliseconds)} = ${formatMilliseconds(p.irradianceMs)} + ${formatMilliseconds(p.dipole.milliseconds)}`,
    );
    let squares = 0;
    let sum = 0;
    let n = 0;
    mask.forEach((inside, q) => {
      if (!inside) return;
      for (let c = 0; c < 3; c++) {
        const se = referenceSe[3 * q + c]!;
        squares += Number.isFinite(se) ? se * se : 0;
        sum += reference[3 * q + c]!;
        n += 1;
      }
    });
    set(
      'path-se',
      p.reference.samples > 1 && n > 0
        ? `${formatNumber((100 * Math.sqrt(squares / n)) / (sum / n), 3)}% of the mean`
        : '—',
    );
    if (p.reference.samples < 2 || p.dipole.samples < 2 || n === 0) {
      set(
        'dipole-error',
        n === 0 ? '— (no pixel lies wholly on the sphere)' : '— (after two samples per pixel)',
      );
    } else {
      const e = dipoleError(
        p.dipole.mean(),
        p.dipole.standardError(),
        reference,
        referenceSe,
        mask,
      );
      const sign = e.meanError >= 0 ? '+' : '−';
      const mean = `${sign}${formatNumber(Math.abs(100 * e.meanError), 3)}%`;
      const noise = `±${formatNumber(100 * e.referenceNoise, 2)}%`;
      set(
        'dipole-error',
        e.belowNoise
          ? `below the noise (${noise}) · ${mean}`
          : `${e.referenceNoise > e.relativeRmse / 4 ? '≈ ' : ''}${formatNumber(100 * e.relativeRmse, 3)}% · ${mean} (noise ${noise})`,
      );
      context.host.dataset['dipoleError'] = String(e.relativeRmse);
    }
    const capped = p.reference.capped + p.dipole.capped;
    set('capped', String(capped), capped > 0 ? 'bad' : 'ok');
    context.host.dataset['referenceSpp'] = String(p.reference.samples);
    context.host.dataset['dipoleSpp'] = String(p.dipole.samples);
  };

  /** Accumulates both pictures up to the target, alternating steps of about STEP_BUDGET_MS. */
  const accumulate = async (): Promise<void> => {
    const job = pictures;
    if (!job || running) return;
    const backend = await context.backend();
    if (backend.kind !== 'gpu') return;
    const mine = ++token;
    const current = (): boolean => mine === token && job === pictures && !context.signal.aborted;
    running = true;
    context.host.toggleAttribute('data-accumulating', true);
    const perStep = { reference: 1, dipole: 1 };
    const step = async (which: 'reference' | 'dipole'): Promise<void> => {
      const acc = job[which];
      const samples = Math.min(perStep[which], job.target - acc.samples);
      if (samples <= 0) return;
      // In bands of rows (RoomKernels): an input stops the step between two, and the
      // input's frame starts the accumulation again from the same offset.
      const options = {
        samples,
        offset: acc.samples,
        seed: which === 'reference' ? job.seed : job.seed + 1,
        signal: context.inputSignal,
        bandBudgetMs: BACKGROUND_BAND_BUDGET_MS,
      };
      const batch: PathBatch =
        which === 'reference'
          ? await backend.renderer.pathBatch(job.scene, options)
          : await backend.renderer.dipoleBatch(job.scene, job.samples, options);
      if (!current()) return;
      acc.add(batch);
      if (which === 'reference') job.timing = batch.timing;
      const perSample = batch.milliseconds / samples;
      perStep[which] = Math.max(
        1,
        Math.min(256, Math.floor(STEP_BUDGET_MS / Math.max(perSample, 1e-3))),
      );
    };
    try {
      while (job.reference.samples < job.target || job.dipole.samples < job.target) {
        await step('reference');
        if (!current()) return;
        await step('dipole');
        if (!current()) return;
        if (status)
          status.textContent = `Accumulating: ${job.reference.samples} and ${job.dipole.samples} of ${job.target} samples per pixel…`;
        show();
        await new Promise((resolve) => setTimeout(resolve, 0));
      }
      if (status) status.textContent = `Done: ${job.target} samples per pixel in each picture.`;
    } catch (error) {
      // An input stopped the step: its frame calls accumulate again.
      if (error instanceof DOMException && error.name === 'AbortError') return;
      if (status)
        status.textContent = `Accumulation failed: ${error instanceof Error ? error.message : String(error)}`;
    } finally {
      if (mine === token) {
        running = false;
        context.host.toggleAttribute('data-accumulating', false);
      }
    }
  };

  const frameOf = (
    p: Pictures,
    timing: GpuTiming | 'cpu',
    sizes: { samples: number; rays: number },
  ): RoomFrame => ({
    size: p.scene.size,
    samples: sizes.samples,
    rays: sizes.rays,
    irradiance: { milliseconds: p.irradianceMs, timing },
    indirect: indirectShare(p.samples),
  });

  return {
    get cpuNotice() {
      return `Showing the float64 twins of both pictures at ${CPU_SIZE}² pixels with ${CPU_SPP} samples per pixel (in a worker); WebGPU accumulates many more.`;
    },
    build(stage) {
      const left = imagePanel(canvases[0].element, 'Volumetric path tracing (reference)');
      const right = imagePanel(canvases[1].element, 'Dipole BSSRDF under the room’s light');
      stage.appendChild(imageFigure(left.panel, right.panel));
      status = document.createElement('p');
      status.className = 'sb-tr-status';
      status.setAttribute('role', 'status');
      stage.appendChild(status);
    },
    createRenderer: (gpu: GpuContext) => new RoomKernels(gpu.device, STATIC_KERNELS),
    refinement: (frame) => frame.stage,
    async renderGpu(renderer, _gpu, request: FrameRequest) {
      const key = pictureKey(context.values);
      const target = 2 ** Number(context.values['spp']);
      /** Pass 1 of the dipole method at `sizes` (its samples and the time it took). */
      const passOne = async (
        scene: RoomScene,
        seed: number,
        sizes: { samples: number; rays: number },
      ): Promise<{ samples: Float32Array; milliseconds: number; timing: string }> => {
        let samples: Float32Array = new Float32Array(0);
        let milliseconds = 0;
        let timing = '';
        for (let pass = 0; pass < IRRADIANCE_PASSES; pass++) {
          const r = await renderer.irradiance(
            scene,
            sizes.samples,
            sizes.rays,
            seed + 2 + pass,
            samples,
          );
          samples = r.samples;
          milliseconds += r.milliseconds;
          timing = r.timing;
        }
        return { samples, milliseconds, timing };
      };
      if (pictures?.key !== key) {
        // The first picture after an input: pass 1 at preview size, one sample per pixel
        // of each picture (issue 23's first-picture budget); the next frame refines it.
        cancel('restarted');
        // At half the side: one sample per pixel of the path-traced picture at full size
        // took 84 ms of GPU time on SwiftShader, past the first-picture budget by itself.
        const full = sceneFromValues(context.values);
        const scene = { ...full, size: Math.max(8, Math.round(full.size / 2)) };
        const seed = Number(context.values['seed']);
        const first = await passOne(scene, seed, IRRADIANCE_PREVIEW);
        if (request.signal.aborted) return null;
        const pixels = scene.size * scene.size;
        const next: Pictures = {
          key,
          scene,
          samples: first.samples,
          irradianceMs: first.milliseconds,
          timing: first.timing,
          reference: new PathAccumulator(pixels),
          dipole: new PathAccumulator(pixels),
          target,
          seed,
          preview: true,
        };
        // Both pictures side by side, each in one dispatch: bands would add a read-back
        // each to the first picture, which an input does not need to stop.
        const [reference, dipole] = await Promise.all([
          renderer.pathBatch(scene, { samples: 1, offset: 0, seed, whole: true }),
          renderer.dipoleBatch(scene, first.samples, {
            samples: 1,
            offset: 0,
            seed: seed + 1,
            whole: true,
          }),
        ]);
        next.reference.add(reference);
        next.dipole.add(dipole);
        if (request.signal.aborted) return null;
        pictures = next;
        show();
        return {
          ...frameOf(next, next.timing as GpuTiming, IRRADIANCE_PREVIEW),
          stage: {
            label: `Preview: pass 1 with ${IRRADIANCE_PREVIEW.samples} × ${IRRADIANCE_PREVIEW.rays}, 1 sample per pixel at ${scene.size}² pixels`,
            pending: 'frame',
          },
        };
      }
      const p = pictures;
      p.target = target;
      if (p.preview) {
        // The full pass 1; the dipole picture starts again on it (the path-traced one does
        // not depend on it and goes on). The preview's dipole stays on screen meanwhile.
        // Both pictures at full size from here: the preview's were at half the side.
        const scene = sceneFromValues(context.values);
        const pixels = scene.size * scene.size;
        const full = await passOne(scene, p.seed, IRRADIANCE.gpu);
        if (request.signal.aborted || pictures !== p) return null;
        const dipole = new PathAccumulator(pixels);
        const reference = p.scene.size === scene.size ? p.reference : new PathAccumulator(pixels);
        const [dipoleBatch, referenceBatch] = await Promise.all([
          renderer.dipoleBatch(scene, full.samples, {
            samples: 1,
            offset: 0,
            seed: p.seed + 1,
            signal: request.signal,
          }),
          reference.samples === 0
            ? renderer.pathBatch(scene, {
                samples: 1,
                offset: 0,
                seed: p.seed,
                signal: request.signal,
              })
            : null,
        ]);
        if (request.signal.aborted || pictures !== p) return null;
        dipole.add(dipoleBatch);
        if (referenceBatch) reference.add(referenceBatch);
        p.scene = scene;
        p.reference = reference;
        p.samples = full.samples;
        p.irradianceMs = full.milliseconds;
        p.timing = full.timing;
        p.dipole = dipole;
        p.preview = false;
      }
      show();
      if (!running && (p.reference.samples < target || p.dipole.samples < target))
        void accumulate();
      return frameOf(p, p.timing as GpuTiming, IRRADIANCE.gpu);
    },
    async renderCpu(request: FrameRequest) {
      cancel('stopped');
      const scene = { ...sceneFromValues(context.values), size: CPU_SIZE };
      const seed = Number(context.values['seed']);
      const drawn = await roomJobs.run('pictures', [scene, CPU_SPP, seed], {
        signal: request.signal,
      });
      const pixels = scene.size * scene.size;
      const reference = new PathAccumulator(pixels);
      reference.add({
        sums: drawn.reference,
        samples: drawn.spp,
        milliseconds: drawn.referenceMs,
        timing: 'cpu',
      });
      const dipole = new PathAccumulator(pixels);
      dipole.add({
        sums: drawn.dipole,
        samples: drawn.spp,
        milliseconds: drawn.dipoleMs,
        timing: 'cpu',
      });
      pictures = {
        key: `cpu|${pictureKey(context.values)}`,
        scene,
        samples: drawn.samples,
        irradianceMs: drawn.irradianceMs,
        timing: '',
        reference,
        dipole,
        target: drawn.spp,
        seed,
        preview: false,
      };
      show();
      return frameOf(pictures, 'cpu', IRRADIANCE.cpu);
    },
    onCpuFallback() {
      cancel('stopped: the GPU was lost');
      pictures = null;
    },
    destroy() {
      cancel('stopped');
    },
  };
}
