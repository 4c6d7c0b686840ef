// Links between the book's pages are written relative to the page that holds them
// (`../chapters/03-….html` from a chapter, `chapters/03-….html` from the home page).
// A relative link works under any URL path the site is published at — the root of a
// host, `/courses/cmsc740/book/`, a project site — without rebuilding, whereas a
// root-absolute `/chapters/…` escapes the sub-path and 404s there.
//
// Templates, Markdown chapters, exercise statements and equation references all
// name pages by their site path (`/chapters/…`, `/deck.html`); this pass rewrites
// every such link of an <a> or <area> element once, when a page is finished, so no
// source has to know how deep its page sits. Vite rewrites the other URLs of the
// HTML itself (script, stylesheet, icon, img src: it prefixes the base to public
// files and bundles the rest), so those are left alone.
import { posix } from 'node:path';

/** The path from a page (`chapters/02-x.html`) to the site root: `../`, or `` at the root. */
export function rootPrefix(pageFile: string): string {
  const depth = pageFile.split('/').length - 1;
  return '../'.repeat(depth);
}

/**
 * The link from `pageFile` (relative to the site root, e.g. `chapters/02-x.html`) to
 * a site path (`/chapters/03-y.html#phase-functions`, `/` for the home page). Query and
 * fragment are kept; a link to the page itself keeps only them.
 */
export function relativeLink(pageFile: string, sitePath: string): string {
  const match = /^\/([^?#]*)([?#].*)?$/.exec(sitePath);
  if (!match || sitePath.startsWith('//')) return sitePath;
  const target = match[1] === '' || match[1]?.endsWith('/') ? `${match[1]}index.html` : match[1]!;
  const suffix = match[2] ?? '';
  if (target === pageFile && suffix) return suffix;
  const relative = posix.relative(posix.dirname(pageFile), target);
  return relative === '' ? posix.basename(target) + suffix : relative + suffix;
}

const LINK_ELEMENT = /<(a|area)\b[^>]*>/gi;
const SITE_HREF = /(\shref\s*=\s*)(["'])(\/(?!\/)[^"']*)\2/i;

/** Rewrites the root-absolute hrefs of every <a>/<area> in a finished page (see above). */
export function relativizeLinks(html: string, pageFile: string): string {
  return html.replace(LINK_ELEMENT, (tag) =>
    tag.replace(
      SITE_HREF,
      (_all, before: string, quote: string, path: string) =>
        `${before}${quote}${relativeLink(pageFile, path)}${quote}`,
    ),
  );
}

/**
 * Stamps the page's way to the site root on its <html> element (`data-sb-root="../"`):
 * the widgets' run-time fetches (src/widgets/base/siteUrl.ts) resolve against it when
 * the site is built with a relative base (`--base ./`), where Vite's BASE_URL is
 * `./` on every page whatever its depth.
 */
export function markRoot(html: string, pageFile: string): string {
  return html.replace(/<html\b/i, `<html data-sb-root="${rootPrefix(pageFile)}"`);
}
