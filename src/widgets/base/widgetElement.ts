// The shared shell of every widget (DESIGN.md contract 2): a custom element whose
// attributes are its parameters (clamped and reported when invalid), labelled
// form controls generated from the parameter schema, state in the URL hash,
// presentation mode (key F or the button, Esc to leave, number keys for presets),
// visible notices, and rendering only while on screen. A failure inside a widget
// is shown inside it and never escapes to the page.
import { HeightHold } from './heightHold.ts';
import {
  encodeParameters,
  parseParameters,
  withCurrentNames,
  type NumberParameter,
  type ChoiceParameter,
  type ParameterValues,
  type WidgetEntry,
} from '../parameters.ts';
import {
  STATE_VERSION,
  readStateVersion,
  readWidgetState,
  widgetLink,
  writeWidgetState,
} from './urlState.ts';
import { snapshotCanvases } from './print.ts';
import { ThrottledWriter } from './throttledWriter.ts';
import { embedHeight, embedUrl, fullState, iframeSnippet } from './embedCode.ts';
import { siteUrl } from './siteUrl.ts';

import type { Preset } from './definition.ts';

export type { Preset };

/** Hash keys a widget understands besides its parameters. */
const STATE_KEYS = new Set(['present']);

export type NoticeKind = 'info' | 'warning' | 'error';

let instanceCounter = 0;

/** The widgets on the page, for printing (see print.ts). */
const connectedWidgets = new Set<WidgetElement>();

/**
 * Copies every widget's current picture for printing. `beforeprint` cannot wait, so
 * a figure that has never drawn (it was never on screen) prints a note instead; the
 * book's print command (src/book/print.ts) draws them all first (renderAllForPrint).
 */
export function snapshotAllForPrint(): void {
  for (const widget of connectedWidgets) widget.snapshotForPrint();
}

/** Draws every widget on the page, one after another, then copies them for printing. */
export async function renderAllForPrint(
  progress?: (done: number, total: number) => void,
): Promise<void> {
  const widgets = [...connectedWidgets];
  for (const [index, widget] of widgets.entries()) {
    progress?.(index, widgets.length);
    await widget.renderForPrint();
  }
  progress?.(widgets.length, widgets.length);
}

if (typeof window !== 'undefined') window.addEventListener('beforeprint', snapshotAllForPrint);

export abstract class WidgetElement extends HTMLElement {
  /** The widget's schema; set by each subclass. */
  protected abstract readonly entry: WidgetEntry;
  /** Presets recalled by the number keys 1–9. */
  protected presets: readonly Preset[] = [];

  protected values: ParameterValues = {};
  private initialValues: ParameterValues = {};
  private root: HTMLElement | null = null;
  private noticeArea: HTMLElement | null = null;
  private readonly notices = new Map<string, HTMLElement>();
  private readonly controlInputs = new Map<string, HTMLInputElement[] | HTMLSelectElement>();
  private visible = false;
  private dirty = true;
  private rendering = false;
  private frameRequest: number | null = null;
  private observer: IntersectionObserver | null = null;
  private presentButton: HTMLButtonElement | null = null;
  /** Keeps the widget's body from shrinking back as its numbers change (heightHold.ts). */
  private bodyHold: HeightHold | null = null;
  protected widgetId = '';

  /** Builds the widget's own drawing area (canvas, plot) inside the stage. */
  protected abstract buildStage(stage: HTMLElement): void;
  /** Builds the readout area (numbers, costs) under the controls. */
  protected abstract buildReadout(readout: HTMLElement): void;
  /** Draws the current `values`. May be async (GPU work); errors are caught and shown. */
  protected abstract render(): Promise<void> | void;

