// The 3D lobe of <sb-hg-lobe>, independent of the backend: the latitude–longitude
// grid, the surface r(θ) of a phase function with its normal, the beam arrow and
// the orbit camera. The vertex shaders of shaders/kernels/hg-lobe-3d.wesl compute
// the same grid and surface in f32; this is their float64 twin, used by the CPU
// fallback's wireframe, by the camera fit, and by the tests.
//
// Geometry: the beam travels along +x and scatters at the origin, so the direction
// at polar angle θ from the beam (μ = cos θ, physics.md §0.3: μ = +1 forward) and
// azimuth φ is ω = (μ, sin θ cos φ, sin θ sin φ). The lobe is the surface r(θ)·ω,
// with r the radius of the polar plot at k = 1: r = p in sr⁻¹ (linear) or
// r = max(log₁₀ p − logFloor, 0) decades (log), the same mapping as model.ts's
// radiusFor. The world's y axis is up on the screen at zero elevation.
import { packStruct } from '../../gpu/layout.ts';
import { hgLobe3dKernel } from '../../gpu/layouts.generated.ts';
import { hgEvalTerms, phaseIsotropic, rayleighEval } from '../../reference/phase.ts';
import type { CompareLobe, HgLobeInputs, RadiusScale } from './model.ts';

/** Rings of the grid from θ = 0 to θ = π (the shader's THETA_SEGMENTS). */
export const THETA_SEGMENTS = 96;
/** Meridians of the grid around the beam (the shader's PHI_SEGMENTS). */
export const PHI_SEGMENTS = 64;
/** Wireframe of the comparison lobe: meridians every 30° and parallels every 15°. */
export const WIRE_MERIDIANS = 12;
export const WIRE_PARALLELS = 11;
/** Segments around the beam arrow's shaft and head. */
export const ARROW_SEGMENTS = 24;

/** Vertex counts of the draws (non-indexed triangle and line lists). */
export const LOBE_VERTEX_COUNT = 6 * THETA_SEGMENTS * PHI_SEGMENTS;
export const WIRE_VERTEX_COUNT =
  2 * (WIRE_MERIDIANS * THETA_SEGMENTS + WIRE_PARALLELS * PHI_SEGMENTS);
/** Six triangles per arrow segment: shaft (2), back cap (1), head base ring (2), cone (1). */
export const ARROW_VERTEX_COUNT = 18 * ARROW_SEGMENTS;

export type Vec3 = [number, number, number];

/** One grid node: the two complements of μ (no cancellation near either pole), μ and sin θ. */
export interface LobeNode {
  oneMinusMu: number;
  onePlusMu: number;
  mu: number;
  sinTheta: number;
}

/**
 * Ring i of the grid, 0 ≤ i ≤ THETA_SEGMENTS, for a lobe peaked forward or backward.
 * With s = i/THETA_SEGMENTS the ring spacing is warped toward the peak by
 * w(s) = s(1 − a + a s), a = warp ∈ [0, 1): the HG peak has a width ~(1 − |g|) rad
 * (physics.md §2.2), so uniform rings would miss it at g = 0.99. A forward lobe
 * puts the ring at θ = π·w(s), a backward one at θ = π − π·w(1 − s). The half angle
 * θ/2 gives the complements without cancellation, 1 − μ = 2 sin²(θ/2) and
 * 1 + μ = 2 cos²(θ/2) (the robust form of physics.md §2.5), and
 * μ = (cos − sin)(cos + sin) of θ/2, sin θ = 2 sin(θ/2) cos(θ/2).
 */
export function lobeNode(i: number, warp: number, backward: boolean): LobeNode {
  const t = (backward ? THETA_SEGMENTS - i : i) / THETA_SEGMENTS;
  const halfAngle = 0.5 * Math.PI * t * (1 - warp + warp * t);
  const a = Math.sin(halfAngle);
  const b = Math.cos(halfAngle);
  // Forward: θ/2 = halfAngle. Backward: θ/2 = π/2 − halfAngle swaps sine and cosine.
  const sinHalf = backward ? b : a;
  const cosHalf = backward ? a : b;
  return {
    oneMinusMu: 2 * sinHalf * sinHalf,
    onePlusMu: 2 * cosHalf * cosHalf,
    mu: (cosHalf - sinHalf) * (cosHalf + sinHalf),
    sinTheta: 2 * sinHalf * cosHalf,
  };
}

