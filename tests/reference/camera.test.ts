// Properties of the float64 camera and geometry twins that hold for all inputs:
// camera frames are orthonormal and right-handed; a perspective ray through a pixel
// passes through that pixel's point on the image plane; an orthographic footprint is
// the exact rectangle asked for; segments returned by the intersections lie on the
// shapes' surfaces.
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  cameraFrame,
  cameraOrthographic,
  cameraPerspective,
  cameraRay,
} from '../../src/reference/camera.ts';
import { rayBoxSegment, raySphereSegment, segmentIsEmpty } from '../../src/reference/geometry.ts';
import type { Vec3 } from '../../src/reference/phase.ts';

const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const vec = fc.tuple(
  fc.double({ min: -10, max: 10, noNaN: true }),
  fc.double({ min: -10, max: 10, noNaN: true }),
  fc.double({ min: -10, max: 10, noNaN: true }),
);
const unitVec = vec
  .filter((v) => Math.hypot(...v) > 1e-3)
  .map((v): Vec3 => {
    const l = Math.hypot(...v);
    return [v[0] / l, v[1] / l, v[2] / l];
  });

describe('cameraFrame', () => {
  it('is orthonormal and right-handed for any view and up hint, degenerate ones included', () => {
    fc.assert(
      fc.property(vec, vec, (view, up) => {
        const [f, r, u] = cameraFrame(view, up);
        for (const a of [f, r, u]) expect(dot(a, a)).toBeCloseTo(1, 12);
        expect(Math.abs(dot(f, r))).toBeLessThan(1e-12);
        expect(Math.abs(dot(f, u))).toBeLessThan(1e-12);
        expect(Math.abs(dot(r, u))).toBeLessThan(1e-12);
        // right × up = −forward (the camera looks down its −z, OpenGL-style).
        const rxu: Vec3 = [
          r[1] * u[2] - r[2] * u[1],
          r[2] * u[0] - r[0] * u[2],
          r[0] * u[1] - r[1] * u[0],
        ];
        expect(dot(rxu, f)).toBeCloseTo(-1, 12);
      }),
    );
  });
  it('keeps the up hint on the upper side of the image', () => {
    fc.assert(
      fc.property(unitVec, unitVec, (view, up) => {
        fc.pre(Math.abs(dot(view, up)) < 0.99);
        const [, , u] = cameraFrame(view, up);
        expect(dot(u, up)).toBeGreaterThan(0);
      }),
    );
  });
});

describe('cameraRay', () => {
  it('perspective: the ray through pixel (x, y) hits the image plane at the mapped point', () => {
    const camera = cameraPerspective([1, 2, 3], [0, 0, 0], [0, 1, 0], 50, 160, 90);
    fc.assert(
      fc.property(
        fc.double({ min: 0, max: 160, noNaN: true }),
        fc.double({ min: 0, max: 90, noNaN: true }),
        (x, y) => {
          const ray = cameraRay(camera, [x, y]);
          const t = 1 / dot(ray.direction, camera.forward); // reach the plane at unit distance
          const hit = ray.direction.map((d) => d * t) as unknown as Vec3;
          const tanHalf = Math.tan((25 * Math.PI) / 180);
          expect(dot(hit, camera.right)).toBeCloseTo(
            ((2 * x) / 160 - 1) * tanHalf * (160 / 90),
            10,
          );
          expect(dot(hit, camera.up)).toBeCloseTo((1 - (2 * y) / 90) * tanHalf, 10);
        },
      ),
    );
  });
  it('orthographic: corners are the exact footprint, whatever the image aspect', () => {
    const camera = cameraOrthographic([0, 0, 0], [0, -1, 0], [0, 0, -1], 3, 1, 100, 10);
    expect(cameraRay(camera, [0, 0]).origin.map((v) => v + 0)).toEqual([-1.5, 0, -0.5]);
    expect(cameraRay(camera, [100, 10]).origin.map((v) => v + 0)).toEqual([1.5, 0, 0.5]);
    expect(cameraRay(camera, [50, 5]).direction).toEqual([0, -1, 0]);
  });
});

describe('segments', () => {
  it('box: the end points of a non-empty segment lie on the box boundary or at tMin/tMax', () => {
    fc.assert(
      fc.property(vec, unitVec, (origin, direction) => {
        const s = rayBoxSegment([-1, -2, -0.5], [2, 1, 0.5], origin, direction, 0, 100);
        if (segmentIsEmpty(s)) return;
        for (const t of s) {
          const p = origin.map((o, k) => o + t * (direction[k] ?? 0));
          const inside =
            [-1, -2, -0.5].every((lo, k) => (p[k] ?? 0) >= lo - 1e-9) &&
            [2, 1, 0.5].every((hi, k) => (p[k] ?? 0) <= hi + 1e-9);
          expect(inside).toBe(true);
        }
      }),
    );
  });
  it('sphere: the end points of a segment from outside lie on the sphere', () => {
    fc.assert(
      fc.property(vec, unitVec, (origin, direction) => {
        fc.pre(Math.hypot(origin[0] - 0.5, origin[1], origin[2]) > 2);
        const s = raySphereSegment([0.5, 0, 0], 2, origin, direction, 0, 100);
        if (segmentIsEmpty(s)) return;
        for (const t of s) {
          const p: Vec3 = [
            origin[0] + t * direction[0] - 0.5,
            origin[1] + t * direction[1],
            origin[2] + t * direction[2],
          ];
          expect(Math.hypot(...p)).toBeCloseTo(2, 9);
        }
      }),
    );
  });
});