  connectedCallback(): void {
    connectedWidgets.add(this);
    if (this.root) {
      // Moved in the DOM (or put back): the observer was dropped on disconnect, so
      // observe again and draw again once on screen.
      this.observe();
      if (this.isPresenting()) document.addEventListener('keydown', this.documentEscapeListener);
      this.scheduleRender();
      return;
    }
    instanceCounter += 1;
    const sameKind = [...document.querySelectorAll(this.localName)].indexOf(this) + 1;
    this.widgetId = this.id || `${this.entry.name}-${sameKind > 0 ? sameKind : instanceCounter}`;
    const attributes = parseParameters(this.entry.parameters, (name) => this.getAttribute(name));
    this.initialValues = { ...attributes.values };
    // A link written before a parameter was renamed names it by its alias.
    const fromUrl = withCurrentNames(this.entry.parameters, readWidgetState(this.widgetId));
    const merged = parseParameters(
      this.entry.parameters,
      (name) => fromUrl.get(name) ?? this.getAttribute(name),
    );
    this.values = merged.values;

    try {
      this.buildShell();
    } catch (error) {
      this.textContent = `This figure could not be built: ${String(error)}`;
      return;
    }
    for (const warning of new Set([...attributes.warnings, ...merged.warnings])) {
      this.showNotice(`param:${warning}`, 'warning', warning);
    }
    this.reportLinkProblems(fromUrl);
    if (fromUrl.get('present') === '1') this.setPresenting(true);
    this.observe();
  }

  /** Draws while the shell is on screen (IntersectionObserver reports at once on observe). */
  private observe(): void {
    this.observer?.disconnect();
    this.observer = new IntersectionObserver((entries) => {
      this.visible = entries.some((entry) => entry.isIntersecting);
      if (this.visible && this.dirty) this.scheduleRender();
    });
    // Observe the shell, not the host: in presentation mode the shell is fixed to the
    // viewport while the (then empty) host may sit off screen.
    if (this.root) this.observer.observe(this.root);
  }

  /** Off the page: stop observing and drop a requested frame (connectedCallback resumes). */
  disconnectedCallback(): void {
    // A deferred URL write of a drag is not lost when the widget goes.
    this.stateWriter.flush();
    connectedWidgets.delete(this);
    this.observer?.disconnect();
    this.observer = null;
    this.visible = false;
    document.removeEventListener('keydown', this.documentEscapeListener);
    if (this.frameRequest !== null) {
      cancelAnimationFrame(this.frameRequest);
      this.frameRequest = null;
      this.dirty = true;
    }
  }

  /**
   * Forgets the built shell so that the next connection builds the widget anew;
   * subclasses release their GPU resources and subscriptions first (definedElement.ts).
   */
  protected forgetShell(): void {
    this.observer?.disconnect();
    this.observer = null;
    this.root = null;
    this.noticeArea = null;
    this.notices.clear();
    this.controlInputs.clear();
    this.presentButton = null;
    this.bodyHold?.disconnect();
    this.bodyHold = null;
    this.replaceChildren();
  }

  /** A link from a newer build, or with settings this widget does not know, opens anyway and says so. */
  private reportLinkProblems(fromUrl: Map<string, string>): void {
    const version = readStateVersion();
    if (fromUrl.size > 0 && !(version >= 1 && version <= STATE_VERSION)) {
      this.showNotice(
        'link-version',
        'warning',
        `This link uses format version “${String(version)}”, which this book does not know; settings were read as version ${STATE_VERSION} and checked.`,
      );
    }
    const known = new Set(this.entry.parameters.map((p) => p.name));
    for (const key of fromUrl.keys()) {
      if (!known.has(key) && !STATE_KEYS.has(key)) {
        this.showNotice(
          `link-unknown:${key}`,
          'warning',
          `Ignored the unknown setting “${key}” in the link.`,
        );
      }
    }
  }

