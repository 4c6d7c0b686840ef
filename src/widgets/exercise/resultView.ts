// Draws one grading outcome: a summary line in honest words (public checks only —
// hidden tests run when graded), then per public check the verdict, points, the
// message in the chapter's words, a table of the student's values next to the
// reference's, and the check's figure with a difference view. Compile errors are a
// list of "line L, column C: message" entries that move the editor's cursor there.
import type {
  CheckFigure,
  CheckResult,
  GradeOutcome,
  SourceDiagnostic,
} from '../../grading/types.ts';
import { LinePlot } from '../base/plot.ts';
import { context2d } from '../base/canvas2d.ts';

/** Okabe–Ito colours, as the other widgets use: distinguishable with colour-vision deficiency. */
const STUDENT_COLOR = '#d55e00';
const REFERENCE_COLOR = '#0072b2';
const DIFFERENCE_COLOR = '#009e73';

function element<K extends keyof HTMLElementTagNameMap>(
  tag: K,
  className: string,
  text?: string,
): HTMLElementTagNameMap[K] {
  const node = document.createElement(tag);
  if (className) node.className = className;
  if (text !== undefined) node.textContent = text;
  return node;
}

/** The headline for an outcome; never claims more than the public checks show. */
export function outcomeSummary(outcome: GradeOutcome): { text: string; ok: boolean } {
  switch (outcome.status) {
    case 'graded': {
      const passed = outcome.checks.filter((c) => c.verdict === 'pass').length;
      const all = passed === outcome.checks.length;
      return {
        ok: all,
        text: all
          ? `Public checks passed (${passed} of ${outcome.checks.length}, ${outcome.score} of ${outcome.maxScore} points) — hidden tests run when graded.`
          : `${passed} of ${outcome.checks.length} public checks passed (${outcome.score} of ${outcome.maxScore} points). Hidden tests run when graded.`,
      };
    }
    case 'device-lost':
      // The runner drops a lost device and requests a fresh one on the next run.
      return {
        ok: false,
        text: `${outcome.message} The next run uses a fresh GPU device.`,
      };
    default:
      // The grading core words these itself (what went wrong and where to look).
      return { ok: false, text: outcome.message };
  }
}

export class ResultView {
  private readonly plots: LinePlot[] = [];

  constructor(
    private readonly container: HTMLElement,
    private readonly moveTo: (line: number, column: number) => void,
  ) {}

  clear(): void {
    for (const plot of this.plots) plot.destroy();
    this.plots.length = 0;
    this.container.replaceChildren();
  }

  /** A line of text in place of results (a stored summary, a cancelled run). */
  showMessage(text: string, state?: 'ok' | 'bad'): void {
    this.clear();
    const line = element('p', 'sb-exercise-summary', text);
    if (state) line.classList.add(state === 'ok' ? 'sb-ok' : 'sb-bad');
    this.container.appendChild(line);
  }

  show(outcome: GradeOutcome): void {
    const summary = outcomeSummary(outcome);
    this.showMessage(summary.text, summary.ok ? 'ok' : 'bad');
    if (outcome.status === 'compile-error') this.showDiagnostics(outcome.diagnostics);
    if (outcome.status !== 'graded') return;
    const list = element('ol', 'sb-exercise-checks');
    list.setAttribute('aria-label', 'Public checks');
    for (const check of outcome.checks) list.appendChild(this.checkItem(check));
    this.container.appendChild(list);
  }

  private showDiagnostics(diagnostics: readonly SourceDiagnostic[]): void {
    const list = element('ul', 'sb-exercise-diagnostics');
    list.setAttribute('aria-label', 'Compiler messages');
    for (const d of diagnostics) {
      const item = element('li', '');
      if (d.line < 1) {
        // No position (e.g. a pipeline error after compiling): the message alone.
        item.textContent = d.message;
        list.appendChild(item);
        continue;
      }
      const button = element(
        'button',
        `sb-exercise-diagnostic sb-exercise-diagnostic--${d.severity}`,
        `line ${d.line}, column ${d.column}: ${d.message}`,
      );
      button.type = 'button';
      button.title = 'Move the cursor there';
      button.addEventListener('click', () => this.moveTo(d.line, d.column));
      item.appendChild(button);
      list.appendChild(item);
    }
    this.container.appendChild(list);
  }

