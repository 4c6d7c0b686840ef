// <sb-rayleigh-sky>: why the sky is blue and sunsets red (chapter 3). Draws a
// panorama toward the sun on the GPU, one single-scattering march per pixel,
// evaluates three probe directions and the direct sun in a compute pass, and shows
// them next to a converged float64 reference (relative error) and the GPU time.
import { BackendChooser, type Backend as ChosenBackend } from '../base/backend.ts';
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { WidgetElement, type Preset } from '../base/widgetElement.ts';
import { RAYLEIGH_SKY } from './schema.ts';
import { drawSkyCpu } from './cpuBackend.ts';
import { RayleighSkyGpu } from './gpuBackend.ts';
import {
  CANVAS_HEIGHT,
  CANVAS_WIDTH,
  ELEVATION_MAX_DEG,
  ELEVATION_MIN_DEG,
  FIELD_OF_VIEW_DEG,
  REFERENCE_STEPS,
  SUN_ENLARGEMENT,
  computeProbes,
  inputsFrom,
  probesFor,
  referenceProbes,
  relativeError,
  srgbEncode,
  type Rgb,
  type SkyInputs,
  type SkyResult,
} from './model.ts';

type Backend = ChosenBackend<RayleighSkyGpu>;

const READOUT_ROWS = [
  ['zenith', 'Zenith radiance L (R, G, B), sr⁻¹'],
  ['toward', '10° up, toward the sun'],
  ['away', '10° up, away from the sun'],
  ['error', `Relative error vs float64, N = M = ${REFERENCE_STEPS}`],
  ['sun', 'Direct sunlight T_sun (R, G, B)'],
  ['zenith-ratio', 'Zenith blue/red, L_B/L_R'],
  ['sun-ratio', 'Direct sun red/blue, T_R/T_B'],
] as const;

/** Probe keys in probesFor order, and the readout each one fills. */
const PROBE_KEYS = ['zenith', 'toward', 'away'] as const;
const CPU_SCALE = 4;

function formatRgb(rgb: Rgb, digits = 4): string {
  return rgb.map((v) => formatNumber(v, digits)).join(', ');
}

function formatPercent(error: number | null): string {
  if (error === null) return '0 (exact: no light)';
  return `${formatNumber(100 * error, 3)}%`;
}

export class RayleighSkyElement extends WidgetElement {
  protected readonly entry = RAYLEIGH_SKY;
  protected override presets: readonly Preset[] = [
    { label: 'noon', values: { 'sun-elevation': 60, scattering: 'on' } },
    { label: 'afternoon', values: { 'sun-elevation': 20, scattering: 'on' } },
    { label: 'sunset', values: { 'sun-elevation': 2, scattering: 'on' } },
    { label: 'no scattering', values: { 'sun-elevation': 30, scattering: 'off' } },
  ];

  private canvas: HTMLCanvasElement | null = null;
  private labels: HTMLElement | null = null;
  private readouts = new Map<string, HTMLElement>();
  private swatch: HTMLElement | null = null;
  private cost: HTMLElement | null = null;
  private readonly backends = new BackendChooser<RayleighSkyGpu>(
    (gpu) => {
      if (!this.canvas) throw new Error('no canvas');
      return new RayleighSkyGpu(gpu, this.canvas);
    },
    (reason) => this.fallBackToCpu(reason),
  );

  protected buildStage(stage: HTMLElement): void {
    const figure = document.createElement('div');
    figure.className = 'sb-sky-figure';
    this.canvas = this.createCanvas();
    this.labels = document.createElement('div');
    this.labels.className = 'sb-sky-labels';
    this.labels.setAttribute('aria-hidden', 'true');
    figure.append(this.canvas, this.labels);
    stage.appendChild(figure);
  }

  private createCanvas(): HTMLCanvasElement {
    const canvas = document.createElement('canvas');
    canvas.className = 'sb-canvas';
    canvas.setAttribute('role', 'img');
    canvas.width = CANVAS_WIDTH;
    canvas.height = CANVAS_HEIGHT;
    return canvas;
  }

