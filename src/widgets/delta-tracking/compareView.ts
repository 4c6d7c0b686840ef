// The DOM of the delta-tracking widget's comparison view: two labelled rows of
// five small images (equal samples, equal time), each with its estimator, spp,
// RMSE, mean bias and time written under it as text (so screen readers and
// screenshots read the same numbers), one colour scale for all ten, a status
// line, and the readout table of cost per sample, lookups and sweep slopes.
import { formatMilliseconds, formatNumber } from '../base/format.ts';
import { gradientCss, imageCanvas } from '../base/imagePanel.ts';
import { paintEstimate, paintVariance } from './cpuBackend.ts';
import { ESTIMATOR_ORDER, FIT_MIN_SPP, type EstimatorKey } from './compare.ts';
import {
  ESTIMATOR_NAMES,
  IMAGE_HEIGHT,
  IMAGE_WIDTH,
  transmittanceColour,
  varianceColour,
  type ImageStatistics,
  type TrackingImage,
} from './model.ts';

export type CompareRow = 'samples' | 'time';

/**
 * Top of the variance colour scale shared by all ten images: 1/4 is the largest
 * variance T(1 − T) of a 0/1 estimate (delta tracking, physics.md §4.1), so delta
 * tracking spans the scale and every lower-variance estimator is visibly darker.
 * A ratio estimator with a majorant that is too low can exceed it; its pixels
 * saturate at the top colour, and the caption gives the number.
 */
export const VARIANCE_SCALE = 0.25;

/** What one image of the grid shows and says. */
export interface CompareCell {
  image: TrackingImage;
  variance: Float64Array;
  stats: ImageStatistics;
  milliseconds: number;
  /** Mean over the pixels of the variance of one estimate. */
  meanVariance: number;
  /** Bias beyond 5 standard errors (the book's threshold, physics.md §4.5). */
  biased: boolean;
}

/** "+4.2×10⁻⁴" or "-0.031": the sign of a bias always shown. */
export function signed(value: number, digits: number): string {
  const text = formatNumber(value, digits);
  return value > 0 ? `+${text}` : text;
}

interface CellElements {
  canvas: HTMLCanvasElement;
  name: HTMLElement;
  lines: HTMLElement;
}

export class CompareGrid {
  readonly element: HTMLElement;
  private readonly rowTitles = new Map<CompareRow, HTMLElement>();
  private readonly cells = new Map<string, CellElements>();
  private readonly data = new Map<string, CompareCell>();
  private readonly legendBar: HTMLElement;
  private readonly legendLow: HTMLElement;
  private readonly legendTop: HTMLElement;
  private readonly legendName: HTMLElement;
  readonly status: HTMLElement;

  constructor(idPrefix: string) {
    this.element = document.createElement('div');
    this.element.className = 'sb-dt-compare';
    const legend = document.createElement('div');
    legend.className = 'sb-image-scale sb-dt-legend';
    this.legendName = document.createElement('span');
    this.legendLow = document.createElement('span');
    this.legendBar = document.createElement('span');
    this.legendBar.className = 'sb-image-scale-bar';
    this.legendBar.setAttribute('aria-hidden', 'true');
    this.legendTop = document.createElement('span');
    this.legendTop.dataset['readout'] = 'grid-scale';
    legend.append(this.legendName, this.legendLow, this.legendBar, this.legendTop);
    this.element.appendChild(legend);

    for (const row of ['samples', 'time'] as const) {
      const group = document.createElement('div');
      group.className = 'sb-dt-row';
      group.dataset['row'] = row;
      group.setAttribute('role', 'group');
      const title = document.createElement('p');
      title.className = 'sb-dt-row-title';
      title.id = `${idPrefix}-row-${row}`;
      group.setAttribute('aria-labelledby', title.id);
      this.rowTitles.set(row, title);
      const cells = document.createElement('div');
      cells.className = 'sb-dt-cells';
      for (const key of ESTIMATOR_ORDER) {
        const figure = document.createElement('figure');
        figure.className = 'sb-dt-cell';
        figure.dataset['estimator'] = key;
        const canvas = imageCanvas(ESTIMATOR_NAMES[key] ?? key, IMAGE_WIDTH, IMAGE_HEIGHT);
        const caption = document.createElement('figcaption');
        const name = document.createElement('strong');
        name.className = 'sb-dt-cell-name';
        name.textContent = ESTIMATOR_NAMES[key] ?? key;
        const lines = document.createElement('span');
        lines.className = 'sb-dt-cell-lines';
        lines.textContent = '…';
        caption.append(name, lines);
        figure.append(canvas, caption);
        cells.appendChild(figure);
        this.cells.set(`${row}:${key}`, { canvas, name, lines });
      }
      group.append(title, cells);
      this.element.appendChild(group);
    }
    this.status = document.createElement('p');
    this.status.className = 'sb-dt-compare-status';
    this.status.setAttribute('aria-live', 'polite');
    this.element.appendChild(this.status);
  }

