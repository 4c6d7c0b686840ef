// Hostile submissions found by red-teaming the grader (issue 15): each test pins the
// class of problem, not only the example file in exercises/*/wrong/.
import { describe, expect, it } from 'vitest';
import {
  blankComments,
  blankImports,
  inlinedSize,
  MAX_INLINED_TOKENS,
  normalizeSource,
  prepareSource,
  tokenize,
} from '../../src/grading/instrument.ts';

const sizeOf = (source: string) => inlinedSize(tokenize(blankComments(normalizeSource(source))));

/** f_k calls f_{k-1} `width` times; f_0 is one statement. */
function callTree(depth: number, width: number): string {
  const lines = ['fn e0(x: f32) -> f32 { return x + 1.0; }'];
  for (let k = 1; k <= depth; k++) {
    const calls =
      Array.from({ length: width }, () => `e${k - 1}(`).join('') + 'x' + ')'.repeat(width);
    lines.push(`fn e${k}(x: f32) -> f32 { return ${calls}; }`);
  }
  lines.push(`fn f(x: f32) -> f32 { return e${depth}(x); }`);
  return lines.join('\n');
}

describe('the inlined size of a call tree is bounded before compiling', () => {
  it('counts each call as the callee inlined, whatever the declaration order', () => {
    // e0's body `{ return x + 1.0;` counts 5 tokens (a literal is no token; the
    // closing brace is not counted).
    const one = sizeOf('fn e0(x: f32) -> f32 { return x + 1.0; }');
    expect(one).toEqual({ name: 'e0', tokens: 5 });
    const forward = sizeOf(
      'fn g(x: f32) -> f32 { return h(h(x)); }\nfn h(x: f32) -> f32 { return x + 1.0; }',
    );
    // g: `{ return h ( h ( x ) ) ;` is 10 tokens, plus h inlined twice.
    expect(forward).toEqual({ name: 'g', tokens: 10 + 2 * 5 });
  });

  it('grows exponentially with a doubling tree and saturates instead of overflowing', () => {
    const size = (d: number) => sizeOf(callTree(d, 2))?.tokens ?? 0;
    expect(size(11) / size(10)).toBeGreaterThan(1.9);
    expect(size(40)).toBeGreaterThan(2 ** 40);
    expect(Number.isNaN(sizeOf(callTree(1100, 2))?.tokens)).toBe(false);
  });

  it('ignores a recursive cycle (the compiler reports it) and calls of builtins or structs', () => {
    const cyclic = sizeOf(
      'struct S { a: f32 }\nfn a(x: f32) -> f32 { return b(x) + exp(x) + S(x).a; }\nfn b(x: f32) -> f32 { return a(x); }',
    );
    expect(cyclic?.tokens).toBeLessThan(40);
  });

  it('refuses a multiplying call tree but accepts a long straight-line submission', () => {
    const refused = prepareSource(callTree(40, 2), 100);
    expect(refused.ok).toBe(false);
    if (!refused.ok) expect(refused.message).toMatch(/inlines to about \d\.\de\+13 tokens/);
    // 60 KB of straight-line code stays under the cap: only call trees are refused.
    const statements = '  y = y * 1.0001 + 0.0001;\n'.repeat(2200);
    const long = `fn f(x: f32) -> f32 {\n  var y = x;\n${statements}  return y;\n}\n`;
    expect(prepareSource(long, 100).ok).toBe(true);
    expect(sizeOf(long)?.tokens).toBeLessThan(MAX_INLINED_TOKENS);
  });

  it('is linear: 5,000 functions in a chain are measured without recursion', () => {
    const chain = Array.from(
      { length: 5000 },
      (_, k) => `fn c${k}(x: f32) -> f32 { return ${k > 0 ? `c${k - 1}(x)` : 'x'}; }`,
    ).join('\n');
    const started = performance.now();
    expect(sizeOf(chain)?.name).toBe('c4999');
    expect(performance.now() - started).toBeLessThan(2000);
  });
});

describe('results depend only on the arguments', () => {
  it('refuses var<workgroup> however it is spelled, and accepts var<private> and function vars', () => {
    for (const spelling of [
      'var<workgroup>',
      'var < /* c */ workgroup >',
      'var\n<\nworkgroup\n>',
    ]) {
      const prepared = prepareSource(
        `${spelling} w: array<f32, 4>;\nfn f(x: f32) -> f32 { w[0] = x; return w[1]; }`,
        100,
      );
      expect(prepared.ok).toBe(false);
      if (!prepared.ok) expect(prepared.message).toMatch(/line \d, column \d+: `var<workgroup>`/);
    }
    const allowed = prepareSource(
      'var<private> p: f32;\nfn f(x: f32) -> f32 { var workgroup = x; p = workgroup; return p; }',
      100,
    );
    expect(allowed.ok).toBe(true);
  });
});

describe('import lines are found in linear time', () => {
  it('reads `import`, 60,000 blanks and `;x` quickly (the multiline regex took 24 s)', () => {
    const started = performance.now();
    const hostile = `import${' '.repeat(60000)};x\nfn f() {}`;
    // Code after the `;`: not an import line, kept.
    expect(blankImports(hostile)).toBe(hostile);
    const unterminated = `${'import a\n'.repeat(6000)}${' '.repeat(30000)};`;
    expect(blankImports(unterminated).startsWith(' '.repeat(8))).toBe(true);
    expect(performance.now() - started).toBeLessThan(1000);
  });

  it('keeps the rules: any leading blanks, one `;` then blanks, whole word only', () => {
    const lines = [
      `${' '.repeat(100)}import package::a::b;`,
      '\timport package::c;  \t',
      'import package::d',
      'importance = 1.0;',
      'import a; let x = 1;',
    ];
    const out = blankImports(lines.join('\n')).split('\n');
    expect(out.slice(0, 3)).toEqual(lines.slice(0, 3).map((l) => ' '.repeat(l.length)));
    expect(out.slice(3)).toEqual(lines.slice(3));
  });
});

describe('every regex of the preprocessing is linear on 60 KB floods', () => {
  it('prepares each flood in well under a second (quadratic backtracking took 4 to 24 s)', () => {
    const floods: Record<string, string> = {
      importBlanks: `import${' '.repeat(60000)};x`,
      unclosedAttributes: `fn f(${'@a('.repeat(20000)}: f32`,
      attributeBlanks: `fn f(${'@ '.repeat(30000)}: f32) {}`,
      arrowFlood: `fn f() ->${' x'.repeat(30000)}`,
      hexFlood: `0x${'a'.repeat(60000)}`,
    };
    for (const [name, source] of Object.entries(floods)) {
      const started = performance.now();
      prepareSource(source, 100);
      const ms = performance.now() - started;
      expect(ms, name).toBeLessThan(1500);
    }
  });
});
