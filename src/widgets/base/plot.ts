// Line plots through uPlot (a charting library, not hand-drawn axes). One helper
// so every widget's plots look alike and follow the page's theme.
import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import { CPU_RASTERISED } from './canvas2d.ts';
import { formatNumber } from './format.ts';

/**
 * Tick label of a logarithmic axis: decades only (1, 0.1, 0.01, 1×10⁻³, …), so
 * that small values are not rounded to "0" and the labels never crowd.
 */
export function logTickLabel(value: number): string {
  if (!(value > 0)) return '';
  const exponent = Math.round(Math.log10(value));
  if (Math.abs(Math.log10(value) - exponent) > 1e-6) return '';
  return formatNumber(10 ** exponent, 1);
}

/**
 * The element a plot draws into: a figure for assistive technology (role img) whose
 * label says what the plot shows, since the canvas uPlot draws says nothing itself.
 */
export function createPlotArea(label: string): HTMLDivElement {
  const area = document.createElement('div');
  area.className = 'sb-plot';
  area.setAttribute('role', 'img');
  area.setAttribute('aria-label', label);
  return area;
}

export interface PlotSeries {
  label: string;
  color: string;
  dash?: number[];
  /** Draw across missing values (NaN, or ≤ 0 on a log axis) instead of leaving a gap. */
  spanGaps?: boolean;
  values: ArrayLike<number>;
}

export interface LinePlotOptions {
  xLabel: string;
  yLabel: string;
  yRange?: [number, number];
  height?: number;
  /** Logarithmic y axis (base 10); values ≤ 0 have no logarithm and are left as gaps. */
  yLog?: boolean;
}

/**
 * Runs `make` (which creates canvases) with every 2D context asked for as context2d asks
 * (canvas2d.ts: rasterised on the CPU, not in the GPU process beside WebGPU). uPlot takes
 * its context when it is built and has no option for the attributes.
 */
function withCpuCanvases<T>(make: () => T): T {
  type GetContext = (
    this: HTMLCanvasElement,
    type: string,
    attributes?: object,
  ) => RenderingContext | GPUCanvasContext | null;
  const prototype = HTMLCanvasElement.prototype;
  const saved = prototype.getContext;
  // getContext's overloads (one per context type) cannot be restated one by one here.
  const original = saved as GetContext;
  const patched: GetContext = function (type, attributes) {
    return original.call(
      this,
      type,
      type === '2d' ? { ...attributes, ...CPU_RASTERISED } : attributes,
    );
  };
  prototype.getContext = patched as typeof saved;
  try {
    return make();
  } finally {
    prototype.getContext = saved;
  }
}

export class LinePlot {
  private plot: uPlot | null = null;
  private signature = '';
  /**
   * The legend's label of each series, as elements uPlot shows as they are: a label that
   * changes (chromatic-media's fitted slope, after every pass) is rewritten in place
   * instead of rebuilding the chart.
   */
  private labels: HTMLSpanElement[] = [];
  private readonly resizeObserver: ResizeObserver;
  private readonly themeObserver: MutationObserver;
  private lastData: { x: ArrayLike<number>; series: readonly PlotSeries[] } | null = null;

  constructor(
    private readonly container: HTMLElement,
    private readonly options: LinePlotOptions,
  ) {
    this.resizeObserver = new ResizeObserver(() => {
      if (!this.plot) return;
      // Presentation mode changes the type size: rebuild so the axes scale with it.
      if (this.lastData && this.fontSize() !== this.builtFontSize)
        this.update(this.lastData.x, this.lastData.series);
      else this.plot.setSize({ width: this.width(), height: this.height() });
    });
    this.resizeObserver.observe(container);
    // Axis colours are baked into the chart: rebuild it when the theme changes.
    this.themeObserver = new MutationObserver(() => {
      this.signature = '';
      if (this.lastData) this.update(this.lastData.x, this.lastData.series);
    });
    this.themeObserver.observe(document.documentElement, {
      attributes: true,
      attributeFilter: ['data-theme'],
    });
  }