/** Azimuth of meridian j, φ = π(2j/PHI_SEGMENTS − 1) ∈ [−π, π] (where WGSL bounds sin and cos). */
export function azimuth(j: number, segments = PHI_SEGMENTS): { cos: number; sin: number } {
  const phi = Math.PI * ((2 * j) / segments - 1);
  return { cos: Math.cos(phi), sin: Math.sin(phi) };
}

/** A phase value p (sr⁻¹) and its slope dp/dμ. */
export interface PhaseSlope {
  p: number;
  dpdmu: number;
}

/**
 * HG (physics.md §2.2) from the complements, and its slope: p ∝ d^{−3/2} with
 * d = 1 + g² − 2gμ, so dp/dμ = 3g·p/d; d in the robust form of §2.5.
 */
export function hgPhaseSlope(g: number, node: LobeNode): PhaseSlope {
  const p = hgEvalTerms(g, node.oneMinusMu, node.onePlusMu);
  const d = g >= 0 ? (1 - g) ** 2 + 2 * g * node.oneMinusMu : (1 + g) ** 2 - 2 * g * node.onePlusMu;
  return { p, dpdmu: (3 * g * p) / Math.max(d, 1e-6) };
}

/** Isotropic (slope 0) or Rayleigh, p = 3(1 + μ²)/(16π), dp/dμ = 3μ/(8π) (physics.md §2.1, §2.6). */
export function comparePhaseSlope(compare: CompareLobe, node: LobeNode): PhaseSlope {
  if (compare === 'rayleigh')
    return { p: rayleighEval(node.mu), dpdmu: (3 * node.mu) / (8 * Math.PI) };
  return { p: phaseIsotropic(), dpdmu: 0 };
}

/** r(θ) and dr/dμ for the radius mapping of the polar plot (model.ts radiusFor, k = 1). */
export function lobeRadius(
  phase: PhaseSlope,
  scale: RadiusScale,
  logFloor: number,
): { r: number; drdmu: number } {
  if (scale === 'linear') return { r: phase.p, drdmu: phase.dpdmu };
  const decades = Math.log10(phase.p) - logFloor;
  return decades > 0
    ? { r: decades, drdmu: phase.dpdmu / (Math.LN10 * phase.p) }
    : { r: 0, drdmu: 0 };
}

export interface SurfacePoint {
  position: Vec3;
  normal: Vec3;
}

/**
 * The point r·ω of the surface of revolution and its outward unit normal. In the
 * meridian plane (axial, radial) the curve is r(θ)(cos θ, sin θ); its tangent is
 * r'(cos θ, sin θ) + r(−sin θ, cos θ) with r' = dr/dθ = −sin θ·dr/dμ, and the
 * outward normal is the tangent turned by −90°:
 * (r' sin θ + r cos θ, r sin θ − r' cos θ). Where r and r' both vanish (the log
 * radius clamped at its floor) the normal is the direction ω itself.
 */
export function surfacePoint(
  node: LobeNode,
  phi: { cos: number; sin: number },
  radius: { r: number; drdmu: number },
): SurfacePoint {
  const { r, drdmu } = radius;
  const direction: Vec3 = [node.mu, node.sinTheta * phi.cos, node.sinTheta * phi.sin];
  const rPrime = -drdmu * node.sinTheta;
  const axial = rPrime * node.sinTheta + r * node.mu;
  const radial = r * node.sinTheta - rPrime * node.mu;
  const length = Math.hypot(axial, radial);
  const normal: Vec3 =
    length > 1e-30
      ? [axial / length, (radial / length) * phi.cos, (radial / length) * phi.sin]
      : direction;
  return { position: [r * direction[0], r * direction[1], r * direction[2]], normal };
}

/** The ring warp of the HG lobe: |g| (0 for the isotropic g = 0, where no ring is special). */
export function lobeWarp(g: number): number {
  return Math.min(Math.abs(g), 0.99);
}