  private checkItem(check: CheckResult): HTMLElement {
    const item = element('li', `sb-exercise-check sb-exercise-check--${check.verdict}`);
    item.dataset['verdict'] = check.verdict;
    const head = element('p', 'sb-exercise-check-head');
    head.append(
      element(
        'span',
        check.verdict === 'pass' ? 'sb-ok' : 'sb-bad',
        check.verdict === 'pass' ? '✓ pass' : '✗ fail',
      ),
      ` ${check.name} · ${check.points} / ${check.maxPoints} points`,
    );
    item.append(head, element('p', 'sb-exercise-check-message', check.message));
    if (check.samples && check.samples.length > 0) item.appendChild(samplesTable(check.samples));
    if (check.figure) item.appendChild(this.figure(check.figure, check.name));
    return item;
  }

  private figure(figure: CheckFigure, name: string): HTMLElement {
    const box = element('figure', 'sb-exercise-figure');
    const caption = element('figcaption', '');
    box.appendChild(caption);
    if (figure.kind === 'series') {
      caption.textContent = `${name}: your output and the reference, and their difference.`;
      this.linePlots(box, figure.xLabel, figure.x, figure.student, figure.reference, 'value');
    } else if (figure.kind === 'histogram') {
      caption.textContent = `${name}: your samples (filled) against what the analytic density predicts (outlined), as count ÷ bin width; below, observed − expected count per bin.`;
      const centers = figure.edges
        .slice(0, -1)
        .map((e, i) => 0.5 * (e + (figure.edges[i + 1] ?? e)));
      box.appendChild(barChart(figure.edges, figure.observed, figure.expected, figure.xLabel));
      this.linePlots(box, figure.xLabel, centers, figure.observed, figure.expected, 'count', true);
    } else {
      caption.textContent = `${name}: your image, the reference, and the difference (orange: yours brighter, blue: darker).`;
      box.appendChild(imageTriptych(figure.width, figure.height, figure.student, figure.reference));
    }
    return box;
  }

  /** Student and reference over x, then student − reference on its own axis. */
  private linePlots(
    box: HTMLElement,
    xLabel: string,
    x: readonly number[],
    student: readonly number[],
    reference: readonly number[],
    yLabel: string,
    differenceOnly = false,
  ): void {
    if (!differenceOnly) {
      const main = element('div', 'sb-plot sb-exercise-plot');
      box.appendChild(main);
      const plot = new LinePlot(main, { xLabel, yLabel, height: 180 });
      plot.update(x, [
        { label: 'yours', color: STUDENT_COLOR, values: student },
        { label: 'reference', color: REFERENCE_COLOR, dash: [8, 4], values: reference },
      ]);
      this.plots.push(plot);
    }
    const diffBox = element('div', 'sb-plot sb-exercise-plot');
    box.appendChild(diffBox);
    const diff = new LinePlot(diffBox, { xLabel, yLabel: 'yours − ref.', height: 180 });
    diff.update(x, [
      {
        label: 'difference',
        color: DIFFERENCE_COLOR,
        values: student.map((s, i) => s - (reference[i] ?? Number.NaN)),
      },
    ]);
    this.plots.push(diff);
  }
}

function samplesTable(samples: NonNullable<CheckResult['samples']>): HTMLElement {
  const table = element('table', 'sb-exercise-samples');
  const head = element('thead', '');
  const row = element('tr', '');
  for (const title of ['Arguments', 'Yours', 'Reference']) {
    const th = element('th', '', title);
    th.scope = 'col';
    row.appendChild(th);
  }
  head.appendChild(row);
  const body = element('tbody', '');
  for (const sample of samples) {
    const tr = element('tr', '');
    tr.append(
      element('td', '', sample.args),
      element('td', '', sample.student),
      element('td', '', sample.reference),
    );
    body.appendChild(tr);
  }
  table.append(head, body);
  return table;
}

/**
 * Observed (filled) against expected (outlined) bars at the bins' true positions on
 * the x axis. Bins may differ in width (equiprobable bins do), so a bar's height is
 * its count divided by its width: the bars then trace the density itself, and a
 * sampler with the wrong shape stands out against the outlines.
 */
