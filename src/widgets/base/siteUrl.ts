// URLs of the site's own files fetched at run time (public/: volumes, the photon-map
// reference, scenes). A fetch of `/volumes/…` escapes a book published under a
// sub-path, and a page-relative `volumes/…` depends on the page's depth; every
// run-time fetch goes through siteUrl instead.
//
// With an absolute base (`vite build --base /courses/cmsc740/book/`, the default `/`)
// Vite's BASE_URL is the site root. With a relative base (`--base ./`, a build that
// can be copied under any path) BASE_URL is `./` on every page, so the root comes
// from the page itself: the book's generator stamps `data-sb-root` ("../" on a
// chapter) on <html> (src/book/build/links.ts).

/** The absolute URL of a file under the site root, e.g. siteUrl('volumes/smoke-24.f32'). */
export function siteUrl(path: string, base: string = import.meta.env.BASE_URL): string {
  const file = path.replace(/^\/+/, '');
  // '/', '/book/' or 'https://cdn.example/book/': already the root.
  if (/^(?:[a-z][a-z0-9+.-]*:)?\//i.test(base))
    return new URL(`${base}${file}`, document.baseURI).href;
  const root = document.documentElement.dataset['sbRoot'] ?? '';
  return new URL(`${root}${file}`, document.baseURI).href;
}