/** Grid node (i, j) of the HG lobe, as the vertex shader hgLobeVertex computes it. */
export function hgLobeVertex(
  inputs: Pick<HgLobeInputs, 'g' | 'scale'>,
  logFloor: number,
  i: number,
  j: number,
): SurfacePoint {
  const node = lobeNode(i, lobeWarp(inputs.g), inputs.g < 0);
  const radius = lobeRadius(hgPhaseSlope(inputs.g, node), inputs.scale, logFloor);
  return surfacePoint(node, azimuth(j), radius);
}

/** Grid node (i, j) of the comparison lobe (uniform rings), as compareLobeVertex computes it. */
export function compareLobeVertex(
  inputs: Pick<HgLobeInputs, 'compare' | 'scale'>,
  logFloor: number,
  i: number,
  j: number,
  phiSegments = PHI_SEGMENTS,
): SurfacePoint {
  const node = lobeNode(i, 0, false);
  const radius = lobeRadius(comparePhaseSlope(inputs.compare, node), inputs.scale, logFloor);
  return surfacePoint(node, azimuth(j, phiSegments), radius);
}

/**
 * The incoming beam as an arrow along the x axis: a shaft of radius shaftRadius
 * from tailX to headBaseX and a cone of radius headRadius from there to the
 * scattering point at the origin.
 */
export interface BeamArrow {
  tailX: number;
  headBaseX: number;
  shaftRadius: number;
  headRadius: number;
}

/** Extents of the scene along the beam (x) and away from it (ρ), from the twin's grid. */
export interface SceneBounds {
  xMin: number;
  xMax: number;
  rhoMax: number;
  /** The largest of the lobes' extents, the unit the arrow is sized in. */
  size: number;
  arrow: BeamArrow;
  /** Where the forward guide line along +x ends. */
  forwardExtent: number;
  /** Points the camera keeps in view: the lobes' grid on eight meridians, the arrow and the guide. */
  fitPoints: Vec3[];
}

export function sceneBounds(inputs: HgLobeInputs, logFloor: number): SceneBounds {
  let xMin = 0;
  let xMax = 0;
  let rhoMax = 0;
  const profiles: { x: number; rho: number }[] = [];
  const visit = (point: SurfacePoint): void => {
    const x = point.position[0];
    const rho = Math.hypot(point.position[1], point.position[2]);
    xMin = Math.min(xMin, x);
    xMax = Math.max(xMax, x);
    rhoMax = Math.max(rhoMax, rho);
    profiles.push({ x, rho });
  };
  // Meridian j = PHI_SEGMENTS/2 has φ = 0, so ρ = y there: the profile of the lobe.
  const profile = PHI_SEGMENTS / 2;
  for (let i = 0; i <= THETA_SEGMENTS; i++) {
    visit(hgLobeVertex(inputs, logFloor, i, profile));
    if (inputs.compare !== 'none') visit(compareLobeVertex(inputs, logFloor, i, profile));
  }
  const size = Math.max(xMax, -xMin, rhoMax, 1e-12);
  // The arrow starts 0.45 size units behind the lobes' back, so it shows even when a
  // backward lobe swallows its head (which the x-ray pass then shows faintly).
  const tailX = Math.min(xMin, 0) - 0.45 * size;
  const headLength = 0.12 * size;
  const arrow: BeamArrow = {
    tailX,
    headBaseX: -headLength,
    shaftRadius: 0.012 * size,
    headRadius: 0.04 * size,
  };
  const forwardExtent = xMax + 0.15 * size;
  // The surfaces of revolution on eight meridians (every 45°) bound their silhouette
  // to within 1 − cos 22.5° ≈ 8%, which the camera's margin covers.
  const fitPoints: Vec3[] = [
    [tailX, 0, 0],
    [forwardExtent, 0, 0],
  ];
  for (const { x, rho } of profiles)
    for (let k = 0; k < 8; k++) {
      const phi = (k * Math.PI) / 4;
      fitPoints.push([x, rho * Math.cos(phi), rho * Math.sin(phi)]);
    }
  return {
    xMin: Math.min(xMin, tailX),
    xMax: forwardExtent,
    rhoMax: Math.max(rhoMax, arrow.headRadius),
    size,
    arrow,
    forwardExtent,
    fitPoints,
  };
}

