// Float32 helpers for comparing GPU results with float64 twins.

const scratch = new DataView(new ArrayBuffer(4));

export function f32ToBits(value: number): number {
  scratch.setFloat32(0, value);
  return scratch.getUint32(0);
}

export function bitsToF32(bits: number): number {
  scratch.setUint32(0, bits >>> 0);
  return scratch.getFloat32(0);
}

/** Position of a float32 on the integer line, so that adjacent floats differ by 1. */
function ordinal(value: number): number {
  const bits = f32ToBits(value);
  return bits & 0x80000000 ? -(bits & 0x7fffffff) : bits;
}

/** Distance in units in the last place between two float32 values (both rounded to f32 first). */
export function ulpDistance(a: number, b: number): number {
  return Math.abs(ordinal(Math.fround(a)) - ordinal(Math.fround(b)));
}

/** The float32 just below 1: 1 − 2⁻²⁴. */
export const ONE_MINUS_EPSILON_F32 = 1 - 2 ** -24;
/** Smallest positive subnormal and normal float32, and the largest finite one. */
export const F32_MIN_SUBNORMAL = 2 ** -149;
export const F32_MIN_NORMAL = 2 ** -126;
export const F32_MAX = (2 - 2 ** -23) * 2 ** 127;
