// Source handling: loop instrumentation, comment blanking, signature parsing and
// the mapping of compiler positions back to the student's text.
import { describe, expect, it } from 'vitest';
import {
  blankComments,
  blankImports,
  findRefusals,
  instrumentLoops,
  LineIndex,
  mapPosition,
  MAX_SUBMISSION_BYTES,
  normalizeSource,
  parseFunctions,
  prepareSource,
  tokenize,
  utf8Length,
} from '../../src/grading/instrument.ts';

describe('loop instrumentation', () => {
  it('guards loop, for and while bodies, not comments or identifiers', () => {
    const source = [
      'fn f(n: u32) -> f32 {',
      '  var s = 0.0; // a loop { } in a comment',
      '  for (var i = 0u; i < n; i++) { s += 1.0; }',
      '  var j = 0u;',
      '  while (j < n) { j++; }',
      '  let whileLoop = 1u; /* loop { */',
      '  loop { if (s > 3.0) { break; } s += 1.0; }',
      '  return s;',
      '}',
    ].join('\n');
    const result = instrumentLoops(source, 100);
    expect(result.loops).toBe(3);
    expect(result.source.split('\n')).toHaveLength(9);
    expect(result.source).toContain(
      '{ sbg_iterations += 1u; if (sbg_iterations > 100u) { sbg_budgetExceeded = 1u; return f32(); } s += 1.0; }',
    );
    // Comments keep their text; only code is touched.
    expect(result.source).toContain('// a loop { } in a comment');
    expect(result.insertions.map((i) => i.line)).toEqual([3, 5, 7]);
  });

  it('returns nothing from a function without a result', () => {
    const result = instrumentLoops('fn g() {\n  loop { }\n}', 5);
    expect(result.source).toContain('return; }');
  });

  it('maps compiler columns past an insertion back to the student text', () => {
    const source = 'fn f() -> f32 {\n  loop { let x = 1.0 }\n}';
    const { insertions, source: out } = instrumentLoops(source, 8);
    const line = out.split('\n')[1] ?? '';
    const column = line.indexOf('let x') + 1;
    // Two lines of prelude in front.
    expect(mapPosition(2 + 2, column, 2, insertions)).toEqual({
      line: 2,
      column: (source.split('\n')[1] ?? '').indexOf('let x') + 1,
    });
    // Positions before the insertion do not move.
    expect(mapPosition(4, 3, 2, insertions)).toEqual({ line: 2, column: 3 });
  });
});

describe('signature parsing', () => {
  it('reads names, parameter types and results, ignoring comments', () => {
    const functions = parseFunctions(
      '// fn fake(x: f32) -> f32 {\nfn a(x : f32, state: ptr< function , u32 >) -> f32 { return x; }\nfn b(v: vec3<f32>) { }',
    );
    expect(functions.map((f) => f.name)).toEqual(['a', 'b']);
    expect(functions[0]?.params).toEqual([
      { name: 'x', type: 'f32' },
      { name: 'state', type: 'ptr<function, u32>' },
    ]);
    expect(functions[0]?.result).toBe('f32');
    expect(functions[1]?.params[0]?.type).toBe('vec3f');
    expect(functions[1]?.result).toBeNull();
  });

  it('blanks nested block comments without moving text', () => {
    const text = 'a /* b /* c */ d */ e\nf // g';
    const blank = blankComments(text);
    expect(blank).toHaveLength(text.length);
    expect(blank.replace(/\s+/g, ' ').trim()).toBe('a e f');
  });
});

describe('normalisation: every WGSL line break ends a // comment', () => {
  const breaks = ['\n', '\r\n', '\r', '\v', '\f', '\u0085', '\u2028', '\u2029'];

  it('turns every line break into LF and drops a byte-order mark', () => {
    for (const lineBreak of breaks) {
      const text = `\ufeffa // c${lineBreak}b${lineBreak}c`;
      expect(normalizeSource(text)).toBe('a // c\nb\nc');
    }
    // A mark elsewhere is not a byte-order mark: the compiler reports it.
    expect(normalizeSource('a\ufeffb')).toBe('a\ufeffb');
  });

  it('ends a line comment at every break even without normalisation', () => {
    for (const lineBreak of breaks) {
      const blank = blankComments(`// hidden${lineBreak}sbg_x = 0u;`);
      expect(blank).toContain('sbg_x = 0u;');
    }
  });

  it('finds code hidden behind any break: reserved names, loops, bindings', () => {
    for (const lineBreak of breaks) {
      const reset = prepareSource(
        `fn f() -> f32 {\n  loop { // keep going${lineBreak}  sbg_iterations = 0u; }\n}`,
        10,
      );
      expect(reset.ok).toBe(false);
      if (!reset.ok) expect(reset.message).toContain('`sbg_iterations`');
      const loop = prepareSource(`fn f() -> f32 {\n  // x${lineBreak}  loop { }\n}`, 10);
      expect(loop.ok && loop.instrumented.loops).toBe(1);
    }
  });
});