  private buildShell(): void {
    this.replaceChildren();
    const root = document.createElement('section');
    root.className = 'sb-widget';
    const titleId = `${this.widgetId}-title`;
    root.setAttribute('aria-labelledby', titleId);
    root.innerHTML = `
      <div class="sb-widget-header">
        <p class="sb-widget-title" id="${titleId}"></p>
        <div class="sb-widget-tools">
          <button type="button" class="sb-button" data-action="present" aria-pressed="false"
            title="Presentation mode (F); Esc leaves it">Present</button>
          <div class="sb-copy">
            <button type="button" class="sb-button" data-action="copy-menu"
              aria-expanded="false" aria-controls="${this.widgetId}-copy">Copy</button>
            <div class="sb-copy-menu" id="${this.widgetId}-copy" role="group"
              aria-label="Copy this figure" hidden>
              <button type="button" class="sb-button" data-action="link"
                title="Copy a link that restores this figure exactly">Copy link</button>
              <button type="button" class="sb-button" data-action="embed"
                title="Copy an iframe that shows this figure, in this state, in another page">Copy embed code</button>
            </div>
          </div>
          <span class="sb-copy-status" role="status"></span>
        </div>
      </div>
      <div class="sb-notices"></div>
      <div class="sb-widget-body">
        <div class="sb-stage"></div>
        <div class="sb-side">
          <form class="sb-controls" aria-label="Parameters"></form>
          <div class="sb-readout-area"></div>
        </div>
      </div>`;
    const title = root.querySelector('.sb-widget-title');
    if (title) title.textContent = this.entry.title;
    this.appendChild(root);
    this.root = root;
    this.noticeArea = root.querySelector('.sb-notices');
    this.presentButton = root.querySelector('[data-action="present"]');
    this.presentButton?.addEventListener('click', () => this.setPresenting(!this.isPresenting()));
    this.buildCopyMenu(root);

    const controls = root.querySelector<HTMLFormElement>('.sb-controls');
    if (controls) {
      controls.addEventListener('submit', (event) => event.preventDefault());
      for (const parameter of this.entry.parameters)
        controls.appendChild(this.buildControl(parameter));
      if (this.presets.length > 0) controls.appendChild(this.buildPresetHint());
    }
    const stage = root.querySelector<HTMLElement>('.sb-stage');
    if (stage) this.buildStage(stage);
    const readout = root.querySelector<HTMLElement>('.sb-readout-area');
    if (readout) this.buildReadout(readout);
    // The body (stage and side) keeps its height while readouts, status lines and captions
    // change. Not on a lecture slide: the deck fits each slide by laying the figure out
    // at several widths and zooms, and holds its controls still itself
    // (book/deck/fit.ts); a height held from another layout would skew what it measures.
    const body = root.querySelector<HTMLElement>('.sb-widget-body');
    this.bodyHold?.disconnect();
    this.bodyHold = body && !this.closest('.deck-slide') ? new HeightHold(body) : null;
    // The same listener object each time, so a shell built again adds no second one.
    this.addEventListener('keydown', this.keyListener);
    root.addEventListener('fullscreenchange', this.fullscreenListener);
  }

  private buildControl(parameter: NumberParameter | ChoiceParameter): HTMLElement {
    const wrapper = document.createElement('div');
    wrapper.className = 'sb-control';
    const id = `${this.widgetId}-${parameter.name}`;
    const label = document.createElement('label');
    label.htmlFor = id;
    label.textContent = parameter.label;
    label.title = parameter.description;
    if (parameter.kind === 'number' && parameter.unit) {
      const unit = document.createElement('span');
      unit.className = 'sb-unit';
      unit.textContent = ` (${parameter.unit})`;
      label.appendChild(unit);
    }
    wrapper.appendChild(label);
    if (parameter.kind === 'choice') {
      const select = document.createElement('select');
      select.id = id;
      select.name = parameter.name;
      for (const choice of parameter.choices) {
        const option = document.createElement('option');
        option.value = choice.value;
        option.textContent = choice.label;
        select.appendChild(option);
      }
      select.value = String(this.values[parameter.name]);
      select.addEventListener('change', () => this.setValue(parameter.name, select.value));
      wrapper.appendChild(select);
      this.controlInputs.set(parameter.name, select);
      return wrapper;
    }
    const row = document.createElement('div');
    row.className = 'sb-control-row';
    const range = document.createElement('input');
    range.type = 'range';
    range.id = id;
    const number = document.createElement('input');
    number.type = 'number';
    number.setAttribute('aria-label', `${parameter.label} in ${parameter.unit || 'units'}`);
    for (const input of [range, number]) {
      input.name = parameter.name;
      input.min = String(parameter.min);
      input.max = String(parameter.max);
      input.step = String(parameter.step);
      input.value = String(this.values[parameter.name]);
      row.appendChild(input);
    }
    range.addEventListener('input', () => this.setValue(parameter.name, range.value));
    number.addEventListener('change', () => this.setValue(parameter.name, number.value));
    wrapper.appendChild(row);
    this.controlInputs.set(parameter.name, [range, number]);
    return wrapper;
  }

