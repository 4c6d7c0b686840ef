// The scene of <sb-translucent-render> (chapter 11) and the CPU side of Jensen & Buhler
// 2002's two-pass hierarchical integration: pass 1 places irradiance samples on the sphere
// (Fibonacci lattice, ΔA = 4πR²/n, E with Fresnel transmittance), the octree over them is
// built here in TypeScript (each node: total ΔA, the irradiance-weighted mean position, total
// ΔA·E, a tight bounding box), and gatherCpu is the float64 twin of the GPU traversal in
// shaders/kernels/translucent-gather.wesl (it can also record the cut a pixel uses). Also the
// parameter block shared by the three kernels, the Lambertian twin, and the error measures.
// Units: mm and 1/mm as in the Jensen et al. 2001 table; the light has unit irradiance.
import {
  bssrdfExitFactor,
  fibonacciSpherePoint,
  gatherAcceptsNode,
  irradianceSample,
} from '../reference/bssrdf.ts';
import {
  dipoleParameters,
  dipoleProfile,
  dipoleTotalReflectance,
  type DipoleParameters,
} from '../reference/dipole.ts';
import { packStruct } from '../gpu/layout.ts';
import { translucentPathKernel } from '../gpu/layouts.generated.ts';
import { relativeRmse, rmse } from '../statistics/errors.ts';
import { mean } from '../statistics/summary.ts';

export type Vec3 = [number, number, number];

export interface TranslucentScene {
  /** Image side in pixels. */
  size: number;
  /** Sphere radius R (mm). */
  radius: number;
  /** Half-width of the image (mm). */
  view: number;
  /** σs' per channel (1/mm). */
  sigmaSPrime: readonly [number, number, number];
  /** σa per channel (1/mm). */
  sigmaA: readonly [number, number, number];
  /** Relative index n_material / n_air. */
  eta: number;
  /** HG g of the path tracer (σs = σs'/(1 − g)). */
  g: number;
  /** Unit direction toward the light. */
  toLight: Vec3;
  /** Irradiance of the light, perpendicular to its beam. */
  irradiance: number;
}

/** The image shows the sphere with this margin: view = IMAGE_MARGIN · R. */
export const IMAGE_MARGIN = 1.08;

/** Toward the light for an angle (degrees) from the viewing axis, from the upper left. */
export function lightDirection(angleDegrees: number): Vec3 {
  const a = (angleDegrees * Math.PI) / 180;
  return [-0.6 * Math.sin(a), 0.8 * Math.sin(a), Math.cos(a)];
}

/** Two unit vectors completing l to an orthonormal basis (the light's cross-section). */
export function lightBasis(l: Vec3): [Vec3, Vec3] {
  const helper: Vec3 = Math.abs(l[1]) < 0.9 ? [0, 1, 0] : [1, 0, 0];
  const u = normalize(cross(helper, l));
  return [u, cross(l, u)];
}

const cross = (a: Vec3, b: Vec3): Vec3 => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];
const normalize = (v: Vec3): Vec3 => {
  const n = Math.hypot(v[0], v[1], v[2]);
  return [v[0] / n, v[1] / n, v[2] / n];
};

/** The sphere point seen through the centre of pixel (i, j) (row 0 at the top), or null. */
export function visiblePoint(scene: TranslucentScene, i: number, j: number): Vec3 | null {
  const x = ((2 * (i + 0.5)) / scene.size - 1) * scene.view;
  const y = (1 - (2 * (j + 0.5)) / scene.size) * scene.view;
  const h2 = scene.radius ** 2 - x * x - y * y;
  return h2 > 0 ? [x, y, Math.sqrt(h2)] : null;
}

/**
 * Pixels whose whole footprint lies on the sphere: the errors are measured over these, where
 * a value at the pixel centre and the reference's average over the pixel agree up to the
 * curvature of the picture (at the silhouette they would differ by the covered fraction).
 */
export function interiorMask(scene: TranslucentScene): Uint8Array {
  const mask = new Uint8Array(scene.size * scene.size);
  const pixel = (2 * scene.view) / scene.size;
  for (let j = 0; j < scene.size; j++)
    for (let i = 0; i < scene.size; i++) {
      const x0 = -scene.view + i * pixel;
      const y0 = scene.view - j * pixel;
      const far = Math.max(
        ...[
          [x0, y0],
          [x0 + pixel, y0],
          [x0, y0 - pixel],
          [x0 + pixel, y0 - pixel],
        ].map(([x, y]) => Math.hypot(x!, y!)),
      );
      mask[j * scene.size + i] = far < scene.radius ? 1 : 0;
    }
  return mask;
}

