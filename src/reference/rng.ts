// Float64/uint32 twin of shaders/rng.wesl: the same PCG stream, bit for bit.
// Written from O'Neill 2014 and Jarzynski & Olano 2020 (pcg_hash), with u32
// arithmetic emulated by Math.imul and `>>> 0`.

const MULTIPLIER = 747796405;
const INCREMENT = 2891336453;
const OUTPUT_MULTIPLIER = 277803737;

/** state·a + c mod 2^32. */
export function pcgAdvance(state: number): number {
  return (Math.imul(state >>> 0, MULTIPLIER) + INCREMENT) >>> 0;
}

/** RXS-M-XS: random xorshift, multiply, xorshift. */
export function pcgOutput(state: number): number {
  const s = state >>> 0;
  const rotation = (s >>> 28) + 4;
  const word = Math.imul(((s >>> rotation) ^ s) >>> 0, OUTPUT_MULTIPLIER) >>> 0;
  return ((word >>> 22) ^ word) >>> 0;
}

export function pcgHash(value: number): number {
  return pcgOutput(pcgAdvance(value));
}

export function rngSeed(pixelIndex: number, frameIndex: number): number {
  return pcgHash((pixelIndex >>> 0) ^ pcgHash(frameIndex));
}

/** Top 24 bits as a multiple of 2^-24: exactly representable in f32, never 1. */
export function u32ToUnitFloat(bits: number): number {
  return (bits >>> 8) / 16777216;
}

/** Mutable stream state; the WGSL version takes `ptr<function, u32>`. */
export interface RngState {
  value: number;
}

export function rngNextFloat(state: RngState): number {
  state.value = pcgAdvance(state.value);
  return u32ToUnitFloat(pcgOutput(state.value));
}
