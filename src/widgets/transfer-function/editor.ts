// The transfer-function editor of <sb-transfer-function>: a uPlot histogram of the
// data (log₁₀ of the voxel counts per 16 HU bin) with the piecewise-linear opacity
// drawn over it on a second axis, the area under the curve filled with the colour
// map, and one draggable handle per control point. The handles are buttons: Tab
// reaches them, the arrow keys move them (←/→ the value, ↑/↓ the opacity, with
// Shift for larger steps), so the editor works without a pointer too.
import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import type { Rgb } from '../base/imagePanel.ts';
import type { Histogram } from './phantom.ts';
import type { ControlPoint } from './model.ts';

/** The value range the editor shows (HU); points beyond it sit at the edge. */
export const EDITOR_RANGE: readonly [number, number] = [-1024, 1400];
/** Arrow-key steps: value in HU, opacity per voxel; Shift multiplies by 10. */
const KEY_STEP_HU = 10;
const KEY_STEP_OPACITY = 0.01;

export interface EditorState {
  /** Control points in increasing order of value, each with its parameter index. */
  points: readonly ControlPoint[];
  /** The emission colour at a value (sRGB in [0, 1]). */
  colourAt: (value: number) => Rgb;
}

export interface EditorCallbacks {
  /** A handle moved: parameter index (1-based) and its new value and opacity. */
  move(index: number, hu: number, opacity: number): void;
}

const css = (rgb: Rgb, alpha = 1): string =>
  `rgba(${Math.round(255 * rgb[0])}, ${Math.round(255 * rgb[1])}, ${Math.round(255 * rgb[2])}, ${alpha})`;

export class TransferEditor {
  private plot: uPlot | null = null;
  private state: EditorState | null = null;
  private handles: HTMLButtonElement[] = [];
  private readonly resizeObserver: ResizeObserver;
  private readonly themeObserver: MutationObserver;
  private builtFontSize = 0;

  constructor(
    private readonly container: HTMLElement,
    private readonly histogram: Histogram,
    private readonly callbacks: EditorCallbacks,
  ) {
    this.resizeObserver = new ResizeObserver(() => {
      if (!this.plot) return;
      if (this.fontSize() !== this.builtFontSize) this.build();
      else this.plot.setSize({ width: this.width(), height: this.height() });
    });
    this.resizeObserver.observe(container);
    // Axis colours are baked into the chart: rebuild it when the theme changes.
    this.themeObserver = new MutationObserver(() => this.build());
    this.themeObserver.observe(document.documentElement, {
      attributes: true,
      attributeFilter: ['data-theme'],
    });
  }

  private fontSize(): number {
    return parseFloat(getComputedStyle(this.container).fontSize) || 16;
  }

  private height(): number {
    return Math.round((200 * this.fontSize()) / 16);
  }

  private width(): number {
    return Math.max(260, Math.floor(this.container.clientWidth || 480));
  }

  /** Draws the current points and colours (builds the chart on first use). */
  update(state: EditorState): void {
    this.state = state;
    // The handles are placed after each draw: uPlot settles its scales asynchronously.
    if (!this.plot) this.build();
    else this.plot.redraw(false, false);
  }