export const dipolesOf = (scene: TranslucentScene): DipoleParameters[] =>
  [0, 1, 2].map((c) => dipoleParameters(scene.sigmaSPrime[c]!, scene.sigmaA[c]!, scene.eta));

/** Pass 1 of Jensen & Buhler: n irradiance samples of area ΔA = 4πR²/n and transmitted E. */
export interface IrradianceSamples {
  count: number;
  /** ΔA = 4πR²/n (mm²). */
  area: number;
  /** x, y, z per sample (mm). */
  positions: Float64Array;
  /** E per sample (per unit beam irradiance), with Fresnel transmittance. */
  irradiance: Float64Array;
}

export function irradianceSamples(
  scene: Pick<TranslucentScene, 'radius' | 'toLight' | 'eta' | 'irradiance'>,
  count: number,
): IrradianceSamples {
  const positions = new Float64Array(3 * count);
  const irradiance = new Float64Array(count);
  for (let i = 0; i < count; i++) {
    const n = fibonacciSpherePoint(i, count);
    positions.set(
      n.map((v) => v * scene.radius),
      3 * i,
    );
    irradiance[i] = scene.irradiance * irradianceSample(n, scene.toLight, scene.eta);
  }
  return { count, area: (4 * Math.PI * scene.radius ** 2) / count, positions, irradiance };
}

export interface OctreeNode {
  /** Irradiance-weighted mean position p̄ (area-weighted where no sample is lit). */
  centroid: Vec3;
  /** Total ΔA (mm²). */
  area: number;
  /** Total ΔA·E. */
  power: number;
  boxMin: Vec3;
  boxMax: Vec3;
  childStart: number;
  childCount: number;
  /** Leaves: their samples are sampleOrder[sampleStart … sampleStart + sampleCount). */
  sampleStart: number;
  sampleCount: number;
  depth: number;
}

export interface Octree {
  nodes: OctreeNode[];
  /** Sample indices in leaf order. */
  sampleOrder: Uint32Array;
  samples: IrradianceSamples;
}

/** Leaves hold at most this many samples; the depth is capped at OCTREE_MAX_DEPTH. */
export const OCTREE_LEAF_SIZE = 8;
export const OCTREE_MAX_DEPTH = 8;

interface BuildNode {
  indices: number[];
  children: BuildNode[];
  depth: number;
}

/**
 * The octree over the samples: the cube around the sphere is split into octants until a
 * cell holds at most OCTREE_LEAF_SIZE samples; empty octants are dropped. Nodes are stored
 * breadth-first, so the children of a node are contiguous (what the GPU traversal reads).
 */
export function buildOctree(samples: IrradianceSamples, radius: number): Octree {
  const half = radius * 1.0001;
  const split = (indices: number[], centre: Vec3, size: number, depth: number): BuildNode => {
    const node: BuildNode = { indices, children: [], depth };
    if (indices.length <= OCTREE_LEAF_SIZE || depth >= OCTREE_MAX_DEPTH) return node;
    const buckets: number[][] = Array.from({ length: 8 }, () => []);
    for (const i of indices) {
      const p = samples.positions;
      const k =
        (p[3 * i]! >= centre[0] ? 1 : 0) +
        (p[3 * i + 1]! >= centre[1] ? 2 : 0) +
        (p[3 * i + 2]! >= centre[2] ? 4 : 0);
      buckets[k]!.push(i);
    }
    const q = size / 2;
    buckets.forEach((bucket, k) => {
      if (bucket.length === 0) return;
      const c: Vec3 = [
        centre[0] + (k & 1 ? q : -q),
        centre[1] + (k & 2 ? q : -q),
        centre[2] + (k & 4 ? q : -q),
      ];
      node.children.push(split(bucket, c, q, depth + 1));
    });
    return node;
  };
  const all = Array.from({ length: samples.count }, (_, i) => i);
  const root = split(all, [0, 0, 0], half, 0);

  const nodes: OctreeNode[] = [];
  const order: number[] = [];
  const queue: BuildNode[] = [root];
  const summary = (b: BuildNode): OctreeNode => {
    let power = 0;
    const weighted: Vec3 = [0, 0, 0];
    const plain: Vec3 = [0, 0, 0];
    const boxMin: Vec3 = [Infinity, Infinity, Infinity];
    const boxMax: Vec3 = [-Infinity, -Infinity, -Infinity];
    for (const i of b.indices) {
      const w = samples.area * samples.irradiance[i]!;
      power += w;
      for (let k = 0; k < 3; k++) {
        const v = samples.positions[3 * i + k]!;
        weighted[k] = weighted[k]! + w * v;
        plain[k] = plain[k]! + v;
        boxMin[k] = Math.min(boxMin[k]!, v);
        boxMax[k] = Math.max(boxMax[k]!, v);
      }
    }
    const centroid: Vec3 =
      power > 0
        ? [weighted[0] / power, weighted[1] / power, weighted[2] / power]
        : [plain[0] / b.indices.length, plain[1] / b.indices.length, plain[2] / b.indices.length];
    return {
      centroid,
      area: samples.area * b.indices.length,
      power,
      boxMin,
      boxMax,
      childStart: 0,
      childCount: b.children.length,
      sampleStart: 0,
      sampleCount: 0,
      depth: b.depth,
    };
  };
  // Breadth-first: a node's children are appended together when it is taken off the queue.
  nodes.push(summary(root));
  for (let head = 0; head < queue.length; head++) {
    const b = queue[head]!;
    const node = nodes[head]!;
    if (b.children.length === 0) {
      node.sampleStart = order.length;
      node.sampleCount = b.indices.length;
      order.push(...b.indices);
    } else {
      node.childStart = nodes.length;
      for (const child of b.children) {
        queue.push(child);
        nodes.push(summary(child));
      }
    }
  }
  return { nodes, sampleOrder: Uint32Array.from(order), samples };
}

