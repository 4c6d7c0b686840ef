// The layout rules against the WGSL specification's own examples (§ "Memory Layout",
// "Structure Member Layout" and "Address Space Layout Constraints"), the packer's errors,
// and the generated layout table against a fresh derivation from the linked kernels.
import { describe, expect, it } from 'vitest';
import {
  packStruct,
  readStruct,
  wordsOf,
  writeStruct,
  type StructLayout,
} from '../../src/gpu/layout.ts';
import {
  deriveStruct,
  evaluateInteger,
  parseDeclarations,
  uniformViolations,
} from '../../src/gpu/layoutDerive.ts';
import { deriveKernelLayouts } from '../../src/gpu/layoutGenerate.ts';
import {
  KERNEL_LAYOUTS,
  rayleighSkyKernel,
  vreRayKernel,
} from '../../src/gpu/layouts.generated.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

const offsets = (layout: StructLayout): Record<string, number> =>
  Object.fromEntries(Object.entries(layout.members).map(([name, m]) => [name, m.offset]));

// WGSL spec, "Structure Member Layout": the storage-buffer example.
const SPEC_STORAGE = `
struct A {                                     //             align(8)  size(24)
    u: f32,                                    // offset(0)   align(4)  size(4)
    v: f32,                                    // offset(4)   align(4)  size(4)
    w: vec2<f32>,                              // offset(8)   align(8)  size(8)
    x: f32                                     // offset(16)  align(4)  size(4)
}
struct B {                                     //             align(16) size(160)
    a: vec2<f32>,                              // offset(0)   align(8)  size(8)
    b: vec3<f32>,                              // offset(16)  align(16) size(12)
    c: f32,                                    // offset(28)  align(4)  size(4)
    d: f32,                                    // offset(32)  align(4)  size(4)
    e: A,                                      // offset(40)  align(8)  size(24)
    f: vec3<f32>,                              // offset(64)  align(16) size(12)
    g: array<A, 3>,    // element stride 24       offset(80)  align(8)  size(72)
    h: i32                                     // offset(152) align(4)  size(4)
}
@group(0) @binding(0) var<storage,read_write> storage_buffer: B;`;

// The same example for a uniform buffer: @align(16) and @size(16) meet the constraints.
const SPEC_UNIFORM = `
struct A {                                     //             align(8)  size(32)
    u: f32,                                    // offset(0)   align(4)  size(4)
    v: f32,                                    // offset(4)   align(4)  size(4)
    w: vec2<f32>,                              // offset(8)   align(8)  size(8)
    @size(16) x: f32                           // offset(16)  align(4)  size(16)
}
struct B {                                     //             align(16) size(208)
    a: vec2<f32>,                              // offset(0)   align(8)  size(8)
    b: vec3<f32>,                              // offset(16)  align(16) size(12)
    c: f32,                                    // offset(28)  align(4)  size(4)
    d: f32,                                    // offset(32)  align(4)  size(4)
    @align(16) e: A,                           // offset(48)  align(16) size(32)
    f: vec3<f32>,                              // offset(80)  align(16) size(12)
    g: array<A, 3>,    // element stride 32       offset(96)  align(8)  size(96)
    h: i32                                     // offset(192) align(4)  size(4)
}
@group(0) @binding(1) var<uniform> uniform_buffer: B;`;

describe('WGSL layout rules', () => {
  it('lays out the specification’s storage example (vec3 + f32 packing, nested struct, array of structs)', () => {
    const a = deriveStruct(SPEC_STORAGE, 'A');
    expect([a.size, a.align]).toEqual([24, 8]);
    expect(offsets(a)).toEqual({ u: 0, v: 4, w: 8, x: 16 });
    const b = deriveStruct(SPEC_STORAGE, 'B');
    expect([b.size, b.align]).toEqual([160, 16]);
    expect(offsets(b)).toEqual({ a: 0, b: 16, c: 28, d: 32, e: 40, f: 64, g: 80, h: 152 });
    const g = b.members.g!;
    expect(g.type.kind === 'array' && [g.type.stride, g.type.count, g.size]).toEqual([24, 3, 72]);
  });

  it('lays out the specification’s uniform example (@align, @size) and finds it valid as a uniform', () => {
    const b = deriveStruct(SPEC_UNIFORM, 'B');
    expect([b.size, b.align]).toEqual([208, 16]);
    expect(offsets(b)).toEqual({ a: 0, b: 16, c: 28, d: 32, e: 48, f: 80, g: 96, h: 192 });
    expect(b.members.e!.size).toBe(32);
    const g = b.members.g!;
    expect(g.type.kind === 'array' && g.type.stride).toBe(32);
    expect(uniformViolations(b)).toEqual([]);
  });

  it('reports the storage example’s uniform violations by member', () => {
    const problems = uniformViolations(deriveStruct(SPEC_STORAGE, 'B'));
    expect(problems).toContain('B.e: offset 40 is not a multiple of 16 in a uniform');
    expect(problems).toContain('B.g: array stride 24 is not a multiple of 16 in a uniform');
    expect(problems.some((p) => p.startsWith('B.e: the next member must start 32 bytes'))).toBe(
      true,
    );
  });

  it('gives arrays of vec3 a stride of 16 and sizes matrices by padded columns', () => {
    const s = deriveStruct(
      `const N: u32 = 2u;
       struct S { p: array<vec3f, 4>, q: f32, m: mat3x3f, n: mat4x2<f32>, r: array<vec2u, N * 3u>, t: vec3h, w: f16 }`,
      'S',
    );
    const p = s.members.p!;
    expect(p.type.kind === 'array' && [p.type.stride, p.size]).toEqual([16, 64]);
    expect(offsets(s)).toEqual({ p: 0, q: 64, m: 80, n: 128, r: 160, t: 208, w: 214 });
    const m = s.members.m!;
    expect(m.type.kind === 'matrix' && [m.type.columnStride, m.size, m.type.align]).toEqual([
      16, 48, 16,
    ]);
    const n = s.members.n!;
    expect(n.type.kind === 'matrix' && [n.type.columnStride, n.size, n.type.align]).toEqual([
      8, 32, 8,
    ]);
    expect(s.members.r!.size).toBe(48);
    expect([s.size, s.align]).toEqual([224, 16]);
  });

  it('aligns a nested struct to its largest member and rounds its size', () => {
    const source = `struct Inner { a: f32, b: vec3f }  // align 16, size 32
      struct Outer { x: u32, inner: Inner, y: u32, tail: array<Inner> }`;
    expect(offsets(deriveStruct(source, 'Inner'))).toEqual({ a: 0, b: 16 });
    const outer = deriveStruct(source, 'Outer');
    expect(offsets(outer)).toEqual({ x: 0, inner: 16, y: 48, tail: 64 });
    expect(outer.size).toBe(64);
    expect(uniformViolations(outer)).toContain(
      'Outer.tail: a runtime-sized array cannot be uniform',
    );
  });

  it('evaluates array sizes given by constants and refuses what it cannot read', () => {
    const consts = parseDeclarations(
      'const A = 4; const B: u32 = (A + 2u) * 3u; const C = 0x10u;',
    ).consts;
    expect(evaluateInteger('B / 4u - 1', consts)).toBe(3);
    expect(evaluateInteger('C % 5', consts)).toBe(1);
    expect(() => evaluateInteger('D', consts)).toThrow(/unknown constant D/);
    expect(() => deriveStruct('struct S { b: bool }', 'S')).toThrow(/b: no layout|bool/);
    expect(() => deriveStruct('struct S { a: array<f32>, b: f32 }', 'S')).toThrow(/last member/);
    expect(() => deriveStruct('struct S { a: f32 }', 'T')).toThrow(/no struct T/);
  });
});

