// The MathML in every built page is structurally valid: each fixed-arity element
// (msub, msup, msubsup, mfrac, mroot, munder, mover, munderover) has the number of
// children MathML Core requires. Firefox logs every violation as a page error
// ("Invalid markup: Incorrect number of children for <msub/> tag") and screen readers
// read this markup. The scan covers chapters, the exercise statements embedded in
// them, the appendix, the deck and the home page.
import { fileURLToPath } from 'node:url';
import katex from 'katex';
import { describe, expect, it } from 'vitest';
import { buildBook } from '../../src/book/build/generate.ts';
import { MATHML_ARITY, mathmlArityProblems, repairMathml } from '../../src/book/build/mathml.ts';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));

function mathml(tex: string, displayMode = false): string {
  return katex.renderToString(tex, { displayMode, throwOnError: true, output: 'mathml' });
}

describe('MathML in the built pages', () => {
  const book = buildBook(ROOT);

  it('every fixed-arity element on every page has the children MathML requires', () => {
    const problems: string[] = [];
    let scanned = 0;
    for (const page of book.pages) {
      const fixedArity = new RegExp(`<(${Object.keys(MATHML_ARITY).join('|')})>`, 'g');
      scanned += [...page.html.matchAll(fixedArity)].length;
      for (const problem of mathmlArityProblems(page.html)) {
        problems.push(
          `${page.file}: <${problem.element}> with ${problem.children} children (needs ` +
            `${problem.expected}) in "${problem.tex}"`,
        );
      }
    }
    // The scan must have seen the book's math, or it proves nothing.
    expect(scanned).toBeGreaterThan(500);
    expect(problems).toEqual([]);
  });

  it('the scan covers the exercise statements and the appendix', () => {
    const statements = book.pages.filter((page) => page.html.includes('sb-exercise-statement'));
    expect(statements.length).toBeGreaterThan(0);
    for (const page of statements) {
      const statement = page.html.slice(page.html.indexOf('sb-exercise-statement'));
      expect(statement, page.file).toContain('<math');
    }
    const appendix = book.pages.find((page) => page.file === 'appendix/shader-library.html');
    expect(appendix?.html).toContain('<msub>');
  });
});

describe('mathmlArityProblems', () => {
  it('accepts well-formed scripts, fractions, roots and limits', () => {
    for (const tex of [
      'x_i',
      'x^2',
      'x_i^2',
      '\\frac{a}{b}',
      '\\sqrt[3]{x}',
      '\\max_k x_{\\min,k}',
    ])
      expect(mathmlArityProblems(mathml(tex)), tex).toEqual([]);
    expect(mathmlArityProblems(mathml('\\sum_{i=1}^{n} x_i', true))).toEqual([]);
  });

  it('reports each fixed-arity element with too many or too few children, with its TeX', () => {
    const bad =
      '<math><semantics><mrow><msub><mi>a</mi></msub><mfrac><mn>1</mn><mn>2</mn><mn>3</mn></mfrac>' +
      '<munderover><mo>∑</mo><mi>i</mi></munderover><msup><mi>x</mi><mn>2</mn></msup></mrow>' +
      '<annotation encoding="application/x-tex">bad</annotation></semantics></math>';
    expect(mathmlArityProblems(bad)).toEqual([
      { element: 'msub', children: 1, expected: 2, tex: 'bad' },
      { element: 'mfrac', children: 3, expected: 2, tex: 'bad' },
      { element: 'munderover', children: 2, expected: 3, tex: 'bad' },
    ]);
  });

  it('refuses markup whose tags do not nest', () => {
    expect(() => mathmlArityProblems('<math><msub><mi>a</msub></mi></math>')).toThrow(/malformed/);
  });
});

describe('repairMathml', () => {
  // KaTeX writes an operator name in a script as <mi>max</mi><mo>⁡</mo>, two children
  // where MathML needs one: every fixed-arity element and both script positions.
  const broken: [string, boolean][] = [
    ['L_{\\max}', false],
    ['a_{\\log}^{\\sin}', false],
    ['x_{\\operatorname{foo}}', false],
    ['\\frac{\\max}{2}', false],
    ['\\sqrt[\\max]{x}', false],
    ['\\underset{\\max}{x}', false],
    ['\\overset{\\lim}{x}', false],
    ['\\sum_{\\max}^{\\min} x', true],
  ];

  it('KaTeX still produces the malformed markup the repair exists for', () => {
    expect(mathmlArityProblems(mathml('L_{\\max}')).length).toBe(1);
  });

  for (const [tex, display] of broken) {
    it(`groups the operator name in ${tex}`, () => {
      const repaired = repairMathml(mathml(tex, display));
      expect(mathmlArityProblems(repaired)).toEqual([]);
      expect(repaired).toMatch(/<mrow><mi[^>]*>[a-z]+<\/mi><mo>\u2061<\/mo><\/mrow>/);
    });
  }

  it('keeps the script content: L_{max} reads L, then max', () => {
    expect(repairMathml(mathml('L_{\\max}'))).toContain(
      '<msub><mi>L</mi><mrow><mi>max</mi><mo>\u2061</mo></mrow></msub>',
    );
  });

  it('leaves valid math byte for byte unchanged, the HTML rendering included', () => {
    for (const tex of ['\\max_k x_{\\min,k}', 'T = e^{-\\sigma_t d}', '\\sin\\theta\\,\\log x']) {
      const html = katex.renderToString(tex, { output: 'htmlAndMathml' });
      expect(repairMathml(html), tex).toBe(html);
    }
  });
});
