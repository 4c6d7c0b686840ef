// Host-shareable WGSL layouts and the packers that write them. The layouts are not written
// by hand: src/gpu/layoutDerive.ts computes them from the WGSL struct declarations of the
// linked kernels, and src/gpu/layouts.generated.ts holds the result (a test regenerates it
// and fails when a kernel's struct changed). Only this small module and that table ship to
// pages; the WGSL parser stays at test time.

export type ScalarName = 'f32' | 'u32' | 'i32' | 'f16';

export interface ScalarLayout {
  readonly kind: 'scalar';
  readonly scalar: ScalarName;
  readonly size: number;
  readonly align: number;
}

export interface VectorLayout {
  readonly kind: 'vector';
  readonly scalar: ScalarName;
  readonly length: number;
  readonly size: number;
  readonly align: number;
}

/** matCxR: `columns` column vectors of `rows` components, `columnStride` bytes apart. */
export interface MatrixLayout {
  readonly kind: 'matrix';
  readonly scalar: ScalarName;
  readonly columns: number;
  readonly rows: number;
  readonly columnStride: number;
  readonly size: number;
  readonly align: number;
}

/** `count` 0 is a runtime-sized array (its size is one stride per element written). */
export interface ArrayLayout {
  readonly kind: 'array';
  readonly element: TypeLayout;
  readonly count: number;
  readonly stride: number;
  readonly size: number;
  readonly align: number;
}

export interface MemberLayout {
  readonly offset: number;
  readonly size: number;
  readonly type: TypeLayout;
}

export interface StructLayout {
  readonly kind: 'struct';
  readonly name: string;
  readonly size: number;
  readonly align: number;
  /** In declaration order. */
  readonly members: Readonly<Record<string, MemberLayout>>;
}

export type TypeLayout = ScalarLayout | VectorLayout | MatrixLayout | ArrayLayout | StructLayout;

/**
 * Members named pad, pad0, _pad3… exist only to place the next member; a packer may leave
 * them out (they are written as zero).
 */
export const isPadding = (name: string): boolean => /^_?pad\d*$/.test(name);
type PaddingName = `pad${string}` | `_pad${string}`;

/**
 * What a packer accepts for a value of layout T: vectors and matrices as flat arrays or
 * typed arrays (a matrix column by column).
 */
export type PackValue<T> = T extends { readonly kind: 'scalar' }
  ? number
  : T extends { readonly kind: 'vector' | 'matrix' }
    ? ArrayLike<number>
    : T extends { readonly kind: 'array'; readonly element: infer E }
      ? readonly PackValue<E>[]
      : T extends { readonly kind: 'struct'; readonly members: infer M }
        ? StructValues<M>
        : never;

type StructValues<M> = {
  readonly [K in keyof M as K extends PaddingName ? never : K]: M[K] extends { type: infer T }
    ? PackValue<T>
    : never;
} & {
  readonly [K in keyof M as K extends PaddingName ? K : never]?: M[K] extends { type: infer T }
    ? PackValue<T>
    : never;
};

/** What an unpacker returns for a value of layout T (a vec3 as a three-number tuple). */
export type UnpackedValue<T> = T extends { readonly kind: 'scalar' }
  ? number
  : T extends { readonly kind: 'vector'; readonly length: 2 }
    ? [number, number]
    : T extends { readonly kind: 'vector'; readonly length: 3 }
      ? [number, number, number]
      : T extends { readonly kind: 'vector' | 'matrix' }
        ? number[]
        : T extends { readonly kind: 'array'; readonly element: infer E }
          ? UnpackedValue<E>[]
          : T extends { readonly kind: 'struct'; readonly members: infer M }
            ? { [K in keyof M]: M[K] extends { type: infer T2 } ? UnpackedValue<T2> : never }
            : never;

/** f32, u32 and i32 views of one buffer, the targets of a packer. */
export interface Words<B extends ArrayBufferLike = ArrayBufferLike> {
  readonly u32: Uint32Array<B>;
  readonly f32: Float32Array<B>;
  readonly i32: Int32Array<B>;
}

