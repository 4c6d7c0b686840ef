// The float64 work of <sb-translucent-render> that held the page for 0.1–2.8 s (issue
// 23): pass 1 of Jensen & Buhler 2002 (the irradiance samples and the octree over
// them, with its GPU packing) and, for the CPU fallback, the Lambertian picture and
// the octree gather of pass 2. They run in the compute worker (src/workers/compute.ts),
// cached there by arguments; an input that arrives meanwhile drops the jobs still
// queued for the old values. No DOM, no GPU.
import {
  buildOctree,
  irradianceSamples,
  packOctree,
  renderDiffuseCpu,
  renderGatherCpu,
  type Octree,
  type TranslucentScene,
} from '../../subsurface/translucent.ts';

/** What pass 1 depends on: the sphere, its index and the light (not the image, σ or ε). */
export type SampleScene = Pick<TranslucentScene, 'radius' | 'eta' | 'toLight' | 'irradiance'>;

/** The fields of a scene that pass 1 reads, so that a cache key holds nothing else. */
export function sampleSceneOf(scene: TranslucentScene): SampleScene {
  return {
    radius: scene.radius,
    eta: scene.eta,
    toLight: [...scene.toLight],
    irradiance: scene.irradiance,
  };
}

/** The octree of `count` samples, with its GPU packing and the time both took (ms). */
export interface BuiltOctree {
  octree: Octree;
  packed: { nodes: Uint32Array; samples: Uint32Array };
  buildMs: number;
}

/** The CPU fallback's two pictures of pass 2 and their float64 times (ms). */
export interface CpuPictures {
  diffuse: Float32Array;
  image: Float32Array;
  visited: Float32Array;
  diffuseMs: number;
  gatherMs: number;
}

/**
 * The last octree built here: the fallback's pictures of one scene at several sizes and
 * ε reuse it. Results sent to the page move their buffers (jobs.ts, transferables), so
 * what is sent is always a copy and this one stays whole.
 */
let last: { key: string; octree: Octree; buildMs: number } | null = null;

function octreeOf(scene: SampleScene, count: number): { octree: Octree; buildMs: number } {
  const key = JSON.stringify([scene, count]);
  if (last?.key === key) return last;
  const start = performance.now();
  const samples = irradianceSamples(scene, count);
  const octree = buildOctree(samples, scene.radius);
  last = { key, octree, buildMs: performance.now() - start };
  return last;
}

/** A copy of an octree whose typed arrays the page may take. */
function copyOf(octree: Octree): Octree {
  return {
    nodes: octree.nodes,
    sampleOrder: octree.sampleOrder.slice(),
    samples: {
      ...octree.samples,
      positions: octree.samples.positions.slice(),
      irradiance: octree.samples.irradiance.slice(),
    },
  };
}

export const jobs = {
  /** Pass 1: n = count irradiance samples, their octree, and its GPU packing. */
  octree(scene: SampleScene, count: number): BuiltOctree {
    const { octree, buildMs } = octreeOf(scene, count);
    const start = performance.now();
    const packed = packOctree(octree);
    return { octree: copyOf(octree), packed, buildMs: buildMs + performance.now() - start };
  },
  /** The CPU fallback's Lambertian picture and octree gather with threshold ε at scene.size². */
  pictures(scene: TranslucentScene, count: number, epsilon: number): CpuPictures {
    const { octree } = octreeOf(sampleSceneOf(scene), count);
    const start = performance.now();
    const diffuse = renderDiffuseCpu(scene);
    const middle = performance.now();
    const { image, visited } = renderGatherCpu(scene, octree, epsilon);
    return {
      diffuse,
      image,
      visited,
      diffuseMs: middle - start,
      gatherMs: performance.now() - middle,
    };
  },
};