function barChart(
  edges: readonly number[],
  observed: readonly number[],
  expected: readonly number[],
  xLabel: string,
): HTMLElement {
  const canvas = element('canvas', 'sb-exercise-bars');
  const width = 640;
  const height = 180;
  canvas.width = width;
  canvas.height = height;
  const lo = edges[0] ?? 0;
  const hi = edges[edges.length - 1] ?? 1;
  canvas.setAttribute('role', 'img');
  canvas.setAttribute(
    'aria-label',
    `Histogram of ${xLabel} over ${observed.length} bins from ${lo} to ${hi}: filled bars are your samples, outlined bars the counts the analytic density predicts (height = count ÷ bin width).`,
  );
  const context = context2d(canvas);
  if (!context) return canvas;
  const density = (counts: readonly number[], i: number): number => {
    const w = (edges[i + 1] ?? 0) - (edges[i] ?? 0);
    return w > 0 ? (counts[i] ?? 0) / w : 0;
  };
  const bins = observed.length;
  let peak = 1e-30;
  for (let i = 0; i < bins; i++) peak = Math.max(peak, density(observed, i), density(expected, i));
  const xOf = (x: number): number => ((x - lo) / (hi - lo || 1)) * (width - 2) + 1;
  const plotHeight = height - 4;
  for (let i = 0; i < bins; i++) {
    const x0 = xOf(edges[i] ?? lo);
    const x1 = xOf(edges[i + 1] ?? hi);
    const o = (density(observed, i) / peak) * plotHeight;
    const e = (density(expected, i) / peak) * plotHeight;
    context.fillStyle = STUDENT_COLOR;
    context.fillRect(x0 + 0.5, plotHeight + 4 - o, Math.max(1, x1 - x0 - 1), o);
    context.strokeStyle = REFERENCE_COLOR;
    context.lineWidth = 2;
    context.strokeRect(x0 + 0.5, plotHeight + 4 - e, Math.max(1, x1 - x0 - 1), e);
  }
  // The x axis in HTML under the canvas, so its text follows the theme.
  const axisRow = element('div', 'sb-exercise-bars-axis');
  axisRow.setAttribute('aria-hidden', 'true');
  axisRow.append(
    element('span', '', String(Number(lo.toPrecision(3)))),
    element('span', '', xLabel),
    element('span', '', String(Number(hi.toPrecision(3)))),
  );
  const wrapper = element('div', 'sb-exercise-bars-box');
  wrapper.append(canvas, axisRow);
  return wrapper;
}

/** Student | reference | difference, each scaled to the pair's common range. */
function imageTriptych(
  width: number,
  height: number,
  student: readonly number[],
  reference: readonly number[],
): HTMLElement {
  const row = element('div', 'sb-exercise-images');
  const finite = [...student, ...reference].filter(Number.isFinite);
  const lo = Math.min(0, ...finite);
  const hi = Math.max(lo + 1e-30, ...finite);
  const maxDiff = Math.max(
    1e-30,
    ...student.map((s, i) => Math.abs(s - (reference[i] ?? 0))).filter(Number.isFinite),
  );
  const panel = (label: string, pixel: (i: number) => [number, number, number]): void => {
    const canvas = element('canvas', 'sb-exercise-image');
    canvas.width = width;
    canvas.height = height;
    canvas.setAttribute('role', 'img');
    canvas.setAttribute('aria-label', label);
    const context = context2d(canvas);
    if (context) {
      const data = context.createImageData(width, height);
      for (let i = 0; i < width * height; i++) {
        const [r, g, b] = pixel(i);
        data.data.set([r, g, b, 255], 4 * i);
      }
      context.putImageData(data, 0, 0);
    }
    const figure = element('div', 'sb-exercise-image-panel');
    figure.append(canvas, element('span', '', label));
    row.appendChild(figure);
  };
  // Non-finite pixels (NaN from a student shader) show in magenta so they stand out.
  const grey = (value: number): [number, number, number] =>
    Number.isFinite(value)
      ? (Array(3).fill(Math.round((255 * (value - lo)) / (hi - lo))) as [number, number, number])
      : [255, 0, 255];
  panel('Yours', (i) => grey(student[i] ?? Number.NaN));
  panel('Reference', (i) => grey(reference[i] ?? Number.NaN));
  panel(`Difference (±${maxDiff.toPrecision(2)})`, (i) => {
    const d = (student[i] ?? Number.NaN) - (reference[i] ?? Number.NaN);
    if (!Number.isFinite(d)) return [255, 0, 255];
    const t = Math.min(1, Math.abs(d) / maxDiff);
    // Orange where the student's image is brighter, blue where darker, white where equal.
    return d > 0
      ? [255, Math.round(255 - 161 * t), Math.round(255 - 255 * t)]
      : [Math.round(255 - 255 * t), Math.round(255 - 141 * t), Math.round(255 - 77 * t)];
  });
  return row;
}