  private buildPresetHint(): HTMLElement {
    const hint = document.createElement('p');
    hint.className = 'sb-preset-hint';
    hint.textContent = `Keys 1–${this.presets.length}: ${this.presets.map((p, i) => `${i + 1} ${p.label}`).join(' · ')}`;
    return hint;
  }

  /** Sets one parameter from user input: validated, clamped and reported like an attribute. */
  protected setValue(name: string, raw: string): void {
    const parameter = this.entry.parameters.find((p) => p.name === name);
    if (!parameter) return;
    const parsed = parseParameters([parameter], () => raw);
    this.values = { ...this.values, ...parsed.values };
    const noticeKey = `input:${name}`;
    const warning = parsed.warnings[0];
    if (warning) this.showNotice(noticeKey, 'warning', warning);
    else this.clearNotice(noticeKey);
    this.syncControls();
    this.saveState();
    this.onInput();
    this.scheduleRender();
  }

  /**
   * The parameters changed (a control, a preset, the view's own input): the next frame
   * is the first of a new picture (definedElement.ts restarts its refinement here).
   */
  protected onInput(): void {}

  protected applyPreset(index: number): void {
    const preset = this.presets[index];
    if (!preset) return;
    const values = withCurrentNames(this.entry.parameters, new Map(Object.entries(preset.values)));
    this.values = { ...this.initialValues, ...Object.fromEntries(values) };
    this.syncControls();
    this.saveState();
    this.onInput();
    this.scheduleRender();
    this.showPresetName(`${index + 1} · ${preset.label}`);
  }

  private presetToastTimer: ReturnType<typeof setTimeout> | null = null;

  /** Shows the recalled preset's name for a moment (announced to screen readers too). */
  private showPresetName(text: string): void {
    if (!this.root) return;
    let toast = this.root.querySelector<HTMLElement>('.sb-preset-toast');
    if (!toast) {
      toast = document.createElement('p');
      toast.className = 'sb-preset-toast';
      toast.setAttribute('role', 'status');
      this.root.appendChild(toast);
    }
    toast.textContent = text;
    toast.hidden = false;
    if (this.presetToastTimer) clearTimeout(this.presetToastTimer);
    this.presetToastTimer = setTimeout(() => {
      if (toast) toast.hidden = true;
    }, 1600);
  }

  private syncControls(): void {
    for (const [name, inputs] of this.controlInputs) {
      const value = String(this.values[name]);
      if (inputs instanceof HTMLSelectElement) inputs.value = value;
      else for (const input of inputs) if (input.value !== value) input.value = value;
    }
  }

  private stateEntries(): [string, string][] {
    const entries = [...new URLSearchParams(encodeParameters(this.entry.parameters, this.values))];
    // Encode relative to the element's attributes, not the schema defaults.
    const changed = entries.filter(([key, value]) => String(this.initialValues[key]) !== value);
    for (const parameter of this.entry.parameters) {
      const value = this.values[parameter.name];
      if (value === parameter.default && value !== this.initialValues[parameter.name]) {
        changed.push([parameter.name, String(value)]);
      }
    }
    if (this.isPresenting()) changed.push(['present', '1']);
    return changed;
  }

  /** URL writes, at most one per STATE_WRITE_INTERVAL_MS while a slider is dragged. */
  private readonly stateWriter = new ThrottledWriter();

  private saveState(): void {
    // The entries are read when the write runs, so a deferred write has the newest state.
    this.stateWriter.write(() => writeWidgetState(this.widgetId, this.stateEntries()));
  }