/** Orbit angles in radians: yaw about the world's up axis, pitch above the horizon. */
export interface Orbit {
  yaw: number;
  pitch: number;
}

/** The default view: from behind the beam's left, a little above (the lobe points away and right). */
export const DEFAULT_ORBIT: Orbit = { yaw: -0.6, pitch: 0.35 };
/** Pitch stays inside ±85°, where the up vector is never parallel to the view. */
export const MAX_PITCH = (85 * Math.PI) / 180;
/** Vertical field of view. */
export const FIELD_OF_VIEW = (30 * Math.PI) / 180;

export function clampOrbit(orbit: Orbit): Orbit {
  const turn = 2 * Math.PI;
  const yaw = orbit.yaw - turn * Math.round(orbit.yaw / turn);
  return { yaw, pitch: Math.min(Math.max(orbit.pitch, -MAX_PITCH), MAX_PITCH) };
}

export interface Camera {
  /** Column-major 4×4 (WGSL mat4x4f), clip z in [0, 1] as WebGPU wants. */
  viewProjection: Float32Array;
  eye: Vec3;
  /** Unit vector toward the key light, in world space (fixed to the camera, up and left). */
  light: Vec3;
}

const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const cross = (a: Vec3, b: Vec3): Vec3 => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];
const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const normalize = (a: Vec3): Vec3 => {
  const length = Math.hypot(a[0], a[1], a[2]);
  return [a[0] / length, a[1] / length, a[2] / length];
};

/** Fraction of the half field of view the fitted scene may fill (the rest is margin). */
const FILL = 0.9;

/**
 * Looks at the scene from the orbit angles, centred on the extent of its fit
 * points across the view and at the distance where all of them fit in the field
 * of view (with a 10% margin): a point at view-space offset (u, v) and depth
 * offset w toward the eye is inside when |u| ≤ (D − w)·tan(half angle), so
 * D = max(w + |u|/tan x, w + |v|/tan y). The framing follows the lobe's shape, so
 * a long lobe seen end-on is not drawn as small as one seen side-on.
 */