describe('packStruct', () => {
  const layout = deriveStruct(
    `struct P { sigmaA: f32, origin: vec3f, count: u32, offset: i32, pad0: f32, list: array<vec2f, 3> }`,
    'P',
  );

  it('writes each member at its derived offset and reads it back', () => {
    const words = packStruct(layout, {
      sigmaA: 1.5,
      origin: [1, 2, 3],
      count: 7,
      offset: -2,
      list: [[4, 5]],
    });
    expect(words.byteLength).toBe(layout.size);
    const f32 = new Float32Array(words.buffer);
    expect(f32[0]).toBe(1.5);
    expect([...f32.subarray(4, 7)]).toEqual([1, 2, 3]);
    expect(words[7]).toBe(7);
    expect(new Int32Array(words.buffer)[8]).toBe(-2);
    expect([...f32.subarray(10, 14)]).toEqual([4, 5, 0, 0]);
    const back = readStruct(layout, wordsOf(words.buffer));
    expect(back).toMatchObject({ sigmaA: 1.5, origin: [1, 2, 3], count: 7, offset: -2, pad0: 0 });
  });

  it('names a missing member, an unknown member, a wrong vector length and an overlong array', () => {
    const base = { sigmaA: 1, origin: [0, 0, 0], count: 1, offset: 0, list: [] };
    const missing: Partial<typeof base> = { ...base };
    delete missing.count;
    expect(() => packStruct(layout, missing as never)).toThrow('P: member "count" of P is missing');
    expect(() => packStruct(layout, { ...base, sigmaS: 2 } as never)).toThrow(
      'P: P has no member "sigmaS"',
    );
    expect(() => packStruct(layout, { ...base, origin: [1, 2] })).toThrow(
      'P.origin: expected 3 numbers',
    );
    expect(() =>
      packStruct(layout, {
        ...base,
        list: [
          [1, 2],
          [3, 4],
          [5, 6],
          [7, 8],
        ],
      }),
    ).toThrow('P.list: 4 elements, the array holds 3');
    const words = wordsOf(new ArrayBuffer(layout.size + 16));
    expect(() => writeStruct(layout, base, words, 32)).toThrow(RangeError);
  });
});

describe('generated layout table', () => {
  it('types a generated layout’s members: an unknown or a missing one does not compile', () => {
    const layout = vreRayKernel.VreRayParams;
    const values = {
      sigma: 1,
      albedo: 0.5,
      emission: 0,
      inscatter: 0,
      background: 0,
      length: 1,
      steps: 4,
      viewMin: 0,
      viewMax: 1,
      width: 2,
      height: 2,
    };
    expect(packStruct(layout, values).byteLength).toBe(48);
    // @ts-expect-error: VreRayParams has no member sigmaT
    expect(() => packStruct(layout, { ...values, sigmaT: 1 })).toThrow('has no member "sigmaT"');
    // @ts-expect-error: steps and the rest are missing
    expect(() => packStruct(layout, { sigma: 1 })).toThrow('member "albedo" of VreRayParams');
    // @ts-expect-error: a vec4f member takes numbers, not a number
    expect(() => packStruct(rayleighSkyKernel.SkyParams, { probeMu: 1 })).toThrow();
  });

  it('equals the layouts derived now from every linked kernel (run `npx tsx src/gpu/layoutGenerate.ts` if not)', async () => {
    expect(await deriveKernelLayouts(SHADER_LIBRARY)).toEqual(KERNEL_LAYOUTS);
  });
});
