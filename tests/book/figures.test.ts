// Static figures and listings (src/book/figures, src/book/listings, build/figures.ts):
// every one is placed, numbered per chapter, captioned, accessible, referenced from the
// prose, coloured only through the theme's classes, and deterministic; every listing links
// to a function that the built shader-library appendix documents; and the geometry the
// figures claim is the physics the chapters teach.
import { posix } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { buildBook, type BookPage } from '../../src/book/build/generate.ts';
import { createMarkdown, renderChapterBody } from '../../src/book/build/markdown.ts';
import { resolveFigureReferences, bookListings } from '../../src/book/build/figures.ts';
import { checkListingReferences, highlightPseudocode } from '../../src/book/build/listings.ts';
import { loadShaderDocs } from '../../src/book/build/shaderDocs.ts';
import { FIGURES } from '../../src/book/figures/index.ts';
import { renderSvg } from '../../src/book/figures/svg.ts';
import { DIPOLE_FIGURE, dipoleFigure } from '../../src/book/figures/dipole.ts';
import { chooseWalk, NULL_COLLISIONS } from '../../src/book/figures/null-collisions.ts';
import {
  chooseNullScatteringWalks,
  NULL_SCATTERING_PATHS,
  nullScatteringPaths,
} from '../../src/book/figures/null-scattering-paths.ts';
import { sineMedium } from '../../src/reference/medium.ts';
import {
  transmittanceDeltaTracking,
  transmittanceNullScattering,
} from '../../src/reference/tracking.ts';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));
const book = buildBook(ROOT);
const chapters = book.pages.filter((page) => page.chapter);
const appendix = book.pages.find((page) => page.file === 'appendix/shader-library.html');

interface Placed {
  page: BookPage;
  id: string;
  number: string;
  kind: 'fig' | 'lst';
  html: string;
}

const placed: Placed[] = chapters.flatMap((page) =>
  [
    ...page.html.matchAll(
      /<figure class="(?:diagram-figure|listing)" id="((fig|lst):[a-z0-9-]+)" data-number="([^"]+)">[\s\S]*?<\/figure>/g,
    ),
  ].map((match) => ({
    page,
    id: match[1] ?? '',
    kind: match[2] as 'fig' | 'lst',
    number: match[3] ?? '',
    html: match[0],
  })),
);
const figures = placed.filter((item) => item.kind === 'fig');
const listings = placed.filter((item) => item.kind === 'lst');

/** The site path of a link written relative to a page (links.ts makes them relative). */
function resolveHref(page: BookPage, href: string): { path: string; fragment: string } {
  const [path = '', fragment = ''] = href.split('#');
  const target =
    path === '' ? page.file : posix.normalize(posix.join(posix.dirname(page.file), path));
  return { path: target, fragment: decodeURIComponent(fragment) };
}

function render(body: string) {
  return renderChapterBody(createMarkdown(), body, 7, '/chapters/07-test.html', 'test.md');
}