export function wordsOf<B extends ArrayBufferLike>(buffer: B): Words<B> {
  return {
    u32: new Uint32Array(buffer),
    f32: new Float32Array(buffer),
    i32: new Int32Array(buffer),
  };
}

/**
 * Packs `values` into a new buffer of `layout.size` bytes and returns its 32-bit words.
 * Every member must be given (padding members may be left out); an unknown member, a
 * vector of the wrong length or an array longer than declared throws an error naming the
 * struct and member. Arrays may be shorter than declared (the rest stays zero).
 */
export function packStruct<L extends StructLayout>(
  layout: L,
  values: PackValue<L>,
): Uint32Array<ArrayBuffer> {
  const words = wordsOf(new ArrayBuffer(layout.size));
  writeValue(layout, values, words, 0, layout.name);
  return words.u32;
}

/** Writes `values` of `layout` at `byteOffset` into existing views (e.g. one record of many). */
export function writeStruct<L extends StructLayout>(
  layout: L,
  values: PackValue<L>,
  words: Words,
  byteOffset = 0,
): void {
  if (byteOffset % 4 !== 0 || byteOffset + layout.size > words.u32.byteLength) {
    throw new RangeError(
      `${layout.name} (${layout.size} bytes) does not fit at byte ${byteOffset} of ${words.u32.byteLength}`,
    );
  }
  writeValue(layout, values, words, byteOffset, layout.name);
}

function writeValue(
  type: TypeLayout,
  value: unknown,
  words: Words,
  offset: number,
  path: string,
): void {
  switch (type.kind) {
    case 'scalar':
      if (typeof value !== 'number') throw new TypeError(`${path}: expected a number`);
      writeScalar(type.scalar, value, words, offset, path);
      return;
    case 'vector':
    case 'matrix': {
      const length = type.kind === 'vector' ? type.length : type.columns * type.rows;
      if (!isNumberArray(value) || value.length !== length) {
        throw new TypeError(`${path}: expected ${length} numbers`);
      }
      const rows = type.kind === 'vector' ? length : type.rows;
      const stride = type.kind === 'vector' ? 0 : type.columnStride;
      for (let i = 0; i < length; i++) {
        const at = offset + Math.floor(i / rows) * stride + (i % rows) * 4;
        writeScalar(type.scalar, value[i]!, words, at, `${path}[${i}]`);
      }
      return;
    }
    case 'array': {
      if (!Array.isArray(value)) throw new TypeError(`${path}: expected an array`);
      if (type.count > 0 && value.length > type.count) {
        throw new RangeError(`${path}: ${value.length} elements, the array holds ${type.count}`);
      }
      value.forEach((element: unknown, i) =>
        writeValue(type.element, element, words, offset + i * type.stride, `${path}[${i}]`),
      );
      return;
    }
    case 'struct': {
      if (typeof value !== 'object' || value === null || Array.isArray(value)) {
        throw new TypeError(`${path}: expected the members of ${type.name}`);
      }
      const given = value as Record<string, unknown>;
      for (const name of Object.keys(given)) {
        if (!(name in type.members))
          throw new Error(`${path}: ${type.name} has no member "${name}"`);
      }
      for (const [name, member] of Object.entries(type.members)) {
        const v = given[name];
        if (v === undefined) {
          if (isPadding(name)) continue;
          throw new Error(`${path}: member "${name}" of ${type.name} is missing`);
        }
        writeValue(member.type, v, words, offset + member.offset, `${path}.${name}`);
      }
      return;
    }
  }
}

function writeScalar(
  scalar: ScalarName,
  value: number,
  words: Words,
  offset: number,
  path: string,
) {
  const index = offset / 4;
  if (scalar === 'f32') words.f32[index] = value;
  else if (scalar === 'u32') words.u32[index] = value;
  else if (scalar === 'i32') words.i32[index] = value;
  else throw new TypeError(`${path}: f16 members are not packed by this module`);
}