  /**
   * The Copy menu: a disclosure button that opens two real buttons (the link and
   * the embed code). Esc or a click elsewhere closes it and focus returns to the
   * button; the result is announced in a status region that is always present.
   */
  private buildCopyMenu(root: HTMLElement): void {
    const toggle = root.querySelector<HTMLButtonElement>('[data-action="copy-menu"]');
    const menu = root.querySelector<HTMLElement>('.sb-copy-menu');
    if (!toggle || !menu) return;
    const onOutside = (event: Event): void => {
      if (!(event.target instanceof Node) || !menu.parentElement?.contains(event.target))
        close(false);
    };
    const close = (refocus: boolean): void => {
      menu.hidden = true;
      toggle.setAttribute('aria-expanded', 'false');
      document.removeEventListener('pointerdown', onOutside, true);
      if (refocus) toggle.focus();
    };
    toggle.addEventListener('click', () => {
      if (!menu.hidden) return close(false);
      menu.hidden = false;
      toggle.setAttribute('aria-expanded', 'true');
      document.addEventListener('pointerdown', onOutside, true);
      menu.querySelector<HTMLButtonElement>('button')?.focus();
    });
    menu.addEventListener('keydown', (event) => {
      if (event.key !== 'Escape') return;
      // The menu takes Esc before presentation mode does.
      event.preventDefault();
      event.stopPropagation();
      close(true);
    });
    menu.querySelector('[data-action="link"]')?.addEventListener('click', () => {
      close(true);
      void this.copyText(this.shareLink(), 'link');
    });
    menu.querySelector('[data-action="embed"]')?.addEventListener('click', () => {
      close(true);
      void this.copyText(this.embedCode(), 'embed code');
    });
  }

  /** The link that restores this figure on this page (relative to its attributes). */
  shareLink(): string {
    return widgetLink(this.widgetId, this.stateEntries());
  }

  /** The `<iframe>` that shows this figure, in its current state, on its embed page. */
  embedCode(): string {
    const entries = fullState(this.entry.parameters, this.values);
    const src = embedUrl(siteUrl(''), this.entry.name, this.widgetId, entries);
    const height = this.isPresenting() ? 0 : (this.root?.getBoundingClientRect().height ?? 0);
    return iframeSnippet(src, `${this.entry.title} — Scatterbook`, embedHeight(height || 600));
  }

  private copyStatusTimer: ReturnType<typeof setTimeout> | null = null;

  private async copyText(text: string, what: 'link' | 'embed code'): Promise<void> {
    const status = this.root?.querySelector<HTMLElement>('.sb-copy-status');
    try {
      await navigator.clipboard.writeText(text);
      this.clearNotice('copy');
      if (status) {
        status.textContent = `Copied ${what}`;
        if (this.copyStatusTimer) clearTimeout(this.copyStatusTimer);
        this.copyStatusTimer = setTimeout(() => (status.textContent = ''), 4000);
      }
    } catch {
      // No clipboard (permission refused, insecure context): show the text to copy by hand.
      this.showNotice('copy', 'info', `Copy this ${what}: ${text}`);
    }
  }

  /**
   * Prepares the printed figure: its canvases copied as images (print.ts), its
   * settings written out (the controls are not printed), and a note if it has not
   * drawn yet.
   */
  snapshotForPrint(): void {
    if (!this.root) return;
    const drawn = Number(this.dataset['rendered'] ?? '0') > 0;
    if (drawn) snapshotCanvases(this.root);
    this.root.classList.toggle('sb-print-undrawn', !drawn);
    let settings = this.root.querySelector<HTMLElement>('.sb-print-settings');
    if (!settings) {
      settings = document.createElement('p');
      settings.className = 'sb-print-settings';
      this.root.querySelector('.sb-widget-header')?.after(settings);
    }
    settings.textContent = drawn
      ? `Settings: ${this.settingsText()}`
      : `This figure had not been drawn when the page was printed (it draws when it scrolls into view). ` +
        `Settings: ${this.settingsText()}`;
  }

