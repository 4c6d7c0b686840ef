// The chapter pipeline: every chapter builds, math is typeset at build time,
// equation labels are numbered and references resolve, mistakes in a chapter are
// reported with the file name, and code comments only cite labels that exist.
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { buildBook } from '../../src/book/build/generate.ts';
import { parseChapter } from '../../src/book/build/chapters.ts';
import {
  createMarkdown,
  renderChapterBody,
  resolveEquationReferences,
} from '../../src/book/build/markdown.ts';
import { loadShaderDocs, parseShaderModule } from '../../src/book/build/shaderDocs.ts';
import { WIDGET_CATALOG } from '../../src/widgets/catalog.ts';
import { parseParameters } from '../../src/widgets/parameters.ts';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));
const book = buildBook(ROOT);

function render(body: string) {
  return renderChapterBody(createMarkdown(), body, 7, '/chapters/07-test.html', 'test.md');
}

describe('the book builds', () => {
  it('has a home page, one page per chapter numbered from the file names, the library appendix, the deck, the embeds and the answer key', () => {
    expect(book.pages[0]?.file).toBe('index.html');
    // Numbers come from the file names and increase; the book may skip numbers while
    // chapters are being written (DESIGN.md numbers them in lecture order).
    const numbers = book.chapters.map((c) => c.number);
    expect(numbers[0]).toBe(1);
    numbers.slice(1).forEach((n, i) => expect(n).toBeGreaterThan(numbers[i] ?? Infinity));
    for (const chapter of book.chapters)
      expect(chapter.slug.startsWith(String(chapter.number).padStart(2, '0'))).toBe(true);
    expect(book.pages.map((p) => p.file).slice(book.chapters.length + 1)).toEqual([
      'appendix/shader-library.html',
      'deck.html',
      ...Object.keys(WIDGET_CATALOG).map((widget) => `embed/${widget}.html`),
      'embed/index.html',
      'appendix/answers.html',
    ]);
  });

  it('the appendix documents every library function from its doc comments', () => {
    const appendix =
      book.pages.find((page) => page.file === 'appendix/shader-library.html')?.html ?? '';
    for (const module of loadShaderDocs(join(ROOT, 'shaders'))) {
      for (const declaration of module.declarations.filter((d) => d.kind === 'fn')) {
        expect(appendix, `${module.name}.${declaration.name}`).toContain(
          `id="${module.name}-${declaration.name}"`,
        );
      }
    }
    expect(appendix).toContain('Beer');
  });

  it('typesets all math at build time: no $$ delimiters or \\label are left in the HTML (TeX survives only in MathML annotations)', () => {
    for (const page of book.pages) {
      expect(page.html, page.file).not.toMatch(/\$\$|\\label\{/);
    }
  });

  it('every widget tag in a chapter has valid attributes', () => {
    for (const page of book.pages) {
      for (const match of page.html.matchAll(/<sb-([a-z-]+)([^>]*)>/g)) {
        const entry = WIDGET_CATALOG[match[1] ?? ''];
        expect(entry, `widget sb-${match[1]} on ${page.file}`).toBeDefined();
        const attributes = new Map(
          [...(match[2] ?? '').matchAll(/([a-z-]+)="([^"]*)"/g)].map((m) => [m[1], m[2]]),
        );
        const parsed = parseParameters(entry?.parameters ?? [], (name) => attributes.get(name));
        expect(parsed.warnings, `attributes of sb-${match[1]} on ${page.file}`).toEqual([]);
      }
    }
  });
});

describe('equations', () => {
  it('are numbered chapter.n in order with anchors', () => {
    const result = render(
      '$$\na = b\n\\label{eq:first}\n$$\n\ntext\n\n$$\nc = d\n\\label{eq:second}\n$$\n',
    );
    expect(result.equations.map((e) => [e.label, e.number])).toEqual([
      ['eq:first', '7.1'],
      ['eq:second', '7.2'],
    ]);
    expect(result.html).toContain('id="eq:first"');
    expect(result.html).toContain('(7.2)');
  });

  it('references resolve to numbers, across pages too', () => {
    const labels = new Map([
      ['eq:here', { label: 'eq:here', number: '7.1', page: '/chapters/07-test.html' }],
      ['eq:there', { label: 'eq:there', number: '2.3', page: '/chapters/02-x.html' }],
    ]);
    const html = resolveEquationReferences(
      '<a href="#eq:here"></a> <a href="#eq:there"></a>',
      labels,
      '/chapters/07-test.html',
      't.md',
    );
    expect(html).toContain('<a class="eqref" href="#eq:here">(7.1)</a>');
    expect(html).toContain('<a class="eqref" href="/chapters/02-x.html#eq:there">(2.3)</a>');
  });

  it('a reference to an unknown label fails the build, naming the file', () => {
    expect(() =>
      resolveEquationReferences('<a href="#eq:nope"></a>', new Map(), '/p.html', 'ch.md'),
    ).toThrow(/ch\.md: reference to unknown equation label "eq:nope"/);
  });

  it('malformed labels and bad TeX are reported with the file name', () => {
    expect(() => render('$$\nx\n\\label{Bad Label}\n$$\n')).toThrow(/test\.md.*label/);
    expect(() => render('$$\n\\frac{1}{\n$$\n')).toThrow(/test\.md: KaTeX cannot typeset/);
  });

  it('every label cited in the book exists', () => {
    for (const page of book.pages) {
      for (const match of page.html.matchAll(/href="[^"]*#(eq:[a-z0-9-]+)"/g)) {
        expect(book.equations.has(match[1] ?? ''), `${page.file} cites ${match[1]}`).toBe(true);
      }
    }
  });

  it('code comments that cite an equation label cite one that exists (STYLE.md 6)', () => {
    const files: string[] = [];
    const visit = (folder: string): void => {
      for (const name of readdirSync(folder)) {
        const path = join(folder, name);
        if (statSync(path).isDirectory()) visit(path);
        else if (/\.(ts|wesl)$/.test(name)) files.push(path);
      }
    };
    visit(join(ROOT, 'src'));
    visit(join(ROOT, 'shaders'));
    for (const file of files) {
      for (const match of readFileSync(file, 'utf8').matchAll(
        /\b(eq:[a-z0-9]+(?:-[a-z0-9]+)*)\b/g,
      )) {
        const label = match[1] ?? '';
        if (file.endsWith('build.test.ts') || label === 'eq:lowercase-words') continue;
        expect(book.equations.has(label), `${file} cites ${label}`).toBe(true);
      }
    }
  });
});

describe('chapter sources', () => {
  it('need front matter with a title and a summary', () => {
    expect(() => parseChapter('chapters/03-x.md', '# no front matter')).toThrow(/front matter/);
    expect(() => parseChapter('chapters/03-x.md', '---\ntitle: T\n---\nbody')).toThrow(/summary/);
    expect(() => parseChapter('chapters/x.md', '---\ntitle: T\nsummary: S\n---\n')).toThrow(
      /NN-slug/,
    );
  });

  it('an unknown widget tag fails the build', () => {
    expect(() => render('<sb-no-such-widget></sb-no-such-widget>\n')).toThrow(
      /unknown widget <sb-no-such-widget>/,
    );
  });

  it('widgets get a no-JavaScript fallback message', () => {
    expect(render('<sb-beer-law thickness="2"></sb-beer-law>\n').html).toMatch(
      /<sb-beer-law thickness="2"><p class="widget-fallback">/,
    );
  });
});

describe('shader doc comments', () => {
  it('attach /// lines to the declaration right below them, and the leading // block to the module', () => {
    const docs = parseShaderModule(
      'm',
      '// Module text.\n\n/// Doc of f.\n/// More.\nfn f(a: f32,\n  b: f32) -> f32 {\n  return a;\n}\n\nfn g() {}\n/// C.\nconst C: f32 = 1.0;\n',
    );
    expect(docs.description).toBe('Module text.');
    expect(docs.declarations.map((d) => [d.kind, d.name, d.doc])).toEqual([
      ['fn', 'f', 'Doc of f.\nMore.'],
      ['fn', 'g', ''],
      ['const', 'C', 'C.'],
    ]);
    expect(docs.declarations[0]?.signature).toBe('fn f(a: f32,\n  b: f32) -> f32');
  });
});
