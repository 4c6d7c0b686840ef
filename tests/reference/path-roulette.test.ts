// The end of a path tracer's segment (integrator.wesl tracedPathRoulette and its twin):
// Russian roulette from the ROULETTE_START_ORDER-th scattering on, that draws a number only
// when the survival q = min(1, max channel of w) is below 1, survivors divided by q, and the PATH_MAX_VERTICES cap after the segment
// that reaches it (counted), so that a capped path gets the same radiance and random
// numbers as when the cap stopped it before its next segment.
import { describe, expect, it } from 'vitest';
import {
  PATH_MAX_VERTICES,
  ROULETTE_START_ORDER,
  tracedPathRoulette,
  tracedPathStart,
  type SceneData,
} from '../../src/reference/integrator.ts';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';

const scene = (): SceneData => ({ stats: { capped: 0, lookups: 0 } }) as unknown as SceneData;

describe('tracedPathRoulette', () => {
  it('draws nothing for a throughput of 1 or more, and the path goes on', () => {
    const s = scene();
    const path = tracedPathStart([0, 0, 0], [0, 0, 1]);
    path.weight = [1.5, 1, 0.2];
    const state = { value: rngSeed(3, 4) };
    const before = state.value;
    expect(tracedPathRoulette(s, path, state)).toBe(false);
    expect(state.value).toBe(before);
    expect(path.weight).toEqual([1.5, 1, 0.2]);
  });

  it('with q < 1 draws one number: survivors are divided by q, the others end', () => {
    let survived = 0;
    for (let i = 0; i < 400; i++) {
      const path = tracedPathStart([0, 0, 0], [0, 0, 1]);
      path.order = ROULETTE_START_ORDER;
      path.weight = [0.25, 0.1, 0.05];
      const state = { value: rngSeed(i, 9) };
      const copy = { value: state.value };
      const u = rngNextFloat(copy);
      const ended = tracedPathRoulette(scene(), path, state);
      expect(state.value).toBe(copy.value);
      expect(ended).toBe(!(u < 0.25));
      if (!ended) {
        survived += 1;
        expect(path.weight[0]).toBeCloseTo(1, 12);
        expect(path.weight[1]).toBeCloseTo(0.4, 12);
      }
    }
    // q = 0.25: about a quarter survive (binomial, 400 trials: ±4.3 standard deviations).
    expect(Math.abs(survived - 100)).toBeLessThan(37);
  });

  it('plays no roulette before the ROULETTE_START_ORDER-th scattering: the albedo-weighted path goes on whole', () => {
    for (let order = 0; order < ROULETTE_START_ORDER; order++) {
      const path = tracedPathStart([0, 0, 0], [0, 0, 1]);
      path.order = order;
      path.weight = [0.25, 0.1, 0.05];
      const state = { value: rngSeed(order, 5) };
      const before = state.value;
      expect(tracedPathRoulette(scene(), path, state)).toBe(false);
      expect(state.value).toBe(before);
      expect(path.weight).toEqual([0.25, 0.1, 0.05]);
    }
  });

  it(`ends a surviving path after its ${PATH_MAX_VERTICES}th segment and counts it`, () => {
    const s = scene();
    const path = tracedPathStart([0, 0, 0], [0, 0, 1]);
    path.segments = PATH_MAX_VERTICES - 1;
    expect(tracedPathRoulette(s, path, { value: 1 })).toBe(false);
    path.segments = PATH_MAX_VERTICES;
    expect(tracedPathRoulette(s, path, { value: 1 })).toBe(true);
    expect(s.stats.capped).toBe(1);
  });
});
