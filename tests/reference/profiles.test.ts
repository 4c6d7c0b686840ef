// The beer-law widget's profiles: τ is the integral of the pointwise extinction,
// the layers have mean 1, and all three profiles share the mean coefficient.
import { describe, expect, it } from 'vitest';
import {
  extinctionAt,
  LAYER_THICKNESS,
  LAYER_WEIGHTS,
  opticalDepth,
  type ProfileName,
} from '../../src/widgets/beer-law/profiles.ts';

function midpoint(f: (s: number) => number, a: number, b: number, n = 100_000): number {
  const h = (b - a) / n;
  let sum = 0;
  for (let i = 0; i < n; i++) sum += f(a + (i + 0.5) * h);
  return sum * h;
}

describe('beer-law profiles', () => {
  it('the layer weights average exactly 1 over 10 m', () => {
    expect(LAYER_WEIGHTS.reduce((a, b) => a + b, 0) / LAYER_WEIGHTS.length).toBeCloseTo(1, 14);
    expect(LAYER_WEIGHTS.length * LAYER_THICKNESS).toBe(10);
  });

  for (const profile of ['homogeneous', 'smooth', 'layered'] as ProfileName[]) {
    it(`${profile}: τ(s0, s1) equals the integral of σt(s)`, () => {
      for (const [s0, s1] of [
        [0, 2],
        [0.3, 4.7],
        [1.1, 9.9],
      ] as const) {
        const integral = midpoint((s) => extinctionAt(profile, 1.7, s), s0, s1);
        expect(opticalDepth(profile, 1.7, s0, s1)).toBeCloseTo(integral, 3);
      }
    });
  }

  it('over the whole 10 m medium, the layered profile has the mean extinction', () => {
    expect(opticalDepth('layered', 2, 0, 10)).toBeCloseTo(20, 12);
  });
});
