// The widget's main plot: R_d(r) per RGB channel on log–log axes through uPlot, with
// the three diffusion profiles as lines (solid, dashed, dotted) and the Monte Carlo
// bins as points with ±1 standard-error whiskers drawn in a draw hook. uPlot needs
// one x array, so the curves' grid and the Monte Carlo's bin centres are merged and
// each series has gaps (null) where it has no value (bridged for the lines). Colours
// follow the channel, dashes the method; a small HTML legend explains both.
import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import { formatNumber } from '../base/format.ts';
import { CHANNEL_NAMES, type ProfileCurves } from './model.ts';
import type { ProfileEstimate } from '../../subsurface/slabKernel.ts';

/** Channel colours, readable on the light and the dark page. */
export const CHANNEL_COLOURS = ['#d9473f', '#2f9e4f', '#3d6fd6'] as const;

const METHODS = [
  { key: 'dipole', label: 'dipole', dash: [] as number[] },
  { key: 'better', label: 'better dipole (one source, α′², d’Eon 2012)', dash: [7, 4] },
  { key: 'burley', label: 'Christensen–Burley', dash: [2, 3] },
] as const;

/** Tick label of a log axis: decades only (0.01, 0.1, 1, 10, 1×10⁻³ …), so labels never crowd. */
export function decadeLabel(value: number): string {
  if (!(value > 0)) return '';
  const exponent = Math.round(Math.log10(value));
  if (Math.abs(Math.log10(value) - exponent) > 1e-6) return '';
  return formatNumber(10 ** exponent, 1);
}

/** The lowest value shown, relative to the plot's largest (seven decades). */
const DYNAMIC_RANGE = 1e-7;

export interface ProfilePlotData {
  curves: ProfileCurves;
  /** Per channel, or null before the first Monte Carlo run. */
  monteCarlo: ProfileEstimate[] | null;
}

export class ProfilePlot {
  private plot: uPlot | null = null;
  private signature = '';
  private lastData: ProfilePlotData | null = null;
  /** MC means and standard errors in plot order, read by the draw hook. */
  private whiskers: { x: number[]; mean: number[][]; se: number[][] } | null = null;
  private readonly resizeObserver: ResizeObserver;
  private readonly themeObserver: MutationObserver;
  private builtFontSize = 0;

  constructor(private readonly container: HTMLElement) {
    this.resizeObserver = new ResizeObserver(() => {
      if (!this.plot) return;
      if (this.lastData && this.fontSize() !== this.builtFontSize) this.update(this.lastData);
      else this.plot.setSize({ width: this.width(), height: this.height() });
    });
    this.resizeObserver.observe(container);
    this.themeObserver = new MutationObserver(() => {
      this.signature = '';
      if (this.lastData) this.update(this.lastData);
    });
    this.themeObserver.observe(document.documentElement, {
      attributes: true,
      attributeFilter: ['data-theme'],
    });
  }

  private fontSize(): number {
    return parseFloat(getComputedStyle(this.container).fontSize) || 16;
  }

  private height(): number {
    return Math.round((340 * this.fontSize()) / 16);
  }

  private width(): number {
    return Math.max(260, Math.floor(this.container.clientWidth || 520));
  }

  /** Merged x (mm) and the series columns (null where a series has no point). */
  private columns(data: ProfilePlotData): { x: number[]; columns: (number | null)[][] } {
    const { curves, monteCarlo } = data;
    const mcCentres = monteCarlo?.[0]?.centres ?? [];
    // Bin 0 is the disc [0, r_min): its centre lies left of the grid, so it is left out.
    const mcIndex = mcCentres.map((_, k) => k).filter((k) => k > 0);
    const x = [...curves.radii, ...mcIndex.map((k) => mcCentres[k]!)];
    const order = x.map((_, i) => i).sort((a, b) => x[a]! - x[b]!);
    const gridLength = curves.radii.length;
    const positive = (v: number): number | null => (v > 0 && Number.isFinite(v) ? v : null);
    const columns: (number | null)[][] = [];
    for (let c = 0; c < 3; c++) {
      for (const method of METHODS) {
        const values = curves[method.key][c]!;
        columns.push(order.map((i) => (i < gridLength ? positive(values[i]!) : null)));
      }
    }
    const mean: number[][] = [];
    const se: number[][] = [];
    for (let c = 0; c < 3; c++) {
      const density = monteCarlo?.[c]?.density ?? [];
      const m = order.map((i) =>
        i < gridLength ? NaN : (density[mcIndex[i - gridLength]!]?.mean ?? NaN),
      );
      const s = order.map((i) =>
        i < gridLength ? NaN : (density[mcIndex[i - gridLength]!]?.se ?? NaN),
      );
      columns.push(m.map((v) => positive(v)));
      mean.push(m);
      se.push(s);
    }
    const sortedX = order.map((i) => x[i]!);
    this.whiskers = { x: sortedX, mean, se };
    return { x: sortedX, columns };
  }