  /** Draws now, visible or not, then copies the picture for printing. */
  async renderForPrint(): Promise<void> {
    try {
      await this.redraw();
      await this.drawForPrint();
    } finally {
      this.snapshotForPrint();
    }
  }

  /**
   * Draws the parts of the figure that draw on their own schedule (only while on
   * screen, like hg-lobe's 3D view), so that a figure printed before it was ever
   * seen prints them too. Most widgets draw everything in render().
   */
  protected async drawForPrint(): Promise<void> {}

  /** The parameters as a reader would set them: "Thickness d = 2 m · Profile: Layered". */
  private settingsText(): string {
    return this.entry.parameters
      .map((parameter) => {
        const value = this.values[parameter.name];
        if (parameter.kind === 'choice') {
          const choice = parameter.choices.find((c) => c.value === value);
          return `${parameter.label}: ${choice?.label ?? String(value)}`;
        }
        return `${parameter.label} = ${String(value)}${parameter.unit ? ` ${parameter.unit}` : ''}`;
      })
      .join(' · ');
  }

  isPresenting(): boolean {
    return this.root?.classList.contains('is-presenting') ?? false;
  }

  setPresenting(on: boolean): void {
    if (!this.root) return;
    this.root.classList.toggle('is-presenting', on);
    this.presentButton?.setAttribute('aria-pressed', String(on));
    if (this.presentButton) this.presentButton.textContent = on ? 'Exit presentation' : 'Present';
    document.documentElement.classList.toggle('sb-presenting', on);
    // Presentation sets larger type: the body's held height is the old type's.
    this.bodyHold?.restart();
    if (on) {
      document.addEventListener('keydown', this.documentEscapeListener);
      this.root.tabIndex = -1;
      this.root.focus({ preventScroll: true });
      // Full screen where the browser allows it; the fixed overlay works without. A grant
      // that comes after the reader left again (Esc while the request was pending) is undone.
      const root = this.root;
      root
        .requestFullscreen?.()
        .then(() => {
          if (this.isPresenting()) this.inFullscreen = true;
          else if (document.fullscreenElement === root)
            void document.exitFullscreen().catch(() => undefined);
        })
        .catch(() => undefined);
    } else {
      document.removeEventListener('keydown', this.documentEscapeListener);
      this.inFullscreen = false;
      if (document.fullscreenElement) void document.exitFullscreen().catch(() => undefined);
    }
    this.saveState();
    this.scheduleRender();
  }

  private readonly keyListener = (event: KeyboardEvent): void => this.onKey(event);

  /**
   * Esc leaves presentation mode wherever the focus is: the widget fills the window, and
   * a key that reached the page outside it (focus on the body after a click or a
   * reload) is meant for it too. Keys inside the widget meet onKey first, and the menu
   * keeps its own Esc (it stops the event).
   */
  private readonly documentEscapeListener = (event: KeyboardEvent): void => {
    if (event.key !== 'Escape' || event.defaultPrevented || !this.isPresenting()) return;
    if (event.target instanceof Node && this.contains(event.target)) return;
    this.setPresenting(false);
    event.preventDefault();
  };

  /**
   * Esc in full screen belongs to the browser: it leaves full screen and need not pass
   * the key on to the page (Chrome never does, Firefox not while the change is under
   * way), so presentation mode ends with the full screen it entered.
   */
  private readonly fullscreenListener = (): void => {
    // Only the end of the full screen this presentation was granted: the change event of
    // an earlier one (left by the button, F again at once) can arrive after the new start.
    if (this.inFullscreen && document.fullscreenElement !== this.root && this.isPresenting())
      this.setPresenting(false);
  };
  /** The full screen this presentation asked for was granted (and not left since). */
  private inFullscreen = false;