describe('static figures', () => {
  it('every figure of the registry is placed exactly once, and every listing too', () => {
    expect(figures.map((f) => f.id.slice(4)).sort()).toEqual(Object.keys(FIGURES).sort());
    expect(listings.map((l) => l.id.slice(4)).sort()).toEqual([...bookListings().keys()].sort());
    expect(figures.length).toBeGreaterThanOrEqual(6);
    expect(listings.length).toBeGreaterThanOrEqual(4);
  });

  it('are numbered per chapter in order of appearance, figures and listings separately', () => {
    for (const page of chapters) {
      for (const kind of ['fig', 'lst'] as const) {
        const numbers = placed
          .filter((p) => p.page === page && p.kind === kind)
          .map((p) => p.number);
        expect(numbers, `${page.file} ${kind}`).toEqual(
          numbers.map((_, i) => `${page.chapter?.number}.${i + 1}`),
        );
      }
    }
  });

  it('each figure is one accessible image: a titled, described SVG and a numbered caption', () => {
    for (const figure of figures) {
      const svg = /<svg class="diagram"[^>]*>/.exec(figure.html)?.[0] ?? '';
      expect(svg, figure.id).toContain('role="img"');
      const titleId = /aria-labelledby="([^"]+)"/.exec(svg)?.[1];
      const descId = /aria-describedby="([^"]+)"/.exec(svg)?.[1];
      const title = new RegExp(`<title id="${titleId}">([^<]{8,})</title>`).exec(figure.html);
      const desc = new RegExp(`<desc id="${descId}">([^<]{80,})</desc>`).exec(figure.html);
      expect(title, `${figure.id} title`).not.toBeNull();
      expect(desc, `${figure.id} desc`).not.toBeNull();
      const caption =
        /<figcaption><span class="figure-label">Figure ([0-9.]+)\.<\/span> ([\s\S]+?)<\/figcaption>/.exec(
          figure.html,
        );
      expect(caption?.[1], figure.id).toBe(figure.number);
      expect((caption?.[2] ?? '').replace(/<[^>]+>/g, '').length, figure.id).toBeGreaterThan(40);
      // The id of <title>/<desc> is unique in the page.
      expect(figure.page.html.split(`id="${titleId}"`).length, figure.id).toBe(2);
    }
  });

  it('fit the text column: at most 646 user units wide, scaled by CSS (width 100 %, height auto)', () => {
    for (const figure of figures) {
      const viewBox = /viewBox="0 0 ([0-9.]+) ([0-9.]+)"/.exec(figure.html);
      expect(Number(viewBox?.[1]), figure.id).toBeLessThanOrEqual(646);
      expect(Number(viewBox?.[2]), figure.id).toBeGreaterThan(100);
    }
  });

  it('name no colour: every stroke and fill comes from a class mapped to a theme token', () => {
    for (const figure of figures) {
      const svg = /<svg[\s\S]*<\/svg>/.exec(figure.html)?.[0] ?? '';
      expect(svg, figure.id).not.toMatch(/\s(fill|stroke|color|style)="/);
      expect(svg, figure.id).not.toMatch(/#[0-9a-f]{3,6}\b|rgb\(|hsl\(/i);
    }
  });

  it('are deterministic: each generator returns the same SVG twice', () => {
    for (const [name, draw] of Object.entries(FIGURES)) {
      expect(renderSvg(draw(), name), name).toBe(renderSvg(draw(), name));
    }
    const again = buildBook(ROOT);
    for (const figure of figures) {
      const page = again.pages.find((p) => p.file === figure.page.file);
      expect(page?.html, figure.id).toContain(figure.html);
    }
  }, 60_000);
});

