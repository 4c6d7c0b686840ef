// Source handling: loop instrumentation, comment blanking, signature parsing and
// the mapping of compiler positions back to the student's text.
import { describe, expect, it } from 'vitest';
import {
  blankComments,
  instrumentLoops,
  mapPosition,
  parseFunctions,
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