  private build(): void {
    this.plot?.destroy();
    this.handles = [];
    const fontSize = this.fontSize();
    this.builtFontSize = fontSize;
    const font = `${Math.round(fontSize * 0.75)}px system-ui, sans-serif`;
    const labelFont = `600 ${Math.round(fontSize * 0.8)}px system-ui, sans-serif`;
    const stroke = getComputedStyle(this.container).color || '#555';
    const axis = (label: string, scale: string, side: uPlot.Axis.Side): uPlot.Axis => ({
      label,
      scale,
      side,
      stroke,
      font,
      labelFont,
      size: Math.round(fontSize * 2.8),
      labelSize: Math.round(fontSize * 1.4),
      grid: { show: side === 3, stroke: 'rgba(128,128,128,0.2)', width: 1 },
      ticks: { stroke: 'rgba(128,128,128,0.4)', width: 1 },
    });
    const { edges, width, counts } = this.histogram;
    const centres = edges.map((e) => e + width / 2);
    const logCounts = counts.map((c) => Math.log10(1 + c));
    const peak = Math.max(...logCounts);
    this.plot = new uPlot(
      {
        width: this.width(),
        height: this.height(),
        legend: { show: false },
        cursor: { show: false, drag: { x: false, y: false } },
        scales: {
          x: { time: false, range: [EDITOR_RANGE[0], EDITOR_RANGE[1]] },
          count: { range: [0, Math.ceil(peak + 0.2)] },
          alpha: { range: [0, 1] },
        },
        axes: [
          { ...axis('value (HU)', 'x', 2), grid: { show: false } },
          axis('log₁₀(voxels + 1)', 'count', 3),
          axis('opacity per voxel α', 'alpha', 1),
        ],
        series: [
          { label: 'HU' },
          {
            label: 'log₁₀(voxels + 1)',
            scale: 'count',
            stroke: 'rgba(128,128,128,0.7)',
            fill: 'rgba(128,128,128,0.28)',
            width: 1,
            paths: uPlot.paths.bars!({ size: [1, Infinity], gap: 0 }),
            points: { show: false },
          },
        ],
        hooks: {
          draw: [
            (u) => {
              this.drawCurve(u, stroke);
              this.placeHandles();
            },
          ],
        },
      },
      [centres, logCounts],
      this.container,
    );
    const layer = document.createElement('div');
    layer.className = 'sb-tf-handles';
    this.plot.over.appendChild(layer);
    const count = this.state?.points.length ?? 0;
    for (let k = 0; k < count; k++) layer.appendChild(this.makeHandle(k));
  }

  /** The opacity curve over the histogram, filled with the colour map, and a colour strip. */
  private drawCurve(u: uPlot, stroke: string): void {
    const state = this.state;
    if (!state || state.points.length === 0) return;
    const ctx = u.ctx;
    const { left, top, width, height } = u.bbox;
    const px = (hu: number): number =>
      Math.round(u.valToPos(Math.min(Math.max(hu, EDITOR_RANGE[0]), EDITOR_RANGE[1]), 'x', true));
    const py = (alpha: number): number => Math.round(u.valToPos(alpha, 'alpha', true));
    const gradient = ctx.createLinearGradient(left, 0, left + width, 0);
    const samples = 24;
    for (let k = 0; k <= samples; k++) {
      const hu = EDITOR_RANGE[0] + ((EDITOR_RANGE[1] - EDITOR_RANGE[0]) * k) / samples;
      gradient.addColorStop(k / samples, css(state.colourAt(hu), 0.7));
    }
    // The curve is flat beyond the end points: extend it to the plot's edges.
    const first = state.points[0]!;
    const last = state.points[state.points.length - 1]!;
    const path: [number, number][] = [
      [left, py(first.opacity)],
      ...state.points.map((p): [number, number] => [px(p.hu), py(p.opacity)]),
      [left + width, py(last.opacity)],
    ];
    ctx.save();
    ctx.beginPath();
    ctx.rect(left, top, width, height);
    ctx.clip();
    ctx.beginPath();
    ctx.moveTo(left, py(0));
    for (const [x, y] of path) ctx.lineTo(x, y);
    ctx.lineTo(left + width, py(0));
    ctx.closePath();
    ctx.fillStyle = gradient;
    ctx.fill();
    ctx.beginPath();
    path.forEach(([x, y], k) => (k === 0 ? ctx.moveTo(x, y) : ctx.lineTo(x, y)));
    ctx.lineWidth = 2 * devicePixelRatio;
    ctx.strokeStyle = stroke;
    ctx.stroke();
    // A strip of the colour map along the bottom, visible where the opacity is 0.
    const strip = Math.round(6 * devicePixelRatio);
    ctx.fillStyle = gradient;
    ctx.globalAlpha = 1;
    ctx.fillRect(left, top + height - strip, width, strip);
    ctx.restore();
  }