/** The octree and samples as the GPU reads them (4 vec4f per node, 1 per sample). */
export function packOctree(octree: Octree): { nodes: Uint32Array; samples: Uint32Array } {
  const nodeFloats = new Float32Array(16 * octree.nodes.length);
  const nodeWords = new Uint32Array(nodeFloats.buffer);
  octree.nodes.forEach((n, k) => {
    const o = 16 * k;
    nodeFloats.set([...n.centroid, n.area, ...n.boxMin, n.power, ...n.boxMax], o);
    nodeWords[o + 11] = n.childStart;
    nodeWords[o + 12] = n.childCount;
    nodeWords[o + 13] = n.sampleStart;
    nodeWords[o + 14] = n.sampleCount;
  });
  const { samples, sampleOrder } = octree;
  const sampleFloats = new Float32Array(4 * samples.count);
  sampleOrder.forEach((i, k) => {
    sampleFloats.set(
      [
        samples.positions[3 * i]!,
        samples.positions[3 * i + 1]!,
        samples.positions[3 * i + 2]!,
        samples.area * samples.irradiance[i]!,
      ],
      4 * k,
    );
  });
  return { nodes: nodeWords, samples: new Uint32Array(sampleFloats.buffer) };
}

export interface GatherResult {
  /** M_o per channel. */
  exitance: Vec3;
  visited: number;
  terms: number;
}

/**
 * Twin of the GPU gather: M_o(x) = Σ R_d(‖x − p‖) ΔA E over the cut of the octree chosen by
 * ε (a node is used whole when gatherAcceptsNode, else its children, at leaves each sample).
 * `cut` collects the nodes used whole (for the widget's view of one pixel's cut).
 */
export function gatherCpu(
  octree: Octree,
  dipoles: readonly DipoleParameters[],
  x: Vec3,
  epsilon: number,
  cut?: OctreeNode[],
): GatherResult {
  const exitance: Vec3 = [0, 0, 0];
  let visited = 0;
  let terms = 0;
  const add = (power: number, p: readonly number[]): void => {
    const r = Math.hypot(x[0] - p[0]!, x[1] - p[1]!, x[2] - p[2]!);
    for (let c = 0; c < 3; c++) exitance[c] = exitance[c]! + power * dipoleProfile(dipoles[c]!, r);
    terms += 1;
  };
  const stack = [0];
  const { samples } = octree;
  while (stack.length > 0) {
    const node = octree.nodes[stack.pop()!]!;
    visited += 1;
    if (node.power <= 0) continue;
    if (gatherAcceptsNode(node.area, node.centroid, node.boxMin, node.boxMax, x, epsilon)) {
      add(node.power, node.centroid);
      cut?.push(node);
      continue;
    }
    if (node.childCount === 0) {
      for (let k = 0; k < node.sampleCount; k++) {
        const i = octree.sampleOrder[node.sampleStart + k]!;
        add(samples.area * samples.irradiance[i]!, [
          samples.positions[3 * i]!,
          samples.positions[3 * i + 1]!,
          samples.positions[3 * i + 2]!,
        ]);
      }
    } else {
      for (let k = 0; k < node.childCount; k++) stack.push(node.childStart + k);
    }
  }
  return { exitance, visited, terms };
}

/** The direct sum over all samples, Σ R_d(‖x − p_i‖) ΔA E_i: the gather's ε → 0 limit. */
export function directSum(
  samples: IrradianceSamples,
  dipoles: readonly DipoleParameters[],
  x: Vec3,
): Vec3 {
  const exitance: Vec3 = [0, 0, 0];
  for (let i = 0; i < samples.count; i++) {
    const power = samples.area * samples.irradiance[i]!;
    if (power <= 0) continue;
    const p = samples.positions;
    const r = Math.hypot(x[0] - p[3 * i]!, x[1] - p[3 * i + 1]!, x[2] - p[3 * i + 2]!);
    for (let c = 0; c < 3; c++) exitance[c] = exitance[c]! + power * dipoleProfile(dipoles[c]!, r);
  }
  return exitance;
}

