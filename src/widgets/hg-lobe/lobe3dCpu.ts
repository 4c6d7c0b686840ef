// CPU fallback of the 3D lobe of <sb-hg-lobe>: the float64 twin's grid
// (lobe3d.ts), projected with the same camera as the GPU's and drawn as a
// wireframe on a 2D canvas. Segments on the far side of a lobe (facing away from
// the eye) are drawn faintly, which is the CPU's cheap stand-in for the GPU's
// depth buffer.
import {
  PHI_SEGMENTS,
  THETA_SEGMENTS,
  WIRE_MERIDIANS,
  WIRE_PARALLELS,
  compareLobeVertex,
  facesEye,
  hgLobeVertex,
  orbitCamera,
  project,
  sceneBounds,
  type Camera,
  type Orbit,
  type SurfacePoint,
  type Vec3,
} from './lobe3d.ts';
import type { HgLobeInputs } from './model.ts';
import { context2d, type Context2D } from '../base/canvas2d.ts';

/** The GPU picture's background (display-encoded 0.148, 0.169, 0.218). */
const BACKGROUND = 'rgb(38, 43, 56)';
const HG_COLOUR = [235, 150, 70] as const;
const COMPARE_COLOUR = [115, 166, 255] as const;
const BEAM_COLOUR = 'rgb(240, 226, 190)';

/** The 2D context of a canvas in the page or of an OffscreenCanvas in a worker. */

interface Segment {
  a: SurfacePoint;
  b: SurfacePoint;
}

/** Rings every `ringStep` and meridians every `meridianStep` of a (THETA+1)×(PHI+1) node grid. */
function gridSegments(
  node: (i: number, j: number) => SurfacePoint,
  rings: readonly number[],
  meridians: readonly number[],
): Segment[] {
  const segments: Segment[] = [];
  for (const i of rings)
    for (let j = 0; j < PHI_SEGMENTS; j++) segments.push({ a: node(i, j), b: node(i, j + 1) });
  for (const j of meridians)
    for (let i = 0; i < THETA_SEGMENTS; i++) segments.push({ a: node(i, j), b: node(i + 1, j) });
  return segments;
}

const range = (count: number, step: number, from = 0): number[] =>
  Array.from({ length: count }, (_, k) => from + k * step);

function strokeSegments(
  context: Context2D,
  camera: Camera,
  segments: readonly Segment[],
  colour: readonly [number, number, number],
  front: boolean,
  lineWidth: number,
): void {
  const { width, height } = context.canvas;
  context.beginPath();
  for (const { a, b } of segments) {
    // A segment is in front when both ends face the eye.
    if ((facesEye(a, camera.eye) && facesEye(b, camera.eye)) !== front) continue;
    const p = project(camera.viewProjection, a.position, width, height);
    const q = project(camera.viewProjection, b.position, width, height);
    context.moveTo(p.x, p.y);
    context.lineTo(q.x, q.y);
  }
  context.strokeStyle = `rgba(${colour.join(', ')}, ${front ? 0.95 : 0.28})`;
  context.lineWidth = lineWidth;
  context.stroke();
}

/** The beam: a thick shaft from the tail and a triangular head ending at the scattering point. */
function drawBeam(
  context: Context2D,
  camera: Camera,
  bounds: ReturnType<typeof sceneBounds>,
  scale: number,
): void {
  const { width, height } = context.canvas;
  const at = (p: Vec3): { x: number; y: number } =>
    project(camera.viewProjection, p, width, height);
  const tail = at([bounds.arrow.tailX, 0, 0]);
  const base = at([bounds.arrow.headBaseX, 0, 0]);
  const tip = at([0, 0, 0]);
  const along = Math.hypot(tip.x - base.x, tip.y - base.y) || 1;
  // The head's half width on screen: the head radius projected at its base, at least 4 px.
  const rim = at([bounds.arrow.headBaseX, bounds.arrow.headRadius, 0]);
  const half = Math.max(Math.hypot(rim.x - base.x, rim.y - base.y), 4 * scale);
  const nx = -(tip.y - base.y) / along;
  const ny = (tip.x - base.x) / along;
  context.strokeStyle = BEAM_COLOUR;
  context.fillStyle = BEAM_COLOUR;
  context.lineWidth = 3 * scale;
  context.beginPath();
  context.moveTo(tail.x, tail.y);
  context.lineTo(base.x, base.y);
  context.stroke();
  context.beginPath();
  context.moveTo(tip.x, tip.y);
  context.lineTo(base.x + half * nx, base.y + half * ny);
  context.lineTo(base.x - half * nx, base.y - half * ny);
  context.closePath();
  context.fill();
  // The forward guide along +x, dashed.
  const end = at([bounds.forwardExtent, 0, 0]);
  context.setLineDash([6 * scale, 5 * scale]);
  context.strokeStyle = 'rgba(217, 224, 242, 0.7)';
  context.lineWidth = scale;
  context.beginPath();
  context.moveTo(tip.x, tip.y);
  context.lineTo(end.x, end.y);
  context.stroke();
  context.setLineDash([]);
}

