// The `<iframe>` snippet of a widget's Copy menu: it shows the widget's embed page
// (embed/<widget>.html, src/book/build/embeds.ts) in the widget's current state.
// The state is written in full — every parameter, not only those that differ from
// the chapter's attributes — so that it does not depend on which attributes the
// embed page starts from (a deck slide's widget has attributes of its own).

import { STATE_VERSION } from './urlState.ts';
import { encodeParameters, type Parameter, type ParameterValues } from '../parameters.ts';

/**
 * Every parameter's value as hash entries, formatted as the deep links format them.
 * encodeParameters leaves out values equal to the schema's default; here nothing is
 * left out (no number equals NaN and no choice is empty), because the embed page's
 * instance may have attributes other than the defaults.
 */
export function fullState(
  parameters: readonly Parameter[],
  values: ParameterValues,
): [string, string][] {
  const keepAll = parameters.map((parameter): Parameter =>
    parameter.kind === 'number'
      ? { ...parameter, default: Number.NaN }
      : { ...parameter, default: '' },
  );
  return [...new URLSearchParams(encodeParameters(keepAll, values))];
}

/** Instance ids as chapter pages number them (`hg-lobe-2`); other ids (a deck slide's) become `<widget>-1`. */
export function embedInstanceId(widget: string, widgetId: string): string {
  return new RegExp(`^${widget}-\\d+$`).test(widgetId) ? widgetId : `${widget}-1`;
}

/**
 * The embed page's URL with the state in the hash, in the deep-link format
 * (`#<id>.<param>=<value>&…&v=1`). `root` is the site root as an absolute URL.
 */
export function embedUrl(
  root: string,
  widget: string,
  widgetId: string,
  entries: Iterable<readonly [string, string]>,
): string {
  const id = embedInstanceId(widget, widgetId);
  const params = new URLSearchParams();
  for (const [key, value] of entries) params.set(`${id}.${key}`, value);
  const url = new URL(`embed/${widget}.html`, root);
  if ([...params.keys()].length > 0) {
    params.set('v', String(STATE_VERSION));
    url.hash = params.toString();
  } else {
    url.hash = id;
  }
  return url.href;
}

function escapeAttribute(text: string): string {
  return text
    .replace(/&/g, '&amp;')
    .replace(/"/g, '&quot;')
    .replace(/</g, '&lt;')
    .replace(/>/g, '&gt;');
}

/**
 * The frame's height in CSS pixels: the widget's own height where it is shown now,
 * plus the embed page's margins and its one-line link to the chapter, rounded up
 * to 10 px and kept between 320 and 2000. A frame narrower than the chapter's column
 * wraps text onto more lines, so the widget gets 5 % to spare.
 */
export function embedHeight(widgetHeight: number): number {
  const pageChrome = 16 + 28; // body padding (2 × 0.5rem) and the "Open in the book" line
  const height = Math.ceil((1.05 * widgetHeight + pageChrome) / 10) * 10;
  return Number.isFinite(height) ? Math.min(Math.max(height, 320), 2000) : 640;
}

/** The HTML a lecturer pastes into a page: full width, lazy, full screen allowed. */
export function iframeSnippet(src: string, title: string, height: number): string {
  return (
    `<iframe src="${escapeAttribute(src)}" title="${escapeAttribute(title)}" ` +
    `width="100%" height="${height}" loading="lazy" allow="fullscreen" ` +
    `style="border: 0; max-width: 100%"></iframe>`
  );
}
