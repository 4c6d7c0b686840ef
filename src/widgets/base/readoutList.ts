// A widget's readout list: labelled values (`data-readout` keys, marked ok or
// bad) and a live cost line under them.

export class ReadoutList {
  /** The cost line (what ran where, and how long it took). */
  readonly cost: HTMLElement;
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
    this.cost = document.createElement('p');
    this.cost.className = 'sb-cost';
    this.cost.setAttribute('aria-live', 'polite');
    container.append(list, this.cost);
  }

  set(key: string, text: string, state?: 'ok' | 'bad'): void {
    const element = this.values.get(key);
    if (!element) return;
    element.textContent = text;
    element.classList.toggle('sb-ok', state === 'ok');
    element.classList.toggle('sb-bad', state === 'bad');
  }
}