const isNumberArray = (value: unknown): value is ArrayLike<number> =>
  (Array.isArray(value) || ArrayBuffer.isView(value)) &&
  Array.prototype.every.call(value, (x: unknown) => typeof x === 'number');

/**
 * Reads a value of `layout` at `byteOffset` (the inverse of writeStruct). A runtime-sized
 * array reads as many elements as the buffer holds.
 */
export function readStruct<L extends StructLayout>(
  layout: L,
  words: Words,
  byteOffset = 0,
): UnpackedValue<L> {
  return readValue(layout, words, byteOffset) as UnpackedValue<L>;
}

function readValue(type: TypeLayout, words: Words, offset: number): unknown {
  switch (type.kind) {
    case 'scalar':
      return readScalar(type.scalar, words, offset);
    case 'vector':
      return Array.from({ length: type.length }, (_, i) =>
        readScalar(type.scalar, words, offset + 4 * i),
      );
    case 'matrix':
      return Array.from({ length: type.columns * type.rows }, (_, i) =>
        readScalar(
          type.scalar,
          words,
          offset + Math.floor(i / type.rows) * type.columnStride + (i % type.rows) * 4,
        ),
      );
    case 'array': {
      const count =
        type.count > 0
          ? type.count
          : Math.floor(
              (words.u32.byteLength - offset + type.stride - type.element.size) / type.stride,
            );
      return Array.from({ length: count }, (_, i) =>
        readValue(type.element, words, offset + i * type.stride),
      );
    }
    case 'struct':
      return Object.fromEntries(
        Object.entries(type.members).map(([name, m]) => [
          name,
          readValue(m.type, words, offset + m.offset),
        ]),
      );
  }
}

function readScalar(scalar: ScalarName, words: Words, offset: number): number {
  const index = offset / 4;
  if (scalar === 'f32') return words.f32[index]!;
  if (scalar === 'u32') return words.u32[index]!;
  if (scalar === 'i32') return words.i32[index]!;
  throw new TypeError('f16 members are not read by this module');
}

/**
 * Groups a list of scalars into vec4s (the last one zero-filled), for an
 * array<vec4f, N> member that holds up to 4N scalars (uniform arrays need a 16-byte stride).
 */
export function vec4s(values: readonly number[]): number[][] {
  return Array.from({ length: Math.ceil(values.length / 4) }, (_, i) => {
    const chunk = values.slice(4 * i, 4 * i + 4);
    return [...chunk, ...new Array<number>(4 - chunk.length).fill(0)];
  });
}

/** A member of `struct`: its offset, its type and (only when @size sets it) its size. */
type MemberSpec = readonly [offset: number, type: TypeLayout, size?: number];

/**
 * Builds a struct layout from compact member specs (the generated table's form: shared
 * type constants referenced by name keep it small on the page).
 */
export function struct<const M extends Readonly<Record<string, MemberSpec>>>(
  name: string,
  size: number,
  align: number,
  specs: M,
): {
  readonly kind: 'struct';
  readonly name: string;
  readonly size: number;
  readonly align: number;
  readonly members: {
    readonly [K in keyof M]: {
      readonly offset: number;
      readonly size: number;
      readonly type: M[K][1];
    };
  };
} {
  const members: Record<string, MemberLayout> = {};
  for (const [member, [offset, type, memberSize]] of Object.entries(specs)) {
    members[member] = { offset, size: memberSize ?? type.size, type };
  }
  return { kind: 'struct', name, size, align, members: members as never };
}

/** An array layout of `count` elements `stride` bytes apart (count 0: runtime-sized). */
export function array<const E extends TypeLayout>(
  element: E,
  count: number,
  stride: number,
): {
  readonly kind: 'array';
  readonly element: E;
  readonly count: number;
  readonly stride: number;
  readonly size: number;
  readonly align: number;
} {
  return { kind: 'array', element, count, stride, size: count * stride, align: element.align };
}
