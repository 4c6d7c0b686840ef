// Exercises embedded in chapters (issue 7): the build renders the statement with
// the chapter's Markdown + KaTeX pipeline inside <sb-exercise>, so it reads without
// JavaScript, adds the starter code, and reports a bad embedding with the file name.
import { mkdirSync, mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { createMarkdown, renderChapterBody } from '../../src/book/build/markdown.ts';

const DIR = mkdtempSync(join(tmpdir(), 'sb-exercises-'));
mkdirSync(join(DIR, 'slab'));
writeFileSync(
  join(DIR, 'slab', 'statement.md'),
  '# Transmittance of a slab\n\nWrite $T = e^{-\\sigma_t d}$ so that\n\n$$\nT(d) = e^{-\\sigma_t d}\n\\label{eq:exercise-slab}\n$$\n\nTolerance: $10^{-5}$ relative.\n',
);
writeFileSync(
  join(DIR, 'slab', 'starter.wgsl'),
  'fn transmittance(sigmaT: f32, d: f32) -> f32 {\n  return 1.0; // a < b && c > d\n}\n',
);

function render(body: string) {
  return renderChapterBody(createMarkdown(), body, 2, '/chapters/02-test.html', 'test.md', DIR);
}

describe('<sb-exercise> in a chapter', () => {
  const result = render(
    '## Exercise\n\nTry it.\n\n<sb-exercise exercise="slab"></sb-exercise>\n\n## Summary\n',
  );

  it('renders the statement with math typeset at build time, headings under the section', () => {
    // Before the statement: which browsers run the checks, so a student knows before writing code.
    expect(result.html).toMatch(
      /<sb-exercise exercise="slab"><p class="sb-exercise-browsers">[^<]*<strong>Browsers\.<\/strong>[^<]*Chrome or Edge \(113 or later\), Safari 26 or later, Firefox 141 or later on Windows[^<]*<\/p><div class="sb-exercise-statement">/,
    );
    // Not inside a paragraph: a <div> there would end the <p> and leave the element empty.
    expect(result.html).not.toMatch(/<p>\s*<sb-exercise/);
    expect(result.html).not.toMatch(/<\/sb-exercise>\s*<\/p>/);
    expect(result.html).toMatch(/<h3[^>]*>Transmittance of a slab<\/h3>/);
    expect(result.html).not.toMatch(/<h1/);
    expect(result.html).toContain('class="katex"');
    expect(result.html).not.toMatch(/\$\$|\\label\{/);
    // The statement's equation is numbered in the chapter's sequence.
    expect(result.equations.map((e) => [e.label, e.number])).toEqual([['eq:exercise-slab', '2.1']]);
  });

  it('lists the starter code, escaped, and a no-JavaScript note; registers the widget', () => {
    expect(result.html).toContain('<pre><code class="language-wgsl">fn transmittance(');
    expect(result.html).toContain('a &lt; b &amp;&amp; c &gt; d');
    expect(result.html).toContain('needs JavaScript');
    expect(result.widgets).toEqual(['exercise']);
    // The exercise is not a table-of-contents entry; the chapter's own headings are.
    expect(result.toc.map((t) => t.text)).toEqual(['Exercise', 'Summary']);
  });

  it('reports an unknown or malformed exercise with the chapter file', () => {
    expect(() => render('<sb-exercise exercise="nope"></sb-exercise>\n')).toThrow(
      /test\.md: exercise "nope" has no .*statement\.md/,
    );
    expect(() => render('<sb-exercise exercise="Bad Id"></sb-exercise>\n')).toThrow(
      /test\.md: <sb-exercise> needs exercise="id"/,
    );
    expect(() => render('<sb-exercise></sb-exercise>\n')).toThrow(/needs exercise="id"/);
  });
});
