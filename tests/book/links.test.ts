// Links between pages are relative to the page that holds them, so the built book
// works under any base path (issue 18): the rewriting rules, and the whole book
// as generated (no <a> of any page points at a root-absolute path, and every one
// names a page the book has).
import { readdirSync, readFileSync } from 'node:fs';
import { join, posix } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { buildBook } from '../../src/book/build/generate.ts';
import { markRoot, relativeLink, relativizeLinks, rootPrefix } from '../../src/book/build/links.ts';
import { siteUrl } from '../../src/widgets/base/siteUrl.ts';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));

describe('relative links', () => {
  it('computes the path to the root from the page depth', () => {
    expect(rootPrefix('index.html')).toBe('');
    expect(rootPrefix('chapters/02-x.html')).toBe('../');
    expect(rootPrefix('a/b/c.html')).toBe('../../');
  });

  it('links a site path relative to the page, keeping query and fragment', () => {
    expect(relativeLink('index.html', '/chapters/02-x.html')).toBe('chapters/02-x.html');
    expect(relativeLink('chapters/02-x.html', '/chapters/03-y.html#eq:a')).toBe('03-y.html#eq:a');
    expect(relativeLink('chapters/02-x.html', '/index.html')).toBe('../index.html');
    expect(relativeLink('chapters/02-x.html', '/')).toBe('../index.html');
    expect(relativeLink('appendix/shader-library.html', '/deck.html?backend=cpu#slide=2')).toBe(
      '../deck.html?backend=cpu#slide=2',
    );
    expect(relativeLink('chapters/02-x.html', '/chapters/02-x.html#eq:b')).toBe('#eq:b');
    expect(relativeLink('chapters/02-x.html', '/chapters/02-x.html')).toBe('02-x.html');
    expect(relativeLink('a/b/c.html', '/a/d.html')).toBe('../d.html');
  });

  it('rewrites only root-absolute hrefs of <a> and <area>; other URLs are left to Vite', () => {
    const html =
      '<link rel="icon" href="/favicon.svg"><script type="module" src="/src/book/main.ts"></script>' +
      '<a class="x" href="/chapters/03-y.html">3</a><A HREF=\'/deck.html\'>deck</A>' +
      '<a href="https://example.org/">ext</a><a href="//cdn.example/x">cdn</a><a href="#top">top</a>' +
      '<abbr title="/no">n</abbr><area href="/index.html"><img src="/photo.png">';
    const out = relativizeLinks(html, 'chapters/02-x.html');
    expect(out).toContain('<link rel="icon" href="/favicon.svg">');
    expect(out).toContain('src="/src/book/main.ts"');
    expect(out).toContain('<a class="x" href="03-y.html">');
    expect(out).toContain("<A HREF='../deck.html'>");
    expect(out).toContain('href="https://example.org/"');
    expect(out).toContain('href="//cdn.example/x"');
    expect(out).toContain('href="#top"');
    expect(out).toContain('<abbr title="/no">');
    expect(out).toContain('<area href="../index.html">');
    expect(out).toContain('<img src="/photo.png">');
  });
});

const book = buildBook(ROOT);

describe('the generated book', () => {
  const files = new Set(book.pages.map((page) => page.file));

  it('has no root-absolute link in any page (they escape a sub-path)', () => {
    for (const page of book.pages) {
      const absolute = [...page.html.matchAll(/<(?:a|area)\b[^>]*\shref=["'](\/[^"']*)["']/gi)];
      expect(
        absolute.map((m) => m[1]),
        page.file,
      ).toEqual([]);
    }
  });

  it('every internal link names a page of the book (and an id on it, for a fragment)', () => {
    let checked = 0;
    for (const page of book.pages) {
      for (const match of page.html.matchAll(/<(?:a|area)\b[^>]*\shref="([^"]*)"/gi)) {
        const href = match[1] ?? '';
        if (/^[a-z][a-z0-9+.-]*:|^\/\//i.test(href)) continue;
        const [pathPart = '', fragment] = href.split('#');
        const path = pathPart.split('?')[0] ?? '';
        const target =
          path === '' ? page.file : posix.normalize(posix.join(posix.dirname(page.file), path));
        // Links to the embed pages' own assets etc. are checked in the built site (e2e).
        if (!target.endsWith('.html')) continue;
        expect(files.has(target), `${page.file}: ${href}`).toBe(true);
        if (fragment) {
          const html = book.pages.find((p) => p.file === target)?.html ?? '';
          expect(html, `${page.file}: ${href}`).toContain(`id="${decodeURIComponent(fragment)}"`);
        }
        checked += 1;
      }
    }
    expect(checked).toBeGreaterThan(100);
  });
});

