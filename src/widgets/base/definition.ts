// A widget as one declarative definition (src/widgets/<name>/widget.ts): its schema,
// presets, readout rows, deck slides and host style as plain data, and a lazy
// load() of the code that draws it. This module and every widget.ts stay free of
// the DOM and of GPU code, so that the book's build (Node), the tests and the
// page's loader can all read the registry; only load() pulls in the view.
import type { ParameterValues, WidgetEntry } from '../parameters.ts';
import type { WidgetModule } from './view.ts';

/** A preset, recalled by the number keys 1–9 (values over the element's attributes). */
export interface Preset {
  label: string;
  values: ParameterValues;
}

/** What a frame ran on, as the readouts and the cost line describe it. */
export type FrameBackend =
  { kind: 'gpu'; adapterDescription: string } | { kind: 'cpu'; reason: string };

/** A readout value: its text, and optionally whether it is a passed (ok) or failed (bad) check. */
export type ReadoutValue = string | { text: string; state?: 'ok' | 'bad' };

/**
 * One row of the readout list: a label, and how to write its value from the frame
 * the view rendered. `format` is a method so that a definition typed with its own
 * frame is still a `WidgetDefinition` in the registry.
 */
export interface ReadoutRow<Frame> {
  /** `data-readout` key of the value (tests select rows by it). */
  key: string;
  label: string;
  /**
   * The value from each reported frame. Without it the row is the view's to write
   * (context.setReadout), e.g. the result of a sweep.
   */
  format?(frame: Frame, backend: FrameBackend): ReadoutValue;
  /** Text shown before the first value. */
  initial?: string;
}

/** What a frame's main work cost, for the cost line and for `npm run bench`. */
export interface FrameCost {
  milliseconds: number;
  timing: 'gpu-timestamp' | 'gpu-wall' | 'cpu';
}

export interface Readouts<Frame> {
  rows: readonly ReadoutRow<Frame>[];
  /**
   * The measured cost of the frame (recorded as data-frame-ms and data-frame-timer).
   * Without it (and costLine) the view records costs and writes the cost line itself.
   */
  cost?(frame: Frame): FrameCost;
  /**
   * The cost line after "WebGPU (adapter): " or "CPU fallback: "; `how` says how the
   * time was measured (timingLabel).
   */
  costLine?(frame: Frame, how: string, backend: FrameBackend): string;
}

/** A slide of the demo deck (deck.html): the widget with these attributes and a caption. */
export interface SlideSpec {
  title: string;
  attributes: Readonly<Record<string, string>>;
  caption: string;
  /** Chapter slug, for the "read more" link and the slide's place in the deck. */
  chapter: string;
}

export interface WidgetDefinition<Frame = unknown> {
  /** The schema: name (the element is `sb-<name>`), title, parameters. */
  entry: WidgetEntry;
  presets?: readonly Preset[];
  /**
   * Parameters a preset leaves as they are (presets that are, say, transfer functions
   * keep the camera and the step).
   */
  presetKeeps?: readonly string[];
  /** Readout rows filled by the base element from each rendered frame. */
  readouts?: Readouts<Frame>;
  /** Deck slides, in the order the lecture shows them. */
  slides?: readonly SlideSpec[];
  /**
   * Place among the widgets that have slides in the same chapter (lower first; default 0).
   * The deck is ordered by chapter, then by this, then by the widget's own slide order.
   */
  deckOrder?: number;
  /**
   * CSS declarations for the host element, written into the book's style sheet (so they
   * hold before the element is defined). Default `display: block`.
   */
  hostStyle?: string;
  /** Loads the view (DOM, GPU and CPU code); called once per page, only where the widget appears. */
  load(): Promise<WidgetModule<Frame>>;
}

/** Identity with the frame type inferred from the readouts (and checked against the view). */
export function defineWidget<Frame>(definition: WidgetDefinition<Frame>): WidgetDefinition<Frame> {
  return definition;
}

/** The custom element name of a widget. */
export function tagName(definition: Pick<WidgetDefinition, 'entry'>): string {
  return `sb-${definition.entry.name}`;
}

const DEFAULT_HOST_STYLE = 'display: block;';

/** The style rules of every widget's host element (the book's generated widget style sheet). */
export function hostStyleSheet(definitions: readonly WidgetDefinition[]): string {
  return definitions
    .map(
      (definition) =>
        `${tagName(definition)} {\n  ${definition.hostStyle ?? DEFAULT_HOST_STYLE}\n}\n`,
    )
    .join('');
}

/** Folder name of a `./<name>/widget.ts` glob key or path. */
export function folderOf(path: string): string {
  const match = /([^/\\]+)[/\\]widget\.ts$/.exec(path);
  if (!match?.[1]) throw new Error(`not a widget definition path: ${path}`);
  return match[1];
}

/**
 * Checks a registry built from the folders: each module exports `widget`, and its name
 * is its folder's (the element name, the embed page and the deck all key on it).
 */
export function registryFrom(
  modules: Readonly<Record<string, { widget?: WidgetDefinition }>>,
): readonly WidgetDefinition[] {
  const definitions = Object.entries(modules).map(([path, module]) => {
    const folder = folderOf(path);
    const definition = module.widget;
    if (!definition) throw new Error(`${path} does not export \`widget\``);
    if (definition.entry.name !== folder) {
      throw new Error(
        `${path} defines "${definition.entry.name}", not its folder's name "${folder}"`,
      );
    }
    return definition;
  });
  return definitions.sort((a, b) => (a.entry.name < b.entry.name ? -1 : 1));
}