  private makeHandle(order: number): HTMLButtonElement {
    const handle = document.createElement('button');
    handle.type = 'button';
    handle.className = 'sb-tf-handle';
    handle.dataset['order'] = String(order);
    handle.addEventListener('pointerdown', (event) => {
      handle.setPointerCapture(event.pointerId);
      handle.focus();
      event.preventDefault();
      event.stopPropagation();
    });
    handle.addEventListener('pointermove', (event) => {
      if (!handle.hasPointerCapture(event.pointerId) || !this.plot) return;
      const rect = this.plot.over.getBoundingClientRect();
      const hu = this.plot.posToVal(event.clientX - rect.left, 'x');
      const alpha = this.plot.posToVal(event.clientY - rect.top, 'alpha');
      this.moveTo(order, hu, alpha);
    });
    handle.addEventListener('keydown', (event) => {
      const point = this.state?.points[order];
      if (!point) return;
      const scale = event.shiftKey ? 10 : 1;
      const moves: Record<string, [number, number]> = {
        ArrowLeft: [-KEY_STEP_HU * scale, 0],
        ArrowRight: [KEY_STEP_HU * scale, 0],
        ArrowUp: [0, KEY_STEP_OPACITY * scale],
        ArrowDown: [0, -KEY_STEP_OPACITY * scale],
      };
      const move = moves[event.key];
      if (!move) return;
      event.preventDefault();
      event.stopPropagation();
      this.moveTo(order, point.hu + move[0], point.opacity + move[1]);
    });
    return handle;
  }

  /** Moves point `order` (in value order), kept between its neighbours and in range. */
  private moveTo(order: number, hu: number, alpha: number): void {
    const points = this.state?.points;
    const point = points?.[order];
    if (!points || !point) return;
    const low = points[order - 1]?.hu ?? -1024;
    const high = points[order + 1]?.hu ?? 3071;
    const value = Math.round(Math.min(Math.max(hu, low), high));
    const opacity = Math.round(Math.min(Math.max(alpha, 0), 1) * 100) / 100;
    // Show the move at once: the next key press or pointer event builds on it even
    // before the widget has rendered the new state and called update().
    if (this.state) {
      this.state = {
        ...this.state,
        points: points.map((p, k) => (k === order ? { ...p, hu: value, opacity } : p)),
      };
      this.plot?.redraw(false, false);
    }
    this.callbacks.move(point.index, value, opacity);
  }

  private placeHandles(): void {
    const plot = this.plot;
    const state = this.state;
    if (!plot || !state) return;
    const layer = plot.over.querySelector('.sb-tf-handles');
    if (!layer) return;
    while (layer.children.length < state.points.length)
      layer.appendChild(this.makeHandle(layer.children.length));
    this.handles = [...layer.querySelectorAll<HTMLButtonElement>('.sb-tf-handle')];
    state.points.forEach((p, order) => {
      const handle = this.handles[order];
      if (!handle) return;
      const hu = Math.min(Math.max(p.hu, EDITOR_RANGE[0]), EDITOR_RANGE[1]);
      handle.style.left = `${plot.valToPos(hu, 'x')}px`;
      handle.style.top = `${plot.valToPos(p.opacity, 'alpha')}px`;
      const label = `Control point ${order + 1}: ${p.hu} HU, opacity ${p.opacity.toFixed(2)}. Arrow keys move it (Shift: faster).`;
      handle.setAttribute('aria-label', label);
      handle.title = `${p.hu} HU, α = ${p.opacity.toFixed(2)}`;
    });
  }

  destroy(): void {
    this.resizeObserver.disconnect();
    this.themeObserver.disconnect();
    this.plot?.destroy();
    this.plot = null;
  }
}