  setRowTitle(row: CompareRow, text: string): void {
    const title = this.rowTitles.get(row);
    if (title) title.textContent = text;
  }

  /** Stores a cell's result and writes its caption (painting waits for paint()). */
  setCell(row: CompareRow, key: EstimatorKey, cell: CompareCell): void {
    this.data.set(`${row}:${key}`, cell);
    const elements = this.cells.get(`${row}:${key}`);
    if (!elements) return;
    const { image, stats, milliseconds } = cell;
    const name = ESTIMATOR_NAMES[key] ?? key;
    const rmse = formatNumber(stats.rmse, 3);
    const bias = signed(stats.bias, 2);
    const variance = image.spp < 2 ? 'needs spp ≥ 2' : formatNumber(cell.meanVariance, 3);
    const lines = [
      `spp ${image.spp} · ${formatMilliseconds(milliseconds)}`,
      `RMSE ${rmse}`,
      `bias ${bias}${cell.biased ? ' (biased)' : ''}`,
      `mean Var ${variance}`,
    ];
    elements.lines.replaceChildren(
      ...lines.map((text, i) => {
        const line = document.createElement('span');
        line.textContent = text;
        if (i === 2 && cell.biased) line.className = 'sb-dt-biased';
        return line;
      }),
    );
    elements.canvas.dataset['spp'] = String(image.spp);
    elements.canvas.setAttribute(
      'aria-label',
      `${name}, ${row === 'samples' ? 'equal samples' : 'equal time'}: spp ${image.spp}, ${formatMilliseconds(milliseconds)}, RMSE ${rmse}, mean bias ${bias}${cell.biased ? ', biased' : ''}`,
    );
  }

  cell(row: CompareRow, key: EstimatorKey): CompareCell | undefined {
    return this.data.get(`${row}:${key}`);
  }

  /** Paints all ten images: the estimates, or the variances on one shared scale. */
  paint(mode: 'estimate' | 'variance'): void {
    if (mode === 'estimate') {
      this.legendName.textContent = 'Estimated T:';
      this.legendLow.textContent = '0';
      this.legendTop.textContent = '1';
      this.legendBar.style.background = gradientCss(transmittanceColour);
    } else {
      this.legendName.textContent = 'Variance of one estimate:';
      this.legendLow.textContent = '0';
      this.legendTop.textContent = formatNumber(VARIANCE_SCALE, 2);
      this.legendBar.style.background = gradientCss((x) => varianceColour(x, 1));
    }
    for (const [id, cell] of this.data) {
      const elements = this.cells.get(id);
      if (!elements) continue;
      if (mode === 'estimate') paintEstimate(elements.canvas, cell.image);
      else paintVariance(elements.canvas, cell.image, cell.variance, VARIANCE_SCALE);
    }
  }
}

/** The comparison's readout table: one row per estimator. */
export class CompareTable {
  readonly element: HTMLTableElement;
  private readonly values = new Map<string, HTMLElement>();

  constructor() {
    this.element = document.createElement('table');
    this.element.className = 'sb-dt-table';
    const caption = document.createElement('caption');
    caption.textContent = `Cost and convergence per estimator. ms per sample: median of the calibration renders. Sweep slopes: RMSE ∝ time^p and ∝ spp^p, fitted over spp ≥ ${FIT_MIN_SPP}.`;
    const head = document.createElement('thead');
    const headRow = document.createElement('tr');
    for (const text of [
      'Estimator',
      'ms per sample',
      'Lookups per estimate',
      'p vs time',
      'p vs spp',
    ]) {
      const cell = document.createElement('th');
      cell.scope = 'col';
      cell.textContent = text;
      headRow.appendChild(cell);
    }
    head.appendChild(headRow);
    const body = document.createElement('tbody');
    for (const key of ESTIMATOR_ORDER) {
      const row = document.createElement('tr');
      const name = document.createElement('th');
      name.scope = 'row';
      name.textContent = ESTIMATOR_NAMES[key] ?? key;
      row.appendChild(name);
      for (const column of ['cost', 'lookups', 'slope', 'spp-slope']) {
        const cell = document.createElement('td');
        cell.dataset['readout'] = `${column}-${key}`;
        cell.textContent = '–';
        row.appendChild(cell);
        this.values.set(`${column}-${key}`, cell);
      }
      body.appendChild(row);
    }
    this.element.append(caption, head, body);
  }

  set(column: 'cost' | 'lookups' | 'slope' | 'spp-slope', key: EstimatorKey, text: string): void {
    const cell = this.values.get(`${column}-${key}`);
    if (cell) cell.textContent = text;
  }
}
