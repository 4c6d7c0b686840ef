// Static figures and pseudo-code listings in chapters, numbered per chapter like the
// equations and referenced like them.
//
// A chapter writes
//
//     ```figure beer-slab
//     Caption in Markdown, with $math$.
//     ```
//
// for a diagram from src/book/figures (FIGURES), or ```listing delta-tracking``` for a
// listing from src/book/listings (listings.ts). The block becomes a <figure> with the id
// `fig:NAME` or `lst:NAME` and the number "Figure 2.1" / "Listing 6.1", counted per chapter
// in the order the blocks appear. Prose refers to one with an empty link, `[](#fig:NAME)`,
// which resolveFigureReferences turns into "Figure 2.1" after every chapter is rendered
// (a reference may precede its figure, or cross chapters). Unknown names, empty captions,
// a listing citing a function the shader library lacks, and references to labels that do
// not exist all stop the build.
import { fileURLToPath } from 'node:url';
import type MarkdownIt from 'markdown-it';
import { FIGURES } from '../figures/index.ts';
import { renderSvg } from '../figures/svg.ts';
import {
  appendixAnchor,
  checkListingReferences,
  highlightPseudocode,
  loadListings,
  type ListingSource,
} from './listings.ts';
import { loadShaderDocs } from './shaderDocs.ts';
import { APPENDIX_FILE } from './appendix.ts';

export interface FigureLabel {
  /** `fig:NAME` or `lst:NAME`. */
  label: string;
  kind: 'Figure' | 'Listing';
  /** Printed number, e.g. "2.1". */
  number: string;
  page: string;
}

/** What the plugin needs from the chapter's render environment (markdown.ts RenderEnv). */
interface FigureEnv {
  chapterNumber: number | string;
  file: string;
}

const counters = new WeakMap<object, { Figure: number; Listing: number }>();

function nextNumber(env: FigureEnv, kind: FigureLabel['kind']): string {
  const count = counters.get(env) ?? { Figure: 0, Listing: 0 };
  count[kind] += 1;
  counters.set(env, count);
  return `${env.chapterNumber}.${count[kind]}`;
}

const ROOT = fileURLToPath(new URL('../../../', import.meta.url));
let listingCache: Map<string, ListingSource> | undefined;

/** The listings, checked once against the shader library's functions. */
export function bookListings(): Map<string, ListingSource> {
  if (!listingCache) {
    const listings = loadListings(`${ROOT}src/book/listings`);
    checkListingReferences(listings, loadShaderDocs(`${ROOT}shaders`));
    listingCache = listings;
  }
  return listingCache;
}

function caption(md: MarkdownIt, content: string, env: FigureEnv, what: string): string {
  const text = content.trim();
  if (text === '') throw new Error(`${env.file}: ${what} needs a caption (the block's body)`);
  return md.renderInline(text.replace(/\s*\n\s*/g, ' '), env);
}

function renderFigure(md: MarkdownIt, name: string, content: string, env: FigureEnv): string {
  const draw = FIGURES[name];
  if (!draw) {
    throw new Error(
      `${env.file}: unknown figure "${name}"; known: ${Object.keys(FIGURES).join(', ')}`,
    );
  }
  const label = `fig:${name}`;
  const number = nextNumber(env, 'Figure');
  return (
    `<figure class="diagram-figure" id="${label}" data-number="${number}">` +
    renderSvg(draw(), `fig-${name}`) +
    `<figcaption><span class="figure-label">Figure ${number}.</span> ` +
    `${caption(md, content, env, `figure ${name}`)}</figcaption></figure>\n`
  );
}

function renderListing(md: MarkdownIt, name: string, content: string, env: FigureEnv): string {
  const listing = bookListings().get(name);
  if (!listing) {
    throw new Error(
      `${env.file}: unknown listing "${name}"; known: ${[...bookListings().keys()].join(', ')}`,
    );
  }
  const label = `lst:${name}`;
  const number = nextNumber(env, 'Listing');
  const links = listing.implements
    .map(
      (reference) =>
        `<a class="listing-source" href="/${APPENDIX_FILE}#${appendixAnchor(reference)}">` +
        `<code>${reference.name}</code></a>`,
    )
    .join(', ');
  return (
    `<figure class="listing" id="${label}" data-number="${number}">` +
    `<figcaption><span class="figure-label">Listing ${number}.</span> ` +
    `${caption(md, content, env, `listing ${name}`)} ` +
    `<span class="listing-implements">WGSL: ${links} (shader library).</span></figcaption>` +
    `<pre class="pseudocode"><code>` +
    `${highlightPseudocode(listing.code)}</code></pre></figure>\n`
  );
}

/** markdown-it plugin: ```figure NAME``` and ```listing NAME``` fences (see above). */
export function figuresAndListings(md: MarkdownIt): void {
  const previous = md.renderer.rules.fence;
  md.renderer.rules.fence = (tokens, index, options, env, self) => {
    const token = tokens[index];
    const [kind, name, ...rest] = (token?.info ?? '').trim().split(/\s+/);
    if (token && (kind === 'figure' || kind === 'listing')) {
      const figureEnv = env as FigureEnv;
      if (!name || rest.length > 0) {
        throw new Error(`${figureEnv.file}: write \`\`\`${kind} NAME, got "${token.info.trim()}"`);
      }
      return kind === 'figure'
        ? renderFigure(md, name, token.content, figureEnv)
        : renderListing(md, name, token.content, figureEnv);
    }
    return previous
      ? previous(tokens, index, options, env, self)
      : self.renderToken(tokens, index, options);
  };
}

const NUMBERED =
  /<figure class="(?:diagram-figure|listing)" id="((?:fig|lst):[a-z0-9-]+)" data-number="([^"]+)">/g;

/** The figure and listing labels a rendered page defines. */
export function collectFigureLabels(html: string, page: string): FigureLabel[] {
  return [...html.matchAll(NUMBERED)].map((match) => {
    const label = match[1] ?? '';
    return {
      label,
      kind: label.startsWith('fig:') ? 'Figure' : 'Listing',
      number: match[2] ?? '',
      page,
    };
  });
}

/**
 * Replaces each empty link `[](#fig:NAME)` / `[](#lst:NAME)` with "Figure 2.1" /
 * "Listing 6.1" and a link to it (on its own page or another chapter's).
 */
export function resolveFigureReferences(
  html: string,
  labels: Map<string, FigureLabel>,
  currentPage: string,
  file: string,
): string {
  return html.replace(/<a href="#((?:fig|lst):[^"]+)"><\/a>/g, (_all, label: string) => {
    const target = labels.get(label);
    if (!target) throw new Error(`${file}: reference to unknown figure or listing "${label}"`);
    const href = target.page === currentPage ? `#${label}` : `${target.page}#${label}`;
    return `<a class="figref" href="${href}">${target.kind}&nbsp;${target.number}</a>`;
  });
}
