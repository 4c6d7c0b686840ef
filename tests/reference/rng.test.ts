// The PCG stream's statistics, on the float64 twin (the WGSL stream is
// bit-identical, tests/shaders/rng.test.ts). Fixed seeds; significance 0.01.
import { describe, expect, it } from 'vitest';
import { pcgHash, rngNextFloat, rngSeed, u32ToUnitFloat } from '../../src/reference/rng.ts';

/** Upper 1% point of the chi-square distribution with 63 degrees of freedom. */
const CHI_SQUARE_63_AT_001 = 92.01;

describe('rng (PCG, Jarzynski & Olano 2020)', () => {
  it('uniform numbers pass a chi-square test (64 bins, 100 000 draws, α = 0.01)', () => {
    const bins = new Array<number>(64).fill(0);
    const state = { value: rngSeed(12345, 0) };
    const n = 100_000;
    for (let i = 0; i < n; i++) {
      const bin = Math.floor(rngNextFloat(state) * 64);
      bins[bin] = (bins[bin] ?? 0) + 1;
    }
    const expected = n / 64;
    const chiSquare = bins.reduce((sum, count) => sum + (count - expected) ** 2 / expected, 0);
    expect(chiSquare).toBeLessThan(CHI_SQUARE_63_AT_001);
  });

  it('consecutive numbers are uncorrelated (|r| < 3/√n)', () => {
    const state = { value: rngSeed(7, 3) };
    const n = 100_000;
    let previous = rngNextFloat(state);
    let sxy = 0;
    let sx = 0;
    let sxx = 0;
    for (let i = 0; i < n; i++) {
      const next = rngNextFloat(state);
      sxy += previous * next;
      sx += previous;
      sxx += previous * previous;
      previous = next;
    }
    const mean = sx / n;
    const correlation = (sxy / n - mean * mean) / (sxx / n - mean * mean);
    expect(Math.abs(correlation)).toBeLessThan(3 / Math.sqrt(n));
  });

  it('first numbers of neighbouring pixels are uniform too (per-pixel seeding)', () => {
    const bins = new Array<number>(64).fill(0);
    const n = 64_000;
    for (let pixel = 0; pixel < n; pixel++) {
      const bin = Math.floor(rngNextFloat({ value: rngSeed(pixel, 0) }) * 64);
      bins[bin] = (bins[bin] ?? 0) + 1;
    }
    const expected = n / 64;
    const chiSquare = bins.reduce((sum, count) => sum + (count - expected) ** 2 / expected, 0);
    expect(chiSquare).toBeLessThan(CHI_SQUARE_63_AT_001);
  });

  it('pcgHash avalanches: flipping one input bit flips about half the output bits', () => {
    let flipped = 0;
    let trials = 0;
    for (let value = 0; value < 2000; value++) {
      for (let bit = 0; bit < 32; bit++) {
        const difference = (pcgHash(value) ^ pcgHash((value ^ (1 << bit)) >>> 0)) >>> 0;
        flipped += difference.toString(2).split('1').length - 1;
        trials += 32;
      }
    }
    expect(flipped / trials).toBeGreaterThan(0.45);
    expect(flipped / trials).toBeLessThan(0.55);
  });

  it('u32ToUnitFloat stays in [0, 1 − 2⁻²⁴] so −ln(1 − ξ) is finite (hard case 16)', () => {
    expect(u32ToUnitFloat(0xffffffff)).toBe(1 - 2 ** -24);
    expect(Math.fround(u32ToUnitFloat(0xffffffff))).toBeLessThan(1);
    expect(-Math.log(1 - u32ToUnitFloat(0xffffffff))).toBeCloseTo(16.6355, 4);
    expect(u32ToUnitFloat(0)).toBe(0);
  });

  it('different frames give different streams for the same pixel', () => {
    const a = rngNextFloat({ value: rngSeed(100, 0) });
    const b = rngNextFloat({ value: rngSeed(100, 1) });
    expect(a).not.toBe(b);
  });
});
