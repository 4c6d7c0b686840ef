// The 3D lobe of the hg-lobe widget (shaders/kernels/hg-lobe-3d.wesl) through Dawn:
// the vertex shaders' grid and surface function against the float64 twin
// (src/widgets/hg-lobe/lobe3d.ts), and the render pipelines drawing a picture in
// which the lobe, the beam and the comparison wireframe land where the twin's
// camera puts them.
import { afterAll, describe, expect, it } from 'vitest';
import { linkLibraryKernel } from '../../src/gpu/link.ts';
import {
  DEFAULT_ORBIT,
  PHI_SEGMENTS,
  THETA_SEGMENTS,
  azimuth,
  comparePhaseSlope,
  hgPhaseSlope,
  lobeNode,
  lobeRadius,
  lobeWarp,
  orbitCamera,
  packView,
  project,
  sceneBounds,
  surfacePoint,
  type LobeNode,
  type SurfacePoint,
  type Vec3,
} from '../../src/widgets/hg-lobe/lobe3d.ts';
import {
  LOBE_3D_DEPTH_FORMAT,
  LOBE_3D_KERNEL,
  LOBE_3D_SAMPLES,
  LobeRenderer,
} from '../../src/widgets/hg-lobe/lobe3dGpu.ts';
import { polarLayout, type HgLobeInputs } from '../../src/widgets/hg-lobe/model.ts';
import { nodeDevice, releaseNodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';

afterAll(releaseNodeDevice);

function inputs(
  g: number,
  scale: HgLobeInputs['scale'],
  compare: HgLobeInputs['compare'],
): HgLobeInputs {
  return { g: Math.fround(g), compare, scale, samplesExponent: 16, sampleCount: 65536, seed: 1 };
}

/** logFloor as the widget computes it: the polar plot's, so both pictures use one radius mapping. */
function logFloorOf(input: HgLobeInputs): number {
  return polarLayout(input, 960, 480).logFloor;
}

function viewUniforms(input: HgLobeInputs, aspect = 1.6): Uint32Array<ArrayBuffer> {
  const floor = logFloorOf(input);
  const bounds = sceneBounds(input, floor);
  return packView(input, floor, bounds, orbitCamera(bounds, DEFAULT_ORBIT, aspect));
}

const ROWS = THETA_SEGMENTS + 1;
const COLUMNS = PHI_SEGMENTS + 1;

/** Compute entry points appended to the linked kernel: they call the vertex shaders' functions per grid node. */
const PROBE = `
@group(0) @binding(1) var<storage, read_write> probe: array<vec4f>;

fn store(k: u32, v: LobeVertex) {
  probe[3u * k] = vec4f(v.position, v.oneMinusMu);
  probe[3u * k + 1u] = vec4f(v.normal, v.onePlusMu);
  probe[3u * k + 2u] = vec4f(v.phi, 0.0, 0.0);
}

@compute @workgroup_size(64)
fn probeHg(@builtin(global_invocation_id) id: vec3u) {
  let k = id.x;
  if (k < ${ROWS}u * ${COLUMNS}u) { store(k, hgLobeVertex(k / ${COLUMNS}u, k % ${COLUMNS}u)); }
}

@compute @workgroup_size(64)
fn probeCompare(@builtin(global_invocation_id) id: vec3u) {
  let k = id.x;
  if (k < ${ROWS}u * ${COLUMNS}u) {
    store(k, compareLobeVertex(k / ${COLUMNS}u, k % ${COLUMNS}u, ${PHI_SEGMENTS}u));
  }
}
`;

interface ProbedVertex extends SurfacePoint {
  node: LobeNode;
  phi: { cos: number; sin: number };
}

/** Runs a probe entry point and returns the GPU's vertex for every node (i, j), row-major. */
async function probeVertices(
  input: HgLobeInputs,
  entryPoint: 'probeHg' | 'probeCompare',
): Promise<ProbedVertex[]> {
  const device = await nodeDevice();
  const code = (await linkLibraryKernel(SHADER_LIBRARY, LOBE_3D_KERNEL)) + PROBE;
  device.pushErrorScope('validation');
  const module = device.createShaderModule({ code });
  const pipeline = device.createComputePipeline({
    layout: 'auto',
    compute: { module, entryPoint },
  });
  const count = ROWS * COLUMNS;
  const uniform = device.createBuffer({
    size: 128,
    usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
  });
  device.queue.writeBuffer(uniform, 0, viewUniforms(input));
  const output = device.createBuffer({
    size: count * 48,
    usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC,
  });
  const readBack = device.createBuffer({
    size: count * 48,
    usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
  });
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginComputePass();
  pass.setPipeline(pipeline);
  pass.setBindGroup(
    0,
    device.createBindGroup({
      layout: pipeline.getBindGroupLayout(0),
      entries: [
        { binding: 0, resource: { buffer: uniform } },
        { binding: 1, resource: { buffer: output } },
      ],
    }),
  );
  pass.dispatchWorkgroups(Math.ceil(count / 64));
  pass.end();
  encoder.copyBufferToBuffer(output, 0, readBack, 0, count * 48);
  device.queue.submit([encoder.finish()]);
  const error = await device.popErrorScope();
  expect(error?.message ?? null).toBeNull();
  await readBack.mapAsync(GPUMapMode.READ);
  const data = new Float32Array(readBack.getMappedRange().slice(0));
  readBack.unmap();
  for (const buffer of [uniform, output, readBack]) buffer.destroy();
  return Array.from({ length: count }, (_, k) => {
    const at = (n: number): number => data[12 * k + n]!;
    const oneMinusMu = at(3);
    const onePlusMu = at(7);
    return {
      position: [at(0), at(1), at(2)],
      normal: [at(4), at(5), at(6)],
      // μ and sin θ from the GPU's complements, so that the twin evaluates the surface
      // at exactly the GPU's node and only the radius function is compared.
      node: {
        oneMinusMu,
        onePlusMu,
        mu: 0.5 * (onePlusMu - oneMinusMu),
        sinTheta: Math.sqrt(oneMinusMu * onePlusMu),
      },
      phi: { cos: at(8), sin: at(9) },
    };
  });
}

const distance = (a: Vec3, b: Vec3): number => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

const CASES: [string, HgLobeInputs][] = [
  ['g = 0.6, linear', inputs(0.6, 'linear', 'isotropic')],
  ['g = 0.6, log', inputs(0.6, 'log', 'isotropic')],
  ['g = −0.3, linear (backward lobe, mirrored grid)', inputs(-0.3, 'linear', 'rayleigh')],
  ['g = 0, log (the sphere)', inputs(0, 'log', 'rayleigh')],
  ['g = 0.99, linear (the needle: peak 1584 sr⁻¹)', inputs(0.99, 'linear', 'isotropic')],
  ['g = −0.99, log (seven decades)', inputs(-0.99, 'log', 'rayleigh')],
];

/**
 * Tolerances. The node: WGSL bounds sin and cos on [−π, π] by 2^-11 absolute only
 * (spec, "Floating Point Accuracy"), so 1 ∓ μ = 2·sin²/cos²(θ/2) may move by
 * 4·2^-11; φ likewise. The surface at the GPU's own node: f32 rounding of a dozen
 * operations and of hgEvalTerms (division and sqrt, 2.5 ULP each), ≲ 1e-6
 * relative; log2 adds 2^-21 absolute (×log10 2) to a log radius. 1e-5 relative
 * (plus 1e-5 decades on the log scale) bounds both with margin.
 */
const NODE_TOLERANCE = 4 * 2 ** -11;

describe('hg-lobe 3D vertex shader: the grid and the surface r(θ)·ω against the float64 twin', () => {
  for (const [name, input] of CASES) {
    it(`${name}: the HG lobe's ${ROWS}×${COLUMNS} nodes`, async () => {
      const floor = logFloorOf(input);
      const gpu = await probeVertices(input, 'probeHg');
      const backward = input.g < 0;
      let worstNode = 0;
      let worstPosition = 0;
      let worstNormal = 0;
      for (let i = 0; i < ROWS; i++)
        for (let j = 0; j < COLUMNS; j++) {
          const vertex = gpu[i * COLUMNS + j]!;
          for (const value of [...vertex.position, ...vertex.normal])
            expect(Number.isFinite(value)).toBe(true);
          // The grid: the GPU's node is the twin's, to the accuracy WGSL promises for sin and cos.
          const node = lobeNode(i, lobeWarp(input.g), backward);
          const phi = azimuth(j);
          worstNode = Math.max(
            worstNode,
            Math.abs(vertex.node.oneMinusMu - node.oneMinusMu),
            Math.abs(vertex.node.onePlusMu - node.onePlusMu),
            Math.abs(vertex.phi.cos - phi.cos),
            Math.abs(vertex.phi.sin - phi.sin),
          );
          // The surface at the GPU's node: the library's hgEvalTerms and the radius mapping.
          const phase = hgPhaseSlope(input.g, vertex.node);
          const radius = lobeRadius(phase, input.scale, floor);
          const twin = surfacePoint(vertex.node, vertex.phi, radius);
          const allowed = 1e-5 * radius.r + (input.scale === 'log' ? 1e-5 : 1e-30);
          worstPosition = Math.max(
            worstPosition,
            distance(vertex.position, twin.position) / allowed,
          );
          // A log radius that rounds to the floor on one side only has no slope there.
          const nearFloor = input.scale === 'log' && Math.abs(Math.log10(phase.p) - floor) < 1e-4;
          if (!nearFloor) worstNormal = Math.max(worstNormal, distance(vertex.normal, twin.normal));
        }
      expect(worstNode).toBeLessThan(NODE_TOLERANCE);
      expect(worstPosition).toBeLessThan(1);
      // Unit normals: 1e-4 covers the f32 slope 3g·p/d and the normalization.
      expect(worstNormal).toBeLessThan(1e-4);
    });
  }

  for (const compare of ['isotropic', 'rayleigh'] as const) {
    it(`the ${compare} comparison lobe's nodes, linear and log`, async () => {
      for (const scale of ['linear', 'log'] as const) {
        const input = inputs(0.6, scale, compare);
        const floor = logFloorOf(input);
        const gpu = await probeVertices(input, 'probeCompare');
        for (let i = 0; i < ROWS; i++)
          for (let j = 0; j < COLUMNS; j++) {
            const vertex = gpu[i * COLUMNS + j]!;
            const node = lobeNode(i, 0, false);
            expect(Math.abs(vertex.node.oneMinusMu - node.oneMinusMu)).toBeLessThan(NODE_TOLERANCE);
            const radius = lobeRadius(comparePhaseSlope(compare, vertex.node), scale, floor);
            const twin = surfacePoint(vertex.node, vertex.phi, radius);
            expect(distance(vertex.position, twin.position)).toBeLessThan(
              1e-5 * radius.r + (scale === 'log' ? 1e-5 : 1e-30),
            );
          }
      }
    });
  }
});

const WIDTH = 320;
const HEIGHT = 200;

/** Draws the widget's frame into an rgba8unorm texture (4× MSAA, resolved) and reads it back. */
async function renderLobe(input: HgLobeInputs): Promise<Uint8Array> {
  const device = await nodeDevice();
  const code = await linkLibraryKernel(SHADER_LIBRARY, LOBE_3D_KERNEL);
  const renderer = await LobeRenderer.create(device, code, 'rgba8unorm');
  const texture = (format: GPUTextureFormat, sampleCount: number, copy: boolean): GPUTexture =>
    device.createTexture({
      size: [WIDTH, HEIGHT],
      format,
      sampleCount,
      usage: GPUTextureUsage.RENDER_ATTACHMENT | (copy ? GPUTextureUsage.COPY_SRC : 0),
    });
  const color = texture('rgba8unorm', LOBE_3D_SAMPLES, false);
  const resolve = texture('rgba8unorm', 1, true);
  const depth = texture(LOBE_3D_DEPTH_FORMAT, LOBE_3D_SAMPLES, false);
  const readBack = device.createBuffer({
    size: WIDTH * HEIGHT * 4,
    usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
  });
  device.pushErrorScope('validation');
  const encoder = device.createCommandEncoder();
  renderer.encode(
    encoder,
    { color: color.createView(), resolve: resolve.createView(), depth: depth.createView() },
    viewUniforms(input, WIDTH / HEIGHT),
    input.compare !== 'none',
  );
  encoder.copyTextureToBuffer({ texture: resolve }, { buffer: readBack, bytesPerRow: WIDTH * 4 }, [
    WIDTH,
    HEIGHT,
  ]);
  device.queue.submit([encoder.finish()]);
  const error = await device.popErrorScope();
  expect(error?.message ?? null).toBeNull();
  await readBack.mapAsync(GPUMapMode.READ);
  const pixels = new Uint8Array(readBack.getMappedRange().slice(0));
  readBack.unmap();
  readBack.destroy();
  for (const t of [color, resolve, depth]) t.destroy();
  renderer.destroy();
  return pixels;
}

/** The pixel of a world point under the twin's camera. */
function pixelOf(input: HgLobeInputs, point: Vec3): [number, number] {
  const floor = logFloorOf(input);
  const camera = orbitCamera(sceneBounds(input, floor), DEFAULT_ORBIT, WIDTH / HEIGHT);
  const { x, y } = project(camera.viewProjection, point, WIDTH, HEIGHT);
  return [Math.floor(x), Math.floor(y)];
}

const rgb = (pixels: Uint8Array, [x, y]: [number, number]): [number, number, number] => {
  const offset = 4 * (y * WIDTH + x);
  return [pixels[offset]!, pixels[offset + 1]!, pixels[offset + 2]!];
};

/** Pixels in the lobe's orange (red well above blue) and in the wireframe's blue. */
function census(pixels: Uint8Array): { orange: number; blue: number } {
  let orange = 0;
  let blue = 0;
  for (let k = 0; k < WIDTH * HEIGHT; k++) {
    const [r, g, b] = [pixels[4 * k]!, pixels[4 * k + 1]!, pixels[4 * k + 2]!];
    if (r > b + 60 && r > g) orange += 1;
    if (b > r + 60 && b > 150) blue += 1;
  }
  return { orange, blue };
}

describe('hg-lobe 3D render pipelines', () => {
  it('draw the lobe where the twin’s camera projects it, in the lobe’s orange', async () => {
    for (const [, input] of [
      ['forward', inputs(0.6, 'linear', 'none')],
      ['backward', inputs(-0.3, 'linear', 'none')],
      ['log', inputs(0.9, 'log', 'none')],
    ] as const) {
      const pixels = await renderLobe(input);
      const floor = logFloorOf(input);
      // Halfway to a surface node off the axis: inside the lobe, which is star-shaped
      // about the scattering point, so the lobe covers its pixel.
      for (const [i, j] of [
        [THETA_SEGMENTS / 4, PHI_SEGMENTS / 2],
        [THETA_SEGMENTS / 2, PHI_SEGMENTS / 4],
      ] as const) {
        const node = lobeNode(i, lobeWarp(input.g), input.g < 0);
        const surface = surfacePoint(
          node,
          azimuth(j),
          lobeRadius(hgPhaseSlope(input.g, node), input.scale, floor),
        );
        const inside: Vec3 = [
          0.5 * surface.position[0],
          0.5 * surface.position[1],
          0.5 * surface.position[2],
        ];
        const [r, , b] = rgb(pixels, pixelOf(input, inside));
        expect(r, `g = ${input.g}, node (${i}, ${j})`).toBeGreaterThan(b + 40);
      }
      // The corner is background.
      expect(rgb(pixels, [2, 2])).toEqual([38, 43, 56]);
    }
  });

  it('changes with g, and draws the comparison wireframe only when asked', async () => {
    const forward = await renderLobe(inputs(0.6, 'linear', 'isotropic'));
    const backward = await renderLobe(inputs(-0.3, 'linear', 'isotropic'));
    const none = await renderLobe(inputs(0.6, 'linear', 'none'));
    let changed = 0;
    for (let k = 0; k < forward.length; k++) if (forward[k] !== backward[k]) changed += 1;
    expect(changed / forward.length).toBeGreaterThan(0.05);
    expect(census(forward).blue).toBeGreaterThan(200);
    expect(census(none).blue).toBe(0);
    expect(census(none).orange).toBeGreaterThan(0.03 * WIDTH * HEIGHT);
    // The isotropic sphere's wireframe: its meridian at φ = 0 passes through (0, r, 0).
    const sphereTop = pixelOf(inputs(0.6, 'linear', 'isotropic'), [0, 1 / (4 * Math.PI), 0]);
    let nearTop = 0;
    for (let dy = -2; dy <= 2; dy++)
      for (let dx = -2; dx <= 2; dx++) {
        const [r, , b] = rgb(forward, [sphereTop[0] + dx, sphereTop[1] + dy]);
        if (b > r + 40) nearTop += 1;
      }
    expect(nearTop).toBeGreaterThan(0);
  });
});