describe('prepareSource: size cap, refusals with positions', () => {
  it('refuses more than 64 KiB of UTF-8 before parsing, counting bytes', () => {
    expect(MAX_SUBMISSION_BYTES).toBe(65536);
    const fits = `fn f() {}${' '.repeat(MAX_SUBMISSION_BYTES - 9)}`;
    expect(prepareSource(fits, 10).ok).toBe(true);
    const over = prepareSource(`${fits} `, 10);
    expect(over.ok).toBe(false);
    if (!over.ok) expect(over.message).toContain('65537 bytes');
    // σ is two bytes in UTF-8: half as many characters already exceed the cap.
    expect(prepareSource('σ'.repeat(MAX_SUBMISSION_BYTES / 2 + 1), 10).ok).toBe(false);
    expect(utf8Length('aσ€😀')).toBe(1 + 2 + 3 + 4);
    expect(utf8Length('😀')).toBe(new TextEncoder().encode('😀').length);
  });

  it('refuses bindings, entry points, directives, override and reserved names, at their line and column', () => {
    const source = [
      '@group(0) @binding(2) var<storage, read_write> x: array<u32>;', // 1
      'enable f16;', // 2
      '@/* c */compute @workgroup_size(1) fn main() {}', // 3
      'override k: f32 = 1.0;', // 4
      'requires readonly_and_readwrite_storage_textures;', // 5
      '  diagnostic(off, derivative_uniformity);', // 6
      '@diagnostic(off, derivative_uniformity) fn ok() {}', // 7: an attribute, allowed
      'fn f() { let sbg_x = 1; }', // 8
      '@vertex fn v() -> @builtin(position) vec4f { return vec4f(); }', // 9
      '@ fragment fn p() {}', // 10
    ].join('\r\n');
    const result = prepareSource(source, 10);
    expect(result.ok).toBe(false);
    if (result.ok) return;
    const refusals = findRefusals(
      tokenize(blankComments(normalizeSource(source))),
      new LineIndex(normalizeSource(source)),
    );
    expect(refusals.map((r) => `${r.line}:${r.column}`)).toEqual([
      '1:1',
      '1:11',
      '2:1',
      '3:1',
      '4:1',
      '5:1',
      '6:3',
      '8:14',
      '9:1',
      '10:1',
    ]);
    expect(result.message).toContain('line 1, column 1: `@group`');
    expect(result.message).toContain('(5 more)');
    // Allowed: what the exercises need.
    const fine = prepareSource(
      'const k = 2.0;\nvar<private> seen: u32;\nstruct S { a: f32 }\nalias R = f32;\n' +
        '@diagnostic(off, derivative_uniformity) fn f(x: f32) -> R { return x * k; }',
      10,
    );
    expect(fine.ok).toBe(true);
  });

  it('refuses control characters and undecodable bytes in code, with their position', () => {
    const result = prepareSource(
      'fn f() {\n  \u0007 return; \ufffd }\n// \u0001 and \u0000 in a comment',
      10,
    );
    expect(result.ok).toBe(false);
    if (result.ok) return;
    expect(result.message).toContain('line 2, column 3: a control character (U+0007)');
    expect(result.message).toContain('line 2, column 13: a byte sequence that is not UTF-8');
    // NUL even in a comment (Dawn refuses it anywhere); other controls there are fine.
    expect(result.message).toContain('line 3, column 10: a NUL character');
    expect(result.message).not.toContain('U+0001');
  });

  it('keeps line and column of a BOM + CR LF source (one line per CR LF)', () => {
    const source =
      '\ufefffn f(x: f32) -> f32 {\r\n  for (var i = 0; i < 3; i++) { x += 1.0; }\r\n  return x;\r\n}\r\n';
    const result = prepareSource(source, 10);
    expect(result.ok).toBe(true);
    if (!result.ok) return;
    expect(result.lineCount).toBe(5);
    expect(result.text.includes('\r')).toBe(false);
    expect(result.instrumented.insertions).toEqual([
      { line: 2, column: 32, length: expect.any(Number) as number },
    ]);
    expect(result.functions[0]).toMatchObject({ name: 'f', result: 'f32' });
  });
});