  protected buildReadout(readout: HTMLElement): void {
    const list = document.createElement('dl');
    list.className = 'sb-readout';
    for (const [key, label] of READOUT_ROWS) {
      const row = document.createElement('div');
      const term = document.createElement('dt');
      term.textContent = label;
      const value = document.createElement('dd');
      value.dataset['readout'] = key;
      row.append(term, value);
      if (key === 'sun') {
        this.swatch = document.createElement('span');
        this.swatch.className = 'sb-sky-swatch';
        this.swatch.setAttribute('aria-hidden', 'true');
        row.appendChild(this.swatch);
      }
      list.appendChild(row);
      this.readouts.set(key, value);
    }
    this.cost = document.createElement('p');
    this.cost.className = 'sb-cost';
    this.cost.setAttribute('aria-live', 'polite');
    const scope = document.createElement('p');
    scope.className = 'sb-sky-scope';
    scope.textContent =
      'Single Rayleigh scattering only: no ozone, no aerosols, no multiple scattering.';
    readout.append(list, this.cost, scope);
  }

  /** After a device loss: a fresh canvas (a WebGPU canvas cannot become 2D) and the CPU path. */
  private fallBackToCpu(reason: string): void {
    if (this.canvas) {
      const fresh = this.createCanvas();
      this.canvas.replaceWith(fresh);
      this.canvas = fresh;
    }
    this.backends.useCpu(reason);
    this.scheduleRender();
  }

  protected async render(): Promise<void> {
    const inputs = inputsFrom(this.values);
    const backend = await this.backends.choose();
    if (!this.canvas) return;
    let result: SkyResult;
    let capped = false;
    if (backend.kind === 'gpu') {
      try {
        const probes = await backend.renderer.probes(inputs);
        const pictureMilliseconds = await backend.renderer.draw(inputs);
        capped = probes.capped;
        result = {
          radiance: probes.radiance,
          sunTransmittance: probes.sunTransmittance,
          probeMilliseconds: probes.milliseconds,
          pictureMilliseconds,
          timing: probes.timing,
        };
      } catch (error) {
        this.fallBackToCpu(
          `the GPU path failed: ${error instanceof Error ? error.message : String(error)}`,
        );
        return;
      }
      this.clearNotice('backend');
    } else {
      const pictureMilliseconds = drawSkyCpu(this.canvas, inputs, CPU_SCALE);
      const start = performance.now();
      const probes = computeProbes(inputs);
      result = {
        ...probes,
        probeMilliseconds: performance.now() - start,
        pictureMilliseconds,
        timing: 'cpu',
      };
      this.showNotice(
        'backend',
        'warning',
        `WebGPU is not available (${backend.reason}). Showing the float64 CPU twin: the same integral with the same N and M, the picture drawn at quarter resolution.`,
      );
    }
    if (capped) {
      this.showNotice('capped', 'warning', 'A march reached its step cap; the sky is truncated.');
    } else {
      this.clearNotice('capped');
    }
    this.drawLabels(inputs);
    this.showResult(inputs, result, backend);
  }

  /** Angle labels over the canvas, in per cent of its size so they follow its CSS size. */
  private drawLabels(inputs: SkyInputs): void {
    if (!this.labels) return;
    const span = ELEVATION_MAX_DEG - ELEVATION_MIN_DEG;
    const top = (elevation: number): number => (100 * (ELEVATION_MAX_DEG - elevation)) / span;
    const label = (text: string, x: number, y: number, className: string): HTMLElement => {
      const element = document.createElement('span');
      element.className = className;
      element.textContent = text;
      element.style.left = `${x}%`;
      element.style.top = `${y}%`;
      return element;
    };
    const half = FIELD_OF_VIEW_DEG / 2;
    const spans: HTMLElement[] = [
      label('horizon 0°', 1, top(0), 'sb-sky-label'),
      label('30°', 1, top(30), 'sb-sky-label'),
      label('60°', 1, top(60), 'sb-sky-label'),
      label(`azimuth −${half}°`, 1, 99, 'sb-sky-label sb-sky-label--note'),
      label(`+${half}°`, 99, 99, 'sb-sky-label sb-sky-label--end sb-sky-label--note'),
    ];
    const e = inputs.sunElevationDeg;
    if (e < 0) {
      spans.push(
        label(
          `sun ${formatNumber(-e, 3)}° below the horizon`,
          50,
          99,
          'sb-sky-label sb-sky-label--centre sb-sky-label--note',
        ),
      );
    } else if (e > ELEVATION_MAX_DEG - 1) {
      spans.push(
        label(
          `sun at ${formatNumber(e, 3)}°, above the frame`,
          50,
          4,
          'sb-sky-label sb-sky-label--centre sb-sky-label--below',
        ),
      );
    } else {
      spans.push(
        label(
          `sun (disc enlarged ×${SUN_ENLARGEMENT})`,
          52,
          Math.max(top(e) - 2.5, 4),
          'sb-sky-label sb-sky-label--note',
        ),
      );
    }
    this.labels.replaceChildren(...spans);
  }

