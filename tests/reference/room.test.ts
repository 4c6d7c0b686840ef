// The float64 room of chapter 12 (src/reference/room.ts) against closed forms: the emitter's
// irradiance by next-event estimation (uniform points × the geometry term × area) against the
// form factor of a differential area to a parallel rectangle (Howell's catalogue, C-11), the
// exit face of roomWallHit on its plane and inside the room, and the irradiance pass of the
// translucentRoom twin with black walls against a quadrature of the same integral with Fresnel.
import { describe, expect, it } from 'vitest';
import {
  roomWallHit,
  roomWallNormal,
  squareLightGeometry,
  squareLightPoint,
} from '../../src/reference/room.ts';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';
import { fresnelDielectric } from '../../src/reference/fresnel.ts';
import { findMaterial } from '../../src/subsurface/materials.ts';
import {
  roomIrradianceCpu,
  roomScene,
  sphereCentre,
  SAMPLE_FLOATS,
} from '../../src/subsurface/translucentRoom.ts';

/** Form factor dA → a×b rectangle parallel to it at height d, one corner above dA (Howell C-11). */
function cornerFormFactor(a: number, b: number, d: number): number {
  const x = a / d;
  const y = b / d;
  const sx = Math.sqrt(1 + x * x);
  const sy = Math.sqrt(1 + y * y);
  return ((x / sx) * Math.atan(y / sx) + (y / sy) * Math.atan(x / sy)) / (2 * Math.PI);
}

describe('the ceiling emitter by next-event estimation', () => {
  it.each([
    ['below the centre', [0, -1, 0]],
    ['off-centre on the floor', [0.8, -1, -0.3]],
  ] as const)('%s: E/L_e = π F(dA → emitter) within 4.5 standard errors', (_name, p) => {
    const h = 1;
    const a = 0.3;
    const n = 40000;
    const rng = { value: rngSeed(7, 11) };
    let sum = 0;
    let squares = 0;
    for (let k = 0; k < n; k++) {
      const y = squareLightPoint(h, a, [rngNextFloat(rng), rngNextFloat(rng)]);
      const value = squareLightGeometry(p, [0, 1, 0], y) * 4 * a * a;
      sum += value;
      squares += value * value;
    }
    const mean = sum / n;
    const se = Math.sqrt((squares / n - mean * mean) / (n - 1));
    // The emitter split at the point's foot into four corner rectangles.
    const d = h - p[1];
    const [x0, x1] = [a + p[0], a - p[0]];
    const [z0, z1] = [a + p[2], a - p[2]];
    const exact =
      Math.PI *
      (cornerFormFactor(x0, z0, d) +
        cornerFormFactor(x0, z1, d) +
        cornerFormFactor(x1, z0, d) +
        cornerFormFactor(x1, z1, d));
    expect(Math.abs(mean - exact)).toBeLessThan(4.5 * se);
    expect(se / exact).toBeLessThan(0.01);
  });
});

describe('roomWallHit', () => {
  it('the exit point lies on its face, inside the closed room, for random rays', () => {
    const rng = { value: rngSeed(1, 2) };
    const h = 2.5;
    for (let k = 0; k < 2000; k++) {
      const o = [0, 1, 2].map(() => h * (2 * rngNextFloat(rng) - 1));
      const z = 2 * rngNextFloat(rng) - 1;
      const phi = 2 * Math.PI * rngNextFloat(rng);
      const r = Math.sqrt(1 - z * z);
      const d = [r * Math.cos(phi), r * Math.sin(phi), z];
      const [t, face] = roomWallHit(h, o, d);
      const p = o.map((v, i) => v + t * d[i]!);
      const n = roomWallNormal(face);
      // The face's plane is n·p = −h (inward normals), and every coordinate is within [−h, h].
      expect(n[0] * p[0]! + n[1] * p[1]! + n[2] * p[2]!).toBeCloseTo(-h, 9);
      for (const v of p) expect(Math.abs(v)).toBeLessThanOrEqual(h * (1 + 1e-12));
      // The ray leaves through the face: it travels against the inward normal.
      expect(n[0] * d[0]! + n[1] * d[1]! + n[2] * d[2]!).toBeLessThan(0);
    }
  });
});

describe('the irradiance pass (twin)', () => {
  it('with black walls E is the emitter’s direct light through Fresnel, as a quadrature gives', () => {
    const scene = roomScene(findMaterial('skin1')!, 2, 2, 8);
    const count = 16;
    const rays = 40000;
    const samples = roomIrradianceCpu(
      scene,
      count,
      rays,
      3,
      new Float32Array(SAMPLE_FLOATS * count),
    );
    const c = sphereCentre(scene);
    const a = scene.lightHalf;
    const m = 200;
    for (const i of [0, 5, 9]) {
      const o = SAMPLE_FLOATS * i;
      const p = [c[0] + samples[o]!, c[1] + samples[o + 1]!, c[2] + samples[o + 2]!];
      const normal = [samples[o]! / 2, samples[o + 1]! / 2, samples[o + 2]! / 2];
      // Midpoint rule over the emitter of ∫ L_e (1 − F(cos θ)) cos θ cos θ_l / d² dA.
      let exact = 0;
      for (let u = 0; u < m; u++)
        for (let v = 0; v < m; v++) {
          const y = squareLightPoint(scene.halfSize, a, [(u + 0.5) / m, (v + 0.5) / m]);
          const g = squareLightGeometry(p, normal, y);
          if (g <= 0) continue;
          const w = y.map((x, k) => x - p[k]!);
          const cos =
            (w[0]! * normal[0]! + w[1]! * normal[1]! + w[2]! * normal[2]!) / Math.hypot(...w);
          exact += g * (1 - fresnelDielectric(cos, scene.eta));
        }
      exact *= (scene.emission * 4 * a * a) / (m * m);
      const e = samples[o + 4]!;
      // Black walls: nothing indirect, so E equals its direct part, in every channel.
      expect(samples[o + 8]).toBeCloseTo(e, 6);
      expect(samples[o + 6]).toBeCloseTo(e, 6);
      if (exact === 0) expect(e).toBe(0);
      else expect(Math.abs(e / exact - 1), `sample ${i}: ${e} vs ${exact}`).toBeLessThan(0.03);
    }
  });
});
