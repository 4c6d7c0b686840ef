// Embed pages (src/book/build/embeds.ts) and the Copy menu's iframe snippet
// (src/widgets/base/embedCode.ts): one page per catalog widget with the chapter's
// instances, relative links only, and a snippet whose state does not depend on the
// embed page's attributes.
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { buildBook } from '../../src/book/build/generate.ts';
import { planEmbeds, renderEmbedPage, widgetInstances } from '../../src/book/build/embeds.ts';
import type { ChapterSource } from '../../src/book/build/chapters.ts';
import {
  fullState,
  embedHeight,
  embedInstanceId,
  embedUrl,
  iframeSnippet,
} from '../../src/widgets/base/embedCode.ts';
import { WIDGET_CATALOG } from '../../src/widgets/catalog.ts';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));
const book = buildBook(ROOT);

function chapter(slug: string, number: number): ChapterSource {
  return { number, slug, title: `Title ${number}`, summary: 's', body: '', file: `${slug}.md` };
}

describe('embed pages', () => {
  it('exist for every widget in the catalog, and the embed appendix links each one', () => {
    const index = book.pages.find((page) => page.file === 'embed/index.html')?.html ?? '';
    for (const widget of Object.keys(WIDGET_CATALOG)) {
      const page = book.pages.find((p) => p.file === `embed/${widget}.html`);
      expect(page, widget).toBeDefined();
      expect(page?.widgets).toEqual([widget]);
      expect(page?.html).toContain(`<sb-${widget} id="${widget}-1"`);
      expect(index).toContain(`href="${widget}.html"`);
    }
    const home = book.pages.find((page) => page.file === 'index.html')?.html ?? '';
    expect(home).toMatch(/href="[^"]*embed\/index\.html"/);
  });

  it('carry no site chrome and only relative URLs, and link back to the chapter in a new tab', () => {
    for (const page of book.pages.filter((p) => /^embed\/(?!index)/.test(p.file))) {
      expect(page.html).not.toMatch(/site-header|site-footer|theme-toggle/);
      for (const match of page.html.matchAll(/\s(?:href|src)="([^"]*)"/g))
        expect(match[1], `${page.file}: ${match[1]}`).toMatch(/^\.\.\/|^[a-z0-9-]+\.html/);
      expect(page.html).toMatch(
        /<a class="embed-chapter-link" href="\.\.\/chapters\/\d\d-[a-z0-9-]+\.html" target="_blank" rel="noopener">Open in the book: \d+\. /,
      );
    }
  });

  it("hold every instance of the widget in its first chapter, with the chapter's ids and attributes", () => {
    const html =
      '<p>x</p><sb-hg-lobe g="0.6"><p>fallback</p></sb-hg-lobe>' +
      '<sb-hg-lobe-x></sb-hg-lobe-x><sb-hg-lobe g="-0.3" scale="log"></sb-hg-lobe>';
    expect(widgetInstances(html, 'hg-lobe')).toEqual([
      { id: 'hg-lobe-1', attributes: ' g="0.6"', content: '<p>fallback</p>' },
      { id: 'hg-lobe-2', attributes: ' g="-0.3" scale="log"', content: '' },
    ]);
    const pages = [
      { chapter: chapter('01-a', 1), html: '<p>no widgets</p>' },
      { chapter: chapter('03-c', 3), html },
      { chapter: chapter('04-d', 4), html: '<sb-hg-lobe g="0.1"></sb-hg-lobe>' },
    ];
    const missing = (): unknown => planEmbeds(pages);
    // The other catalog widgets are in no chapter here: the build refuses that.
    expect(missing).toThrow(/in no chapter/);
    const all = Object.keys(WIDGET_CATALOG).map((widget) => ({
      chapter: chapter('05-e', 5),
      html: `<sb-${widget}></sb-${widget}>`,
    }));
    const embeds = planEmbeds([...pages, ...all]);
    const lobe = embeds.find((embed) => embed.widget === 'hg-lobe');
    expect(lobe?.chapter.slug).toBe('03-c');
    expect(lobe?.instances.map((instance) => instance.id)).toEqual(['hg-lobe-1', 'hg-lobe-2']);
    const page = lobe ? renderEmbedPage(lobe, 'Scatterbook') : '';
    expect(page).toContain('<sb-hg-lobe id="hg-lobe-1" g="0.6">');
    expect(page).toContain(
      '<template class="embed-instance" data-instance="hg-lobe-2"><sb-hg-lobe id="hg-lobe-2" g="-0.3" scale="log">',
    );
    expect(page).toContain('href="../chapters/03-c.html"');
  });
});

describe('the iframe snippet', () => {
  it('opens the embed page with the full state under the site root, with a title and lazy loading', () => {
    const url = embedUrl('https://uni.example/courses/cmsc740/book/', 'hg-lobe', 'hg-lobe-2', [
      ['g', '-0.5'],
      ['compare', 'rayleigh'],
    ]);
    expect(url).toBe(
      'https://uni.example/courses/cmsc740/book/embed/hg-lobe.html#hg-lobe-2.g=-0.5&hg-lobe-2.compare=rayleigh&v=1',
    );
    // A deck slide's widget (id slide-5-widget) maps to the embed's first instance.
    expect(embedInstanceId('hg-lobe', 'slide-5-widget')).toBe('hg-lobe-1');
    expect(embedUrl('http://localhost:5173/', 'exercise', 'exercise-1', [])).toBe(
      'http://localhost:5173/embed/exercise.html#exercise-1',
    );
    const snippet = iframeSnippet(url, 'Beer\'s law "quoted" <b>', embedHeight(603));
    expect(snippet).toBe(
      `<iframe src="${url.replace(/&/g, '&amp;')}" title="Beer's law &quot;quoted&quot; &lt;b&gt;" ` +
        'width="100%" height="680" loading="lazy" allow="fullscreen" style="border: 0; max-width: 100%"></iframe>',
    );
    expect(embedHeight(0)).toBe(320);
    // The state in the snippet names every parameter, defaults included.
    const lobe = WIDGET_CATALOG['hg-lobe'];
    expect(
      fullState(lobe?.parameters ?? [], {
        g: 0.6,
        compare: 'isotropic',
        scale: 'linear',
        samples: 16,
        seed: 1,
      }),
    ).toEqual([
      ['g', '0.6'],
      ['compare', 'isotropic'],
      ['scale', 'linear'],
      ['samples', '16'],
      ['seed', '1'],
    ]);
    expect(embedHeight(5000)).toBe(2000);
  });
});