describe('references to figures and listings', () => {
  it('every figure and listing is referenced from the prose at least once, outside itself', () => {
    for (const item of placed) {
      const pattern = new RegExp(`<a class="figref" href="[^"]*#${item.id}">`, 'g');
      const outside = chapters.reduce(
        (count, page) => count + (page.html.replace(item.html, '').match(pattern)?.length ?? 0),
        0,
      );
      expect(outside, item.id).toBeGreaterThan(0);
    }
  });

  it('every reference resolves to the number and page of its target', () => {
    let count = 0;
    for (const page of chapters) {
      for (const match of page.html.matchAll(
        /<a class="figref" href="([^"]+)">(Figure|Listing)&nbsp;([0-9.]+)<\/a>/g,
      )) {
        const { path, fragment } = resolveHref(page, match[1] ?? '');
        const target = placed.find((p) => p.id === fragment);
        expect(target, `${page.file} → ${match[1]}`).toBeDefined();
        expect(target?.page.file, fragment).toBe(path);
        expect(match[2], fragment).toBe(target?.kind === 'fig' ? 'Figure' : 'Listing');
        expect(match[3], fragment).toBe(target?.number);
        count += 1;
      }
      expect(page.html, page.file).not.toMatch(/<a href="[^"]*#(fig|lst):[^"]*"><\/a>/);
    }
    expect(count).toBeGreaterThanOrEqual(placed.length);
  });

  it('resolve across pages, and an unknown label fails the build naming the file', () => {
    const labels = new Map([
      [
        'fig:x',
        { label: 'fig:x', kind: 'Figure' as const, number: '2.1', page: '/chapters/02-a.html' },
      ],
    ]);
    expect(
      resolveFigureReferences('<a href="#fig:x"></a>', labels, '/chapters/07-b.html', 'b.md'),
    ).toBe('<a class="figref" href="/chapters/02-a.html#fig:x">Figure&nbsp;2.1</a>');
    expect(() =>
      resolveFigureReferences('<a href="#lst:nope"></a>', labels, '/p.html', 'ch.md'),
    ).toThrow(/ch\.md: reference to unknown figure or listing "lst:nope"/);
  });

  it('an unknown figure, a missing caption or a malformed block fails the build, naming the file', () => {
    expect(() => render('```figure no-such-figure\nA caption.\n```\n')).toThrow(
      /test\.md: unknown figure "no-such-figure"/,
    );
    expect(() => render('```figure beer-slab\n\n```\n')).toThrow(
      /test\.md: figure beer-slab needs a caption/,
    );
    expect(() => render('```listing\nA caption.\n```\n')).toThrow(
      /test\.md: write ```listing NAME/,
    );
    expect(() => render('```listing no-such-listing\nA caption.\n```\n')).toThrow(
      /test\.md: unknown listing "no-such-listing"/,
    );
    const numbered = render('```figure beer-slab\nOne.\n```\n\n```figure dipole\nTwo.\n```\n');
    expect(numbered.html).toContain('id="fig:beer-slab" data-number="7.1"');
    expect(numbered.html).toContain('id="fig:dipole" data-number="7.2"');
  });
});

describe('listings', () => {
  it('link each function they cite to its anchor in the built appendix', () => {
    expect(appendix).toBeDefined();
    for (const listing of listings) {
      const links = [
        ...listing.html.matchAll(
          /<a class="listing-source" href="([^"]+)"><code>(\w+)<\/code><\/a>/g,
        ),
      ];
      const source = bookListings().get(listing.id.slice(4));
      expect(links.length, listing.id).toBe(source?.implements.length);
      for (const link of links) {
        const { path, fragment } = resolveHref(listing.page, link[1] ?? '');
        expect(path, listing.id).toBe(appendix?.file);
        expect(fragment.endsWith(`-${link[2]}`), fragment).toBe(true);
        expect(appendix?.html, `${listing.id} → #${fragment}`).toContain(
          `<section class="api-entry" id="${fragment}">`,
        );
      }
    }
  });

  it('refuse a listing that cites a function the shader library does not have', () => {
    const modules = loadShaderDocs(`${ROOT}shaders`);
    const fake = new Map([
      [
        'fake',
        { name: 'fake', implements: [{ module: 'tracking', name: 'noSuchFunction' }], code: 'x' },
      ],
    ]);
    expect(() => checkListingReferences(fake, modules)).toThrow(
      /listing fake: shaders\/tracking\.wesl has no function noSuchFunction/,
    );
  });

  it('are highlighted line by line: one numbered line per source line, keywords, comments and procedures marked', () => {
    for (const listing of listings) {
      const source = bookListings().get(listing.id.slice(4))?.code ?? '';
      expect(listing.html.match(/<span class="line[ "]/g)?.length, listing.id).toBe(
        source.split('\n').length,
      );
      expect(listing.html, listing.id).toContain('<span class="tok-keyword">');
      expect(listing.html, listing.id).toContain('<span class="tok-comment">');
      expect(listing.html, listing.id).toContain('tok-definition');
      // The visible text is the source, unchanged.
      const text = [
        ...listing.html.matchAll(
          /<span class="line(?: line-comment)?">([\s\S]*?)<\/span>(?=<span class="line|<\/code>)/g,
        ),
      ]
        .map((m) =>
          (m[1] ?? '')
            .replace(/<[^>]+>/g, '')
            .replace(/&lt;/g, '<')
            .replace(/&gt;/g, '>')
            .replace(/&amp;/g, '&'),
        )
        .join('\n');
      expect(text, listing.id).toBe(source);
    }
    expect(highlightPseudocode('if x < 1 then return 0 ▷ done')).toBe(
      '<span class="line"><span class="tok-keyword">if</span> <span class="tok-variableName">x</span> ' +
        '<span class="tok-operator">&lt;</span> <span class="tok-number">1</span> <span class="tok-keyword">then</span> ' +
        '<span class="tok-keyword">return</span> <span class="tok-number">0</span> <span class="tok-comment">▷ done</span></span>',
    );
  });
});