  update(data: ProfilePlotData): void {
    this.lastData = data;
    const { x, columns } = this.columns(data);
    const plotData = [x, ...columns] as uPlot.AlignedData;
    const fontSize = this.fontSize();
    const signature = `${fontSize}`;
    if (this.plot && signature === this.signature) {
      this.plot.setData(plotData);
      return;
    }
    this.plot?.destroy();
    this.signature = signature;
    this.builtFontSize = fontSize;
    const stroke = getComputedStyle(this.container).color || '#555';
    const font = `${Math.round(fontSize * 0.75)}px system-ui, sans-serif`;
    const labelFont = `600 ${Math.round(fontSize * 0.8)}px system-ui, sans-serif`;
    // The y axis needs room for labels such as "1×10⁻⁵" beside its title.
    const axis = (label: string, size: number): uPlot.Axis => ({
      label,
      stroke,
      font,
      labelFont,
      size: Math.round(fontSize * size),
      labelSize: Math.round(fontSize * 1.5),
      grid: { stroke: 'rgba(128,128,128,0.2)', width: 1 },
      ticks: { stroke: 'rgba(128,128,128,0.4)', width: 1 },
      values: (_: uPlot, splits: number[]) => splits.map(decadeLabel),
    });
    const series: uPlot.Series[] = [{ label: 'r (mm)' }];
    for (let c = 0; c < 3; c++)
      for (const method of METHODS)
        series.push({
          label: `${method.label} ${CHANNEL_NAMES[c]}`,
          stroke: CHANNEL_COLOURS[c],
          width: method.key === 'dipole' ? 2 : 1.6,
          dash: [...method.dash],
          spanGaps: true,
          points: { show: false },
        });
    for (let c = 0; c < 3; c++)
      series.push({
        label: `Monte Carlo ${CHANNEL_NAMES[c]}`,
        stroke: CHANNEL_COLOURS[c],
        fill: CHANNEL_COLOURS[c],
        paths: () => null,
        points: { show: true, size: 6, fill: CHANNEL_COLOURS[c], stroke: CHANNEL_COLOURS[c] },
      });
    this.plot = new uPlot(
      {
        width: this.width(),
        height: this.height(),
        legend: { show: false },
        scales: {
          x: { time: false, distr: 3, log: 10 },
          y: {
            distr: 3,
            log: 10,
            range: (_u, min, max) => {
              const top = Number.isFinite(max) && max > 0 ? max * 2 : 1;
              const bottom = Number.isFinite(min) && min > 0 ? min / 2 : top * DYNAMIC_RANGE;
              return [Math.max(bottom, top * DYNAMIC_RANGE), top];
            },
          },
        },
        axes: [axis('distance r from the beam (mm)', 3.2), axis('Rd(r) (1/mm²)', 4.6)],
        series,
        cursor: { drag: { x: false, y: false } },
        hooks: { draw: [(u) => this.drawWhiskers(u)] },
      },
      plotData,
      this.container,
    );
  }

  /** ±1 standard error of every Monte Carlo bin, as a vertical whisker with caps. */
  private drawWhiskers(u: uPlot): void {
    const whiskers = this.whiskers;
    if (!whiskers) return;
    const { ctx } = u;
    const [yMin, yMax] = [u.scales['y']?.min ?? 0, u.scales['y']?.max ?? 1];
    ctx.save();
    ctx.lineWidth = Math.max(1, devicePixelRatio);
    const cap = 3 * devicePixelRatio;
    for (let c = 0; c < 3; c++) {
      ctx.strokeStyle = CHANNEL_COLOURS[c]!;
      ctx.beginPath();
      whiskers.x.forEach((x, i) => {
        const mean = whiskers.mean[c]![i]!;
        const se = whiskers.se[c]![i]!;
        if (!(mean > 0) || !(se > 0)) return;
        // On a log axis a whisker down to mean − SE ≈ 0 would run off the plot: it stops at a
        // tenth of the mean, without a cap (the uncertainty extends further).
        const bounded = mean - se >= mean / 10;
        const low = Math.max(bounded ? mean - se : mean / 10, yMin);
        const high = Math.min(mean + se, yMax);
        if (!(high > low)) return;
        const px = u.valToPos(x, 'x', true);
        const top = u.valToPos(high, 'y', true);
        const bottom = u.valToPos(low, 'y', true);
        ctx.moveTo(px, top);
        ctx.lineTo(px, bottom);
        ctx.moveTo(px - cap, top);
        ctx.lineTo(px + cap, top);
        if (bounded && mean - se > yMin) {
          ctx.moveTo(px - cap, bottom);
          ctx.lineTo(px + cap, bottom);
        }
      });
      ctx.stroke();
    }
    ctx.restore();
  }

  destroy(): void {
    this.resizeObserver.disconnect();
    this.themeObserver.disconnect();
    this.plot?.destroy();
    this.plot = null;
  }
}

/** The legend under the plot: line styles name the methods, colours the channels. */
export function profileLegend(): HTMLElement {
  const legend = document.createElement('ul');
  legend.className = 'sb-dp-legend';
  const item = (swatch: string, text: string): HTMLLIElement => {
    const li = document.createElement('li');
    li.innerHTML = `<svg width="28" height="10" aria-hidden="true">${swatch}</svg>`;
    li.append(text);
    return li;
  };
  const line = (dash: readonly number[]): string =>
    `<line x1="1" y1="5" x2="27" y2="5" stroke="currentColor" stroke-width="2" stroke-dasharray="${dash.join(' ')}"/>`;
  for (const method of METHODS) legend.appendChild(item(line(method.dash), method.label));
  legend.appendChild(
    item(
      '<line x1="14" y1="0" x2="14" y2="10" stroke="currentColor" stroke-width="1.5"/><circle cx="14" cy="5" r="3" fill="currentColor"/>',
      'Monte Carlo ± 1 SE',
    ),
  );
  CHANNEL_NAMES.forEach((name, c) =>
    legend.appendChild(
      item(
        `<rect x="8" y="1" width="12" height="8" rx="2" fill="${CHANNEL_COLOURS[c]}"/>`,
        `${name} channel`,
      ),
    ),
  );
  return legend;
}