describe("run-time fetches of the site's files", () => {
  function withPage<T>(url: string, root: string | undefined, body: () => T): T {
    const previous = (globalThis as { document?: unknown }).document;
    (globalThis as { document?: unknown }).document = {
      baseURI: url,
      documentElement: { dataset: root === undefined ? {} : { sbRoot: root } },
    };
    try {
      return body();
    } finally {
      (globalThis as { document?: unknown }).document = previous;
    }
  }

  it('resolve under an absolute base whatever the page depth', () => {
    const page = 'https://uni.example/courses/cmsc740/book/chapters/09-single-scattering.html';
    expect(
      withPage(page, '../', () => siteUrl('volumes/smoke-24.f32', '/courses/cmsc740/book/')),
    ).toBe('https://uni.example/courses/cmsc740/book/volumes/smoke-24.f32');
    expect(withPage('http://localhost:4173/index.html', '', () => siteUrl('/a.bin', '/'))).toBe(
      'http://localhost:4173/a.bin',
    );
  });

  it('resolve under a relative base (./) from the root the page declares', () => {
    const page = 'https://uni.example/any/where/chapters/10-multiple-scattering.html';
    expect(withPage(page, '../', () => siteUrl('photon-map/reference.bin', './'))).toBe(
      'https://uni.example/any/where/photon-map/reference.bin',
    );
    expect(
      withPage('https://uni.example/any/where/index.html', '', () => siteUrl('x.bin', './')),
    ).toBe('https://uni.example/any/where/x.bin');
  });

  it('every page declares its way to the root', () => {
    expect(markRoot('<!doctype html>\n<html lang="en">', 'chapters/02-x.html')).toBe(
      '<!doctype html>\n<html data-sb-root="../" lang="en">',
    );
    for (const page of book.pages)
      expect(page.html, page.file).toContain(`<html data-sb-root="${rootPrefix(page.file)}"`);
  });

  it('the browser code fetches site files only through siteUrl and names no root-absolute path', () => {
    const sources: string[] = [];
    const walk = (dir: string): void => {
      for (const entry of readdirSync(dir, { withFileTypes: true })) {
        const path = join(dir, entry.name);
        if (entry.isDirectory()) {
          if (entry.name !== 'build') walk(path);
        } else if (/\.ts$/.test(entry.name)) sources.push(path);
      }
    };
    walk(join(ROOT, 'src/widgets'));
    walk(join(ROOT, 'src/book'));
    let fetches = 0;
    for (const file of sources) {
      const text = readFileSync(file, 'utf8');
      if (file.endsWith('siteUrl.ts')) continue;
      for (const match of text.matchAll(/\bfetch\(\s*([^)]*)/g)) {
        fetches += 1;
        expect(match[1], file).toMatch(/^siteUrl\(/);
      }
      // A root-absolute URL in a string: '/volumes/…', "/chapters/…", `/deck.html`.
      expect(text, file).not.toMatch(
        /['"`]\/(?:chapters|appendix|embed|volumes|scenes|photon-map|assets|index\.html|deck\.html)\b/,
      );
    }
    expect(fetches).toBeGreaterThanOrEqual(2);
  });
});