describe('the geometry the figures claim', () => {
  it('the dipole is drawn to scale: z_r = 1/σt′, z_b = 2AD, z_v = z_r + 4AD (Jensen et al. 2001; physics.md §6.1)', () => {
    const p = DIPOLE_FIGURE;
    // Written from physics.md §6.1, not from the twin the figure uses.
    const fdr = -1.44 / p.eta ** 2 + 0.71 / p.eta + 0.668 + 0.0636 * p.eta;
    const A = (1 + fdr) / (1 - fdr);
    const sigmaTPrime = p.sigmaSPrime + p.sigmaA;
    const zr = 1 / sigmaTPrime;
    const D = 1 / (3 * sigmaTPrime);
    const svg = dipoleFigure().body;
    const surface = Number(
      /<line x1="0" y1="([0-9.]+)" x2="640" y2="\1" class="fig-ink fig-thick"\/>/.exec(svg)?.[1],
    );
    const boundary = Number(
      /<line x1="0" y1="([0-9.]+)" x2="640" y2="\1" class="fig-ink fig-dash"\/>/.exec(svg)?.[1],
    );
    const real = Number(
      /<circle cx="[0-9.]+" cy="([0-9.]+)" r="11" class="fig-solid-accent"\/>/.exec(svg)?.[1],
    );
    const virtual = Number(
      /<circle cx="[0-9.]+" cy="([0-9.]+)" r="11" class="fig-hollow-warm"\/>/.exec(svg)?.[1],
    );
    const unit = p.scale / zr; // pixels per unit of length
    expect(real - surface).toBeCloseTo(zr * unit, 1);
    expect(surface - boundary).toBeCloseTo(2 * A * D * unit, 1);
    expect(surface - virtual).toBeCloseTo((zr + 4 * A * D) * unit, 1);
    expect(dipoleFigure().description).toContain(`A = ${A.toFixed(2)}`);
    expect(A).toBeCloseTo(2.602, 3); // chapter 11: η = 1.3 gives A = 2.602
  });

  it('the null-collision walk is the walk delta tracking takes with the same random stream', () => {
    const p = NULL_COLLISIONS;
    const { seed, walk } = chooseWalk(p);
    const firstReal = walk.findIndex((c) => c.real);
    const estimate = transmittanceDeltaTracking(
      sineMedium(p.sigma0, p.amplitude, p.frequency),
      p.length,
      p.majorant,
      { value: seed },
      1000,
    );
    expect(estimate.estimate).toBe(0);
    expect(estimate.lookups).toBe(firstReal + 1);
  });

  it('the null-scattering walks are the estimator’s walks, and delta/ratio tracking’s, on the same stream', () => {
    const p = NULL_SCATTERING_PATHS;
    const { seed, walks } = chooseNullScatteringWalks(p);
    const medium = sineMedium(p.sigma0, p.amplitude, p.frequency);
    const description = nullScatteringPaths().description;
    walks.forEach((walk) => {
      const direct = transmittanceNullScattering(
        medium,
        p.length,
        p.majorant,
        walk.nullBlend,
        { value: seed },
        1000,
      );
      expect(direct.estimate).toBe(walk.estimate);
      expect(direct.lookups).toBe(walk.vertices.length);
      // Every walk sees the same collisions (ξ is drawn at each, whatever P_n).
      walk.vertices.forEach((v, i) => expect(v.t).toBe(walks[2]?.vertices[i]?.t));
      expect(description).toContain(
        `estimate ${walk.estimate === 0 ? 0 : walk.estimate.toFixed(2)}`,
      );
    });
    // β = 0 is delta tracking on this stream, β = 1 ratio tracking's product ∏(1 − σt/σ̄).
    const delta = transmittanceDeltaTracking(medium, p.length, p.majorant, { value: seed }, 1000);
    expect(delta.estimate).toBe(walks[0]?.estimate);
    expect(delta.lookups).toBe(walks[0]?.vertices.length);
    const ratioProduct = (walks[2]?.vertices ?? []).reduce(
      (w, v) => w * (1 - ((1 + p.amplitude * Math.sin(p.frequency * v.t)) * p.sigma0) / p.majorant),
      1,
    );
    expect(walks[2]?.estimate).toBeCloseTo(ratioProduct, 12);
  });
});