  private onKey(event: KeyboardEvent): void {
    if (event.ctrlKey || event.metaKey || event.altKey) return;
    const target = event.target as HTMLElement | null;
    const typing = target instanceof HTMLInputElement && target.type === 'number';
    if (event.key === 'Escape' && this.isPresenting()) {
      this.setPresenting(false);
      event.preventDefault();
    } else if (!typing && (event.key === 'f' || event.key === 'F')) {
      this.setPresenting(!this.isPresenting());
      event.preventDefault();
    } else if (!typing && /^[1-9]$/.test(event.key) && Number(event.key) <= this.presets.length) {
      this.applyPreset(Number(event.key) - 1);
      event.preventDefault();
    }
  }

  showNotice(key: string, kind: NoticeKind, message: string, timeoutMs?: number): void {
    if (!this.noticeArea) return;
    let notice = this.notices.get(key);
    if (!notice) {
      notice = document.createElement('p');
      notice.setAttribute('role', kind === 'error' ? 'alert' : 'status');
      this.noticeArea.appendChild(notice);
      this.notices.set(key, notice);
    }
    notice.className = `sb-notice sb-notice--${kind}`;
    notice.textContent = message;
    if (timeoutMs) setTimeout(() => this.clearNotice(key), timeoutMs);
  }

  /** The notice every widget shows while it draws with its float64 CPU twin instead. */
  protected showCpuFallbackNotice(reason: string, what: string): void {
    this.showNotice('backend', 'warning', `WebGPU is not available (${reason}). ${what}`);
  }

  clearNotice(key: string): void {
    this.notices.get(key)?.remove();
    this.notices.delete(key);
  }

  /**
   * Records what the last frame's main work cost, as data-frame-ms and data-frame-timer
   * on the element: `npm run bench` (bench/widgets.ts) reads them to report every
   * widget's frame time, and tests can check that a widget measures its cost.
   */
  protected recordFrameCost(milliseconds: number, timer: string): void {
    this.dataset['frameMs'] = String(milliseconds);
    this.dataset['frameTimer'] = timer;
  }

  /** Draws again now, visible or not, and resolves when the frame is done (benchmarks). */
  async redraw(): Promise<void> {
    while (this.rendering) await new Promise((resolve) => requestAnimationFrame(resolve));
    this.dirty = true;
    await this.renderNow();
  }

  /** Renders on the next frame if visible; otherwise when it scrolls into view. */
  protected scheduleRender(): void {
    this.dirty = true;
    if (!this.isConnected || !(this.visible || this.isPresenting()) || this.frameRequest !== null)
      return;
    this.frameRequest = requestAnimationFrame(() => {
      this.frameRequest = null;
      void this.renderNow();
    });
  }

  private async renderNow(): Promise<void> {
    if (this.rendering) return;
    this.rendering = true;
    this.dirty = false;
    try {
      await this.render();
      this.clearNotice('render-error');
      this.dataset['rendered'] = String(Number(this.dataset['rendered'] ?? '0') + 1);
    } catch (error) {
      this.showNotice(
        'render-error',
        'error',
        `This figure failed to draw: ${error instanceof Error ? error.message : String(error)}`,
      );
    } finally {
      this.rendering = false;
      if (this.dirty) this.renderAfterRender();
    }
  }

  /**
   * Whether what was asked during a render starts as soon as it ends (renderAfterRender)
   * rather than at the next animation frame; a subclass says so where it pays.
   */
  protected startsRightAfterRender(): boolean {
    return false;
  }

  /**
   * What was asked while a render ran (an input, the next stage) starts at the next
   * animation frame, or, where startsRightAfterRender says so, as soon as the render ends,
   * in a task of its own: the requests are coalesced already, and while the GPU process is
   * busy animation frames come 30–90 ms late on SwiftShader (bench/firstPictureProbe.ts),
   * which an input's first picture waited for after the stale frame ended (issue 23).
   */
  private renderAfterRender(): void {
    if (!this.startsRightAfterRender()) {
      this.scheduleRender();
      return;
    }
    if (!this.isConnected || !(this.visible || this.isPresenting())) return;
    if (this.frameRequest !== null) {
      cancelAnimationFrame(this.frameRequest);
      this.frameRequest = null;
    }
    setTimeout(() => {
      if (this.dirty && this.frameRequest === null) void this.renderNow();
    }, 0);
  }
}