/**
 * Draws the lobe as the GPU does, in wireframe: the HG lobe's rings (every sixth
 * of the warped grid) and meridians (every 22.5°) in orange, the comparison lobe's
 * wireframe in blue (the GPU's 12 meridians and 11 parallels), the beam arrow, and
 * the far side of each lobe faintly. `scale` is the device pixel ratio.
 */
export function drawLobeWireframe(
  canvas: HTMLCanvasElement | OffscreenCanvas,
  inputs: HgLobeInputs,
  logFloor: number,
  orbit: Orbit,
  scale: number,
): void {
  // A canvas rasterised on the CPU, in the page (context2d). Accelerated, Chromium hands
  // the few thousand round-capped, semi-transparent segments to its GPU process; on a
  // software adapter (SwiftShader) that took 0.6–2.7 s per wireframe, during which the
  // page produced no animation frame at all, so every other picture of the widget
  // waited too (issue 23: hg-lobe's CPU first picture 1.0–2.1 s, 150–230 ms without).
  // The same holds for an OffscreenCanvas in a worker: rasterised in the worker.
  const context = context2d(canvas);
  if (!context) throw new Error('this browser cannot draw on a 2D canvas');
  const bounds = sceneBounds(inputs, logFloor);
  const camera = orbitCamera(bounds, orbit, canvas.width / canvas.height);
  context.fillStyle = BACKGROUND;
  context.fillRect(0, 0, canvas.width, canvas.height);
  context.lineJoin = 'round';
  context.lineCap = 'round';

  const hgNodes = new Map<number, SurfacePoint>();
  const hg = (i: number, j: number): SurfacePoint => {
    const key = i * (PHI_SEGMENTS + 1) + j;
    let point = hgNodes.get(key);
    if (!point) {
      point = hgLobeVertex(inputs, logFloor, i, j);
      hgNodes.set(key, point);
    }
    return point;
  };
  const hgSegments = gridSegments(
    hg,
    range(THETA_SEGMENTS / 6 - 1, 6, 6),
    range(PHI_SEGMENTS / 4, 4),
  );
  let compareSegments: Segment[] = [];
  if (inputs.compare !== 'none') {
    // The wireframe of the GPU's wireVertex: meridians every 30°, parallels every 15° of θ.
    const meridians: Segment[] = [];
    for (let m = 0; m < WIRE_MERIDIANS; m++)
      for (let i = 0; i < THETA_SEGMENTS; i++)
        meridians.push({
          a: compareLobeVertex(inputs, logFloor, i, m, WIRE_MERIDIANS),
          b: compareLobeVertex(inputs, logFloor, i + 1, m, WIRE_MERIDIANS),
        });
    const parallels: Segment[] = [];
    for (let k = 1; k <= WIRE_PARALLELS; k++) {
      const i = (k * THETA_SEGMENTS) / (WIRE_PARALLELS + 1);
      for (let j = 0; j < PHI_SEGMENTS; j++)
        parallels.push({
          a: compareLobeVertex(inputs, logFloor, i, j),
          b: compareLobeVertex(inputs, logFloor, i, j + 1),
        });
    }
    compareSegments = [...meridians, ...parallels];
  }
  strokeSegments(context, camera, compareSegments, COMPARE_COLOUR, false, scale);
  strokeSegments(context, camera, hgSegments, HG_COLOUR, false, scale);
  drawBeam(context, camera, bounds, scale);
  strokeSegments(context, camera, hgSegments, HG_COLOUR, true, 1.5 * scale);
  strokeSegments(context, camera, compareSegments, COMPARE_COLOUR, true, scale);
}