describe('imports', () => {
  it('blanks WESL import lines in place, not identifiers that start with "import"', () => {
    const source = 'import package::rng::rngNextFloat;\nfn f() -> f32 {\n  importance = 1.0;\n}';
    const out = blankImports(source);
    expect(out).toHaveLength(source.length);
    expect(out.split('\n')[0]?.trim()).toBe('');
    expect(out).toContain('importance = 1.0;');
  });
});

describe('tokens as the compiler reads them', () => {
  it('splits literals from the identifiers after them and reads Unicode identifiers whole', () => {
    const texts = tokenize('1uwhile 0x1p4fa 1e-3hx éloop loopé _ _a .5f').map((t) => t.text);
    expect(texts).toEqual(['while', 'a', 'x', 'éloop', 'loopé', '_', '_a']);
  });

  it('instruments only real loop keywords and each body once', () => {
    const source = [
      'struct loopé { a: f32 }',
      'fn éloop() -> f32 { return 1.0; }',
      'fn f(n: u32) -> f32 {',
      '  for (var i = min(0u, (n)); i < n; i++) { while (i > n) { loop { break; } } }',
      '  return éloop();',
      '}',
    ].join('\n');
    const result = instrumentLoops(source, 7);
    expect(result.loops).toBe(3);
    expect(result.insertions.map((i) => i.line)).toEqual([4, 4, 4]);
    expect(result.source.split('\n')[0]).toBe('struct loopé { a: f32 }');
  });

  it('reads parameters with comments, attributes and line breaks inside the list', () => {
    const [f] = parseFunctions(
      'fn g(\r\n  @builtin(x) a /* f32 */ : vec3<f32>, // b: u32\r  b: ptr<function,u32>\u2028) -> f32 {}',
    );
    expect(f?.params).toEqual([
      { name: 'a', type: 'vec3f' },
      { name: 'b', type: 'ptr<function, u32>' },
    ]);
  });
});

describe('preprocessing is linear in the size of the submission', () => {
  /**
   * Token reads of instrumentLoops (which also parses the functions) through a counting
   * proxy that stops the run once the reads pass `perToken` per token, so a rescanning
   * (quadratic) implementation fails at once instead of running for minutes.
   */
  function readsWithin(source: string, perToken: number): number {
    const code = blankComments(source);
    const tokens = tokenize(code);
    const limit = perToken * tokens.length;
    let reads = 0;
    const counted = new Proxy(tokens, {
      get(target, key, receiver) {
        if (typeof key === 'string' && /^\d+$/.test(key) && ++reads > limit)
          throw new Error(`more than ${perToken} reads per token`);
        return Reflect.get(target, key, receiver) as unknown;
      },
    });
    instrumentLoops(source, 5, { code, tokens: counted });
    return reads;
  }

  it('reads each token a bounded number of times (no rescans), whatever the input', () => {
    const floods = [
      (n: number) => 'fn a('.repeat(n),
      (n: number) => `fn f() -> f32 {${'loop { '.repeat(n)}${'}'.repeat(n)}}`,
      (n: number) => 'for('.repeat(n),
      (n: number) => `fn f() {${'while (true) { '.repeat(n)}}`,
      (n: number) => 'fn a(x: f32) -> f32 { return x; }\n'.repeat(n),
    ];
    for (const flood of floods) {
      // Linear: a constant number of reads per token at both sizes.
      expect(readsWithin(flood(1000), 12)).toBeGreaterThan(0);
      expect(readsWithin(flood(32000), 12)).toBeGreaterThan(0);
    }
  });

  it("handles the issue's floods: 50 KB of `fn a(` and 32,000 loops", () => {
    const fnFlood = 'fn a('.repeat(10240);
    expect(parseFunctions(fnFlood)).toHaveLength(1);
    const loops = `fn f() -> f32 {${'loop { '.repeat(32000)}${'}'.repeat(32000)}}`;
    const result = instrumentLoops(loops, 5);
    expect(result.loops).toBe(32000);
    expect(blankComments('/*'.repeat(30000) + '*/'.repeat(30000))).toBe(' '.repeat(120000));
  });
});
