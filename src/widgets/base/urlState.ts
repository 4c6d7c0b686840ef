// Widget state in the URL hash, so that a link restores a widget exactly.
// The hash holds `widgetId.parameter=value` pairs for every widget on the page
// whose state differs from its initial attributes, e.g.
//   #beer-law-1.sigma-a=0.5&beer-law-1.profile=layered&beer-law-1.present=1
// A hash without "=" is an ordinary anchor and is left alone until a widget changes.
// The key `v` holds the format version, so that a future change of format can
// still read old links; a link without it is read as version 1.

/** Version of the hash format written by this build. */
export const STATE_VERSION = 1;
const VERSION_KEY = 'v';

function readHash(): URLSearchParams {
  const hash = location.hash.replace(/^#/, '');
  return hash.includes('=') ? new URLSearchParams(hash) : new URLSearchParams();
}

/** The format version of the link the page was opened with (1 when unversioned), or NaN if unreadable. */
export function readStateVersion(): number {
  const value = readHash().get(VERSION_KEY);
  return value === null ? 1 : Number.parseInt(value, 10);
}

/** The parameters stored for one widget (without its id prefix). */
export function readWidgetState(widgetId: string): Map<string, string> {
  const state = new Map<string, string>();
  const prefix = `${widgetId}.`;
  for (const [key, value] of readHash()) {
    if (key.startsWith(prefix)) state.set(key.slice(prefix.length), value);
  }
  return state;
}

/** Replaces one widget's entries in the hash without adding a history entry. */
export function writeWidgetState(widgetId: string, entries: Iterable<[string, string]>): void {
  const params = readHash();
  const prefix = `${widgetId}.`;
  for (const key of [...params.keys()]) if (key.startsWith(prefix)) params.delete(key);
  for (const [key, value] of entries) params.set(`${prefix}${key}`, value);
  params.delete(VERSION_KEY);
  if ([...params.keys()].length > 0) params.set(VERSION_KEY, String(STATE_VERSION));
  const hash = params.toString();
  const url = `${location.pathname}${location.search}${hash ? `#${hash}` : ''}`;
  history.replaceState(history.state, '', url);
}

/** An absolute link to this page that restores one widget's state. */
export function widgetLink(widgetId: string, entries: Iterable<[string, string]>): string {
  const params = new URLSearchParams();
  for (const [key, value] of entries) params.set(`${widgetId}.${key}`, value);
  if ([...params.keys()].length > 0) params.set(VERSION_KEY, String(STATE_VERSION));
  const hash = params.toString();
  return `${location.origin}${location.pathname}${hash ? `#${hash}` : `#${widgetId}`}`;
}