/** L_o per pixel (RGB) and nodes visited, from gatherCpu: the CPU fallback of pass 2. */
export function renderGatherCpu(
  scene: TranslucentScene,
  octree: Octree,
  epsilon: number,
): { image: Float32Array; visited: Float32Array } {
  const dipoles = dipolesOf(scene);
  const image = new Float32Array(3 * scene.size * scene.size);
  const visited = new Float32Array(scene.size * scene.size);
  for (let j = 0; j < scene.size; j++)
    for (let i = 0; i < scene.size; i++) {
      const x = visiblePoint(scene, i, j);
      if (!x) continue;
      const result = gatherCpu(octree, dipoles, x, epsilon);
      const factor = bssrdfExitFactor(x[2] / scene.radius, scene.eta);
      const o = j * scene.size + i;
      for (let c = 0; c < 3; c++) image[3 * o + c] = result.exitance[c]! * factor;
      visited[o] = result.visited;
    }
  return { image, visited };
}

/** Twin of diffuseMain: L = (R_d/π) E max(0, n·l) with R_d = dipoleTotalReflectance. */
export function renderDiffuseCpu(scene: TranslucentScene): Float32Array {
  const albedo = dipolesOf(scene).map((p) => dipoleTotalReflectance(p));
  const image = new Float32Array(3 * scene.size * scene.size);
  for (let j = 0; j < scene.size; j++)
    for (let i = 0; i < scene.size; i++) {
      const x = visiblePoint(scene, i, j);
      if (!x) continue;
      const l = scene.toLight;
      const cos = Math.max(0, (x[0] * l[0] + x[1] * l[1] + x[2] * l[2]) / scene.radius);
      for (let c = 0; c < 3; c++)
        image[3 * (j * scene.size + i) + c] = (albedo[c]! / Math.PI) * scene.irradiance * cos;
    }
  return image;
}

/**
 * The uniform block TranslucentParams of the three kernels (declared alike in each;
 * tests/shaders/layout-constants.test.ts holds the three layouts equal).
 */
export const TRANSLUCENT_PARAMS = translucentPathKernel.TranslucentParams;

export function packParams(
  scene: TranslucentScene,
  extra: {
    count?: number;
    seed?: number;
    offset?: number;
    epsilon?: number;
    ambient?: number;
    maxBounces?: number;
    rowStart?: number;
  },
): Uint32Array<ArrayBuffer> {
  const [lu, lv] = lightBasis(scene.toLight);
  return packStruct(TRANSLUCENT_PARAMS, {
    size: scene.size,
    count: extra.count ?? 0,
    seed: extra.seed ?? 0,
    offset: extra.offset ?? 0,
    radius: scene.radius,
    view: scene.view,
    eta: scene.eta,
    epsilon: extra.epsilon ?? 0,
    sigmaSPrime: [...scene.sigmaSPrime, scene.g],
    sigmaA: [...scene.sigmaA, extra.ambient ?? 0],
    toLight: [...scene.toLight, scene.irradiance],
    lightU: [...lu, extra.maxBounces ?? 4096],
    lightV: [...lv, 0],
    rowStart: extra.rowStart ?? 0,
  });
}

export interface ImageError {
  /** Root mean square difference over the interior pixels and the three channels. */
  rmse: number;
  /** rmse divided by the reference's mean. */
  relativeRmse: number;
  /** (mean of the image − mean of the reference) / mean of the reference. */
  meanError: number;
}

/** Error of an RGB image against a reference over the pixels of `mask`. */
export function imageError(
  image: ArrayLike<number>,
  reference: ArrayLike<number>,
  mask: Uint8Array,
): ImageError {
  // The channels of the pixels inside the mask, then the shared statistics on them.
  const inside: number[] = [];
  const insideReference: number[] = [];
  mask.forEach((flag, p) => {
    if (!flag) return;
    for (let c = 0; c < 3; c++) {
      inside.push(image[3 * p + c]!);
      insideReference.push(reference[3 * p + c]!);
    }
  });
  const meanReference = mean(insideReference);
  if (!(meanReference > 0)) return { rmse: NaN, relativeRmse: NaN, meanError: NaN };
  return {
    rmse: rmse(inside, insideReference),
    relativeRmse: relativeRmse(inside, insideReference),
    meanError: mean(inside) / meanReference - 1,
  };
}
