// A widget's readout list: labelled values (`data-readout` keys, marked ok or
// bad), the stage of refinement shown (preview or full quality) and a live cost line
// under them.

export class ReadoutList {
  /** The cost line (what ran where, and how long it took). */
  readonly cost: HTMLElement;
  /** Which stage of the refinement the picture is (empty for a widget drawn in one go). */
  readonly stage: HTMLElement;
  private readonly values = new Map<string, HTMLElement>();

  /** Appends a `<dl>` with one row per [key, label] and the cost line to container. */
  constructor(container: HTMLElement, rows: readonly (readonly [string, string])[]) {
    const list = document.createElement('dl');
    list.className = 'sb-readout';
    for (const [key, label] of rows) {
      const row = document.createElement('div');
      const term = document.createElement('dt');
      term.textContent = label;
      const value = document.createElement('dd');
      value.dataset['readout'] = key;
      row.append(term, value);
      list.appendChild(row);
      this.values.set(key, value);
    }
    this.stage = document.createElement('p');
    this.stage.className = 'sb-refinement';
    this.stage.dataset['readout'] = 'stage';
    this.stage.hidden = true;
    this.cost = document.createElement('p');
    this.cost.className = 'sb-cost';
    this.cost.setAttribute('aria-live', 'polite');
    container.append(list, this.stage, this.cost);
  }

  /**
   * Shows the stage: a preview or a job in progress ('frame', 'job') says "refining…"
   * with a pulsing dot; a complete picture that goes on improving ('background') says
   * "accumulating" with a still dot; full quality (null) just its label. The live cost
   * line is marked busy while previews follow, so a screen reader announces the
   * finished picture's cost, not every preview's; in background refinement it is
   * announced for the first complete frame, then busy until the accumulation stops.
   */
  setStage(label: string, pending: 'frame' | 'job' | 'background' | null): void {
    const refining = pending === 'frame' || pending === 'job';
    const accumulating = pending === 'background';
    const wasAccumulating = this.stage.classList.contains('sb-accumulating');
    this.stage.hidden = label === '';
    this.stage.textContent = refining
      ? `${label} · refining…`
      : accumulating
        ? `${label} · accumulating`
        : label;
    this.stage.classList.toggle('sb-refining', refining);
    this.stage.classList.toggle('sb-accumulating', accumulating);
    if (refining || (accumulating && wasAccumulating)) this.cost.setAttribute('aria-busy', 'true');
    else this.cost.removeAttribute('aria-busy');
  }

  set(key: string, text: string, state?: 'ok' | 'bad'): void {
    const element = this.values.get(key);
    if (!element) return;
    element.textContent = text;
    element.classList.toggle('sb-ok', state === 'ok');
    element.classList.toggle('sb-bad', state === 'bad');
  }
}