export function orbitCamera(bounds: SceneBounds, orbit: Orbit, aspect: number): Camera {
  const { yaw, pitch } = orbit;
  const back: Vec3 = [
    Math.sin(yaw) * Math.cos(pitch),
    Math.sin(pitch),
    Math.cos(yaw) * Math.cos(pitch),
  ];
  // View basis: z toward the eye, x to the right, y up.
  const zAxis = back;
  const xAxis = normalize(cross([0, 1, 0], zAxis));
  const yAxis = cross(zAxis, xAxis);
  const halfY = FIELD_OF_VIEW / 2;
  const tanY = FILL * Math.tan(halfY);
  const tanX = FILL * aspect * Math.tan(halfY);
  // Centre across the view: the middle of the points' extent in u and v.
  const points = bounds.fitPoints;
  const extent = (axis: Vec3): [number, number] => {
    let lo = Infinity;
    let hi = -Infinity;
    for (const p of points) {
      const t = dot(p, axis);
      lo = Math.min(lo, t);
      hi = Math.max(hi, t);
    }
    return [lo, hi];
  };
  const [uLo, uHi] = extent(xAxis);
  const [vLo, vHi] = extent(yAxis);
  const [wLo, wHi] = extent(zAxis);
  const u0 = 0.5 * (uLo + uHi);
  const v0 = 0.5 * (vLo + vHi);
  const w0 = 0.5 * (wLo + wHi);
  const centre: Vec3 = [
    u0 * xAxis[0] + v0 * yAxis[0] + w0 * zAxis[0],
    u0 * xAxis[1] + v0 * yAxis[1] + w0 * zAxis[1],
    u0 * xAxis[2] + v0 * yAxis[2] + w0 * zAxis[2],
  ];
  let distance = 0;
  for (const p of points) {
    const d = sub(p, centre);
    const w = dot(d, zAxis);
    distance = Math.max(
      distance,
      w + Math.abs(dot(d, xAxis)) / tanX,
      w + Math.abs(dot(d, yAxis)) / tanY,
    );
  }
  const radius = Math.max(
    Math.hypot(0.5 * (uHi - uLo), 0.5 * (vHi - vLo), 0.5 * (wHi - wLo)),
    1e-12,
  );
  distance = Math.max(distance, 1.2 * radius);
  const eye: Vec3 = [
    centre[0] + distance * back[0],
    centre[1] + distance * back[1],
    centre[2] + distance * back[2],
  ];
  const near = Math.max(distance - 1.5 * radius, 1e-3 * distance);
  const far = distance + 1.5 * radius;
  const f = 1 / Math.tan(halfY);
  const nf = 1 / (near - far);
  // projection (gl-matrix perspectiveZO) × view (lookAt), written out column by column.
  const projection = [f / aspect, f, far * nf, far * near * nf];
  const view = [
    [xAxis[0], yAxis[0], zAxis[0]],
    [xAxis[1], yAxis[1], zAxis[1]],
    [xAxis[2], yAxis[2], zAxis[2]],
    [-dot(xAxis, eye), -dot(yAxis, eye), -dot(zAxis, eye)],
  ];
  const m = new Float32Array(16);
  for (let column = 0; column < 4; column++) {
    const [vx, vy, vz] = view[column]!;
    const w = column === 3 ? 1 : 0;
    m[4 * column + 0] = projection[0]! * vx!;
    m[4 * column + 1] = projection[1]! * vy!;
    m[4 * column + 2] = projection[2]! * vz! + projection[3]! * w;
    m[4 * column + 3] = -vz!;
  }
  const light = normalize([
    -0.45 * xAxis[0] + 0.7 * yAxis[0] + 0.55 * zAxis[0],
    -0.45 * xAxis[1] + 0.7 * yAxis[1] + 0.55 * zAxis[1],
    -0.45 * xAxis[2] + 0.7 * yAxis[2] + 0.55 * zAxis[2],
  ]);
  return { viewProjection: m, eye, light };
}

/** Clip coordinates of a world point. */
export function toClip(m: Float32Array, p: Vec3): [number, number, number, number] {
  const out: [number, number, number, number] = [0, 0, 0, 0];
  for (let row = 0; row < 4; row++)
    out[row] = m[row]! * p[0] + m[4 + row]! * p[1] + m[8 + row]! * p[2] + m[12 + row]!;
  return out;
}

/** Pixel position (from the top left) and NDC depth of a world point on a width × height canvas. */
export function project(
  m: Float32Array,
  p: Vec3,
  width: number,
  height: number,
): { x: number; y: number; depth: number } {
  const [x, y, z, w] = toClip(m, p);
  return { x: (0.5 + (0.5 * x) / w) * width, y: (0.5 - (0.5 * y) / w) * height, depth: z / w };
}

/** Whether a surface point faces the eye (its normal points toward it). */
export function facesEye(point: SurfacePoint, eye: Vec3): boolean {
  return dot(point.normal, sub(eye, point.position)) > 0;
}

/** The kernel's LobeView uniform, laid out from its WGSL declaration. */
export const LOBE_VIEW = hgLobe3dKernel.LobeView;
const COMPARE_IDS = { none: 0, isotropic: 1, rayleigh: 2 } as const;

/** Packs the kernel's LobeView uniform (declared in shaders/kernels/hg-lobe-3d.wesl). */
export function packView(
  inputs: HgLobeInputs,
  logFloor: number,
  bounds: SceneBounds,
  camera: Camera,
): Uint32Array<ArrayBuffer> {
  const { arrow } = bounds;
  return packStruct(LOBE_VIEW, {
    viewProjection: camera.viewProjection,
    eye: camera.eye,
    g: inputs.g,
    light: camera.light,
    logScale: inputs.scale === 'log' ? 1 : 0,
    arrow: [arrow.tailX, arrow.headBaseX, arrow.shaftRadius, arrow.headRadius],
    logFloor,
    compareLobe: COMPARE_IDS[inputs.compare],
    forwardExtent: bounds.forwardExtent,
    warp: lobeWarp(inputs.g),
  });
}
