// The model of <sb-translucent-room>: its parameters as the scene of
// src/subsurface/translucentRoom.ts, the sizes of the irradiance pass, and the error of the
// dipole picture against the path-traced one when both are Monte Carlo estimates.
import type { ParameterValues } from '../parameters.ts';
import { findMaterial } from '../../subsurface/materials.ts';
import { roomScene, type RoomScene } from '../../subsurface/translucentRoom.ts';
import {
  errorAgainstNoisyReference,
  type NoisyReferenceError,
} from '../translucent-render/model.ts';
import { TRANSLUCENT_ROOM } from './schema.ts';

export const ROOM_DEFAULTS: ParameterValues = Object.fromEntries(
  TRANSLUCENT_ROOM.parameters.map((p) => [p.name, p.default]),
);

const WALLS: Record<string, number> = { coloured: 0, white: 1, black: 2 };

export function sceneFromValues(values: ParameterValues): RoomScene {
  const material = findMaterial(String(values['material'])) ?? findMaterial('skin1')!;
  return roomScene(
    material,
    Number(values['radius']),
    WALLS[String(values['walls'])] ?? 0,
    Number(values['size']),
  );
}

/**
 * Irradiance samples and rays per sample of pass 1 on each backend. 1024 samples on the 5 mm
 * default sphere own 0.31 mm² each, about 0.55 mm apart, below the mean free paths
 * 1/σt' of 0.7 to 1.3 mm of Skin 1; the CPU fallback uses fewer (its picture is 24² pixels).
 */
export const IRRADIANCE = {
  gpu: { samples: 1024, rays: 64 },
  cpu: { samples: 256, rays: 16 },
} as const;
/**
 * Pass 1 of the first picture after an input on WebGPU (issue 23, a preview within the
 * first-picture budget): a quarter of the samples (about 1.1 mm apart on the default
 * sphere) with an eighth of the rays each, so the dipole picture is a coarser, noisier
 * quadrature of the same integral. The next frame runs the full pass and restarts the
 * dipole picture on it. 16 rays took 44–48 ms on SwiftShader (bench/firstPictureProbe.ts),
 * half of the first-picture budget by itself.
 */
export const IRRADIANCE_PREVIEW = { samples: 256, rays: 8 } as const;
/**
 * Pass 1 runs once: its paths see the sphere only as a mirror, so light that leaves the sphere,
 * bounces off a wall and comes back is left out. A second pass fed with the first's samples adds
 * it (the bench's `passes`), at the cost of a gather over all samples wherever a path of pass 1
 * meets the sphere, which is most of pass 1's time on a CPU implementation of WebGPU.
 */
export const IRRADIANCE_PASSES = 1;

/** A key of everything the pictures depend on (both restart when it changes). */
export function pictureKey(values: ParameterValues): string {
  return ['material', 'radius', 'walls', 'size', 'seed'].map((k) => values[k]).join('|');
}

/**
 * The dipole picture's error against the reference, over `mask`. Both are Monte Carlo means
 * with per-value standard errors; their noises are independent, so E[(a − r̂)²] = (a − r)² +
 * Var a + Var r̂, and errorAgainstNoisyReference (chapter 11) subtracts the sum of both
 * squared standard errors when given their root-sum-square.
 */
export function dipoleError(
  dipoleMean: ArrayLike<number>,
  dipoleSe: ArrayLike<number>,
  referenceMean: ArrayLike<number>,
  referenceSe: ArrayLike<number>,
  mask: Uint8Array,
): NoisyReferenceError {
  const combined = Float64Array.from({ length: referenceSe.length }, (_, k) => {
    const a = Number.isFinite(dipoleSe[k]!) ? dipoleSe[k]! : 0;
    const b = Number.isFinite(referenceSe[k]!) ? referenceSe[k]! : 0;
    return Math.hypot(a, b);
  });
  return errorAgainstNoisyReference(dipoleMean, referenceMean, combined, mask);
}