  private showResult(inputs: SkyInputs, result: SkyResult, backend: Backend): void {
    const set = (key: string, text: string, state?: 'ok' | 'bad'): void => {
      const element = this.readouts.get(key);
      if (!element) return;
      element.textContent = text;
      element.classList.toggle('sb-ok', state === 'ok');
      element.classList.toggle('sb-bad', state === 'bad');
    };
    const reference = referenceProbes(inputs);
    const errors = PROBE_KEYS.map((key, k) => {
      set(key, formatRgb(result.radiance[k]!));
      return relativeError(result.radiance[k]!, reference.radiance[k]!);
    });
    const worst = errors.reduce<number | null>(
      (a, b) => (b === null ? a : Math.max(a ?? 0, b)),
      null,
    );
    set(
      'error',
      `${formatPercent(worst)} (zenith ${formatPercent(errors[0]!)}, toward ${formatPercent(errors[1]!)}, away ${formatPercent(errors[2]!)})`,
    );
    const sun = result.sunTransmittance;
    set('sun', sun.every((t) => t === 0) ? '0, 0, 0 (the sun has set)' : formatRgb(sun));
    if (this.swatch) {
      const peak = Math.max(...sun, 1e-30);
      const [r, g, b] = sun.map((t) => Math.round(255 * srgbEncode(t / peak)));
      this.swatch.style.background = sun.every((t) => t === 0) ? '#000' : `rgb(${r}, ${g}, ${b})`;
      this.swatch.title = 'Colour of the direct sun, T_sun normalised to its largest channel';
    }
    const zenith = result.radiance[0]!;
    set(
      'zenith-ratio',
      zenith[0] > 0 ? formatNumber(zenith[2] / zenith[0], 4) : 'no sky light (scattering off)',
    );
    set('sun-ratio', sun[2] > 0 ? formatNumber(sun[0] / sun[2], 4) : 'no direct sun');

    const work = `N = ${inputs.steps} view samples × M = ${inputs.sunSteps} sun samples per pixel`;
    const probeHow =
      result.timing === 'gpu-timestamp'
        ? 'GPU timestamp query'
        : result.timing === 'gpu-wall'
          ? 'wall time; this GPU has no timestamp queries'
          : 'CPU wall time';
    if (this.cost) {
      this.cost.textContent =
        backend.kind === 'gpu'
          ? `WebGPU (${backend.gpu.adapterDescription}): panorama ${CANVAS_WIDTH}×${CANVAS_HEIGHT}, ${work}, in ${formatMilliseconds(result.pictureMilliseconds)} per frame (wall time, submit to done); probes in ${formatMilliseconds(result.probeMilliseconds)} (${probeHow}).`
          : `CPU fallback: panorama ${CANVAS_WIDTH / CPU_SCALE}×${CANVAS_HEIGHT / CPU_SCALE}, ${work}, in ${formatMilliseconds(result.pictureMilliseconds)}; probes in ${formatMilliseconds(result.probeMilliseconds)} (${probeHow}, float64 twin).`;
    }
    if (this.canvas) {
      const probes = probesFor(inputs);
      this.canvas.setAttribute(
        'aria-label',
        `Panorama of the sky toward the sun, 120° wide, from 5° below the horizon to 85° above, with the sun at ${formatNumber(inputs.sunElevationDeg, 3)}° elevation; ` +
          (inputs.scattering
            ? `zenith blue-to-red radiance ratio ${formatNumber(zenith[0] > 0 ? zenith[2] / zenith[0] : 0, 3)} (${probes.length} probe directions listed beside it).`
            : 'scattering is off, so the sky is black and the sun white.'),
      );
    }
  }
}

export function defineRayleighSky(): void {
  if (!customElements.get('sb-rayleigh-sky'))
    customElements.define('sb-rayleigh-sky', RayleighSkyElement);
}