  private builtFontSize = 0;

  private fontSize(): number {
    return parseFloat(getComputedStyle(this.container).fontSize) || 16;
  }

  /** The plot grows with the type size (presentation mode). */
  private height(): number {
    return Math.round(((this.options.height ?? 220) * this.fontSize()) / 16);
  }

  /**
   * The container's width, but at least 160 px: below that uPlot's axes leave no room for
   * the curves. (At 240, a plot under a narrow deck stage at 1024×768 cut it sideways.)
   */
  private width(): number {
    return Math.max(160, Math.floor(this.container.clientWidth || 480));
  }

  /** Draws x against the series; rebuilds the chart only when the series change. */
  update(x: ArrayLike<number>, series: readonly PlotSeries[]): void {
    this.lastData = { x, series };
    // Missing values (NaN; ≤ 0 on a log axis) as null, which uPlot skips: a NaN would
    // poison the axis range and hide every curve.
    const column = (values: ArrayLike<number>): (number | null)[] =>
      Array.from(values, (v) => (Number.isFinite(v) && (!this.options.yLog || v > 0) ? v : null));
    const data = [Array.from(x), ...series.map((s) => column(s.values))] as uPlot.AlignedData;
    const fontSize = this.fontSize();
    const signature = `${fontSize};${series
      .map((s) => `${s.color}|${(s.dash ?? []).join(',')}|${s.spanGaps === true}`)
      .join(';')}`;
    if (this.plot && signature === this.signature) {
      series.forEach((s, i) => {
        const label = this.labels[i];
        if (label && label.textContent !== s.label) label.textContent = s.label;
      });
      this.plot.setData(data);
      return;
    }
    this.plot?.destroy();
    this.signature = signature;
    this.builtFontSize = fontSize;
    const font = `${Math.round(fontSize * 0.75)}px system-ui, sans-serif`;
    const labelFont = `600 ${Math.round(fontSize * 0.8)}px system-ui, sans-serif`;
    // The resolved text colour of the container (theme colours are light-dark() pairs).
    const stroke = getComputedStyle(this.container).color || '#555';
    const axis = (label: string): uPlot.Axis => ({
      label,
      stroke,
      font,
      labelFont,
      size: Math.round(fontSize * 3),
      labelSize: Math.round(fontSize * 1.5),
      grid: { stroke: 'rgba(128,128,128,0.2)', width: 1 },
      ticks: { stroke: 'rgba(128,128,128,0.4)', width: 1 },
    });
    this.labels = series.map((s) => {
      const label = document.createElement('span');
      label.textContent = s.label;
      return label;
    });
    this.plot = withCpuCanvases(
      () =>
        new uPlot(
          {
            width: this.width(),
            height: this.height(),
            scales: {
              x: { time: false },
              y: {
                ...(this.options.yRange ? { range: this.options.yRange } : {}),
                ...(this.options.yLog ? { distr: 3, log: 10 } : {}),
              },
            },
            axes: [
              axis(this.options.xLabel),
              {
                ...axis(this.options.yLabel),
                ...(this.options.yLog
                  ? { values: (_: uPlot, splits: number[]) => splits.map(logTickLabel) }
                  : {}),
              },
            ],
            series: [
              { label: this.options.xLabel },
              ...series.map((s, i) => ({
                label: this.labels[i]!,
                stroke: s.color,
                width: 2,
                dash: s.dash ?? [],
                ...(s.spanGaps ? { spanGaps: true } : {}),
              })),
            ],
            cursor: { drag: { x: false, y: false } },
            hooks: {
              // The legend's values are those under the cursor: shown only while there is one.
              setCursor: [
                (u: uPlot) =>
                  this.container.classList.toggle('sb-plot-hover', u.cursor.idx != null),
              ],
            },
          },
          data,
          this.container,
        ),
    );
  }

  destroy(): void {
    this.resizeObserver.disconnect();
    this.themeObserver.disconnect();
    this.plot?.destroy();
    this.plot = null;
  }
}
