// A compute kernel that evaluates the density-grid functions of shaders/medium.wesl
// on the GPU, for tests/shaders/medium.test.ts and tests/stability/medium.test.ts.
// The grid's samples are an r32float 3D texture, which neither the table harness nor
// runCompute (storage buffers only) can bind, so this dispatch creates the textures
// with createTexture/writeTexture and binds them through an explicit layout shared by
// all entry points (one per function), whichever bindings each one uses. The twin*
// helpers call the float64 twins on the same grids and rays, for the comparisons.
import { gpuCore } from '../../src/gpu/core.ts';
import { withErrorScopes } from '../../src/gpu/errors.ts';
import { linkKernel } from '../../src/gpu/link.ts';
import {
  gridMajorantAlongRay,
  gridOpticalDepthConstant,
  gridSegmentInBounds,
  makeDensityGrid,
  type DensityGrid,
  type DensityGridData,
  type GridMajorantSegment,
  type Vec3,
} from '../../src/reference/medium.ts';
import { nodeDevice } from './nodeGpu.ts';
import { SHADER_LIBRARY } from './shaderLibrary.ts';

const KERNEL = `
import package::medium::{DensityGrid, gridDensityTrilinear, gridMajorantLookup, gridMajorantAlongRay, gridMajorantAlongSegment, gridOpticalDepthConstant, gridSegmentInBounds};
@group(0) @binding(0) var<storage, read> grids: array<u32>;
@group(0) @binding(1) var<storage, read> records: array<f32>;
@group(0) @binding(2) var<storage, read_write> outputs: array<u32>;
@group(0) @binding(3) var volume: texture_3d<f32>;
@group(0) @binding(4) var majorantVolume: texture_3d<f32>;

fn gridAt(o: u32) -> DensityGrid {
  return DensityGrid(
    vec3u(grids[o], grids[o + 1u], grids[o + 2u]),
    vec3f(bitcast<f32>(grids[o + 3u]), bitcast<f32>(grids[o + 4u]), bitcast<f32>(grids[o + 5u])),
    vec3f(bitcast<f32>(grids[o + 6u]), bitcast<f32>(grids[o + 7u]), bitcast<f32>(grids[o + 8u])),
    bitcast<f32>(grids[o + 9u]));
}
fn vecAt(o: u32) -> vec3f { return vec3f(records[o], records[o + 1u], records[o + 2u]); }

@compute @workgroup_size(64) fn density(@builtin(global_invocation_id) id: vec3u) {
  if (id.x >= arrayLength(&outputs)) { return; }
  outputs[id.x] = bitcast<u32>(gridDensityTrilinear(gridAt(0u), volume, vecAt(3u * id.x)));
}
@compute @workgroup_size(64) fn majorantLookup(@builtin(global_invocation_id) id: vec3u) {
  if (id.x >= arrayLength(&outputs)) { return; }
  outputs[id.x] = bitcast<u32>(gridMajorantLookup(gridAt(10u), majorantVolume, vecAt(3u * id.x)));
}
@compute @workgroup_size(64) fn majorantAlongRay(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (3u * i >= arrayLength(&outputs)) { return; }
  let o = 8u * i;
  let r = gridMajorantAlongRay(gridAt(10u), majorantVolume, vecAt(o), vecAt(o + 3u), records[o + 6u], records[o + 7u]);
  outputs[3u * i] = bitcast<u32>(r.majorant);
  outputs[3u * i + 1u] = r.cellsVisited;
  outputs[3u * i + 2u] = r.capped;
}
@compute @workgroup_size(64) fn majorantAlongSegment(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (3u * i >= arrayLength(&outputs)) { return; }
  let o = 8u * i;
  let r = gridMajorantAlongSegment(gridAt(10u), majorantVolume, vecAt(o), vecAt(o + 3u), vec2f(records[o + 6u], records[o + 7u]));
  outputs[3u * i] = bitcast<u32>(r.majorant);
  outputs[3u * i + 1u] = r.cellsVisited;
  outputs[3u * i + 2u] = r.capped;
}
@compute @workgroup_size(64) fn opticalDepthConstant(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= arrayLength(&outputs)) { return; }
  let o = 8u * i;
  outputs[i] = bitcast<u32>(gridOpticalDepthConstant(gridAt(0u), volume, vecAt(o), vecAt(o + 3u), records[o + 6u], records[o + 7u]));
}
@compute @workgroup_size(64) fn segmentInBounds(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (2u * i >= arrayLength(&outputs)) { return; }
  let o = 8u * i;
  let s = gridSegmentInBounds(gridAt(0u), vecAt(o), vecAt(o + 3u), records[o + 6u], records[o + 7u]);
  outputs[2u * i] = bitcast<u32>(s.x);
  outputs[2u * i + 1u] = bitcast<u32>(s.y);
}
`;

type EntryPoint =
  | 'density'
  | 'majorantLookup'
  | 'majorantAlongRay'
  | 'majorantAlongSegment'
  | 'opticalDepthConstant'
  | 'segmentInBounds';
const OUTPUT_WORDS: Record<EntryPoint, number> = {
  density: 1,
  majorantLookup: 1,
  majorantAlongRay: 3,
  majorantAlongSegment: 3,
  opticalDepthConstant: 1,
  segmentInBounds: 2,
};

export interface Ray {
  origin: Vec3;
  direction: Vec3;
  tMin: number;
  tMax: number;
}

/** A placeholder for the texture an entry point does not read. */
export const EMPTY_GRID: DensityGridData = makeDensityGrid([0], [1, 1, 1], [0, 0, 0], [1, 1, 1], 0);

function packGrid(grid: DensityGrid, words: Uint32Array, offset: number): void {
  const floats = new Float32Array(words.buffer);
  grid.dimensions.forEach((n, a) => (words[offset + a] = n >>> 0));
  grid.boundsMin.forEach((v, a) => (floats[offset + 3 + a] = v));
  grid.boundsMax.forEach((v, a) => (floats[offset + 6 + a] = v));
  floats[offset + 9] = grid.densityScale;
}

function volumeTexture(device: GPUDevice, data: DensityGridData): GPUTexture {
  const [nx, ny, nz] = data.grid.dimensions.map((n) => Math.max(n, 1)) as [number, number, number];
  const texture = device.createTexture({
    size: [nx, ny, nz],
    dimension: '3d',
    format: 'r32float',
    usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST,
  });
  // A grid with a zero dimension still needs a 1×1×1 texture; it holds 0.
  const values = new Float32Array(nx * ny * nz);
  if (data.volume.length === values.length) values.set(data.volume);
  device.queue.writeTexture({ texture }, values, { bytesPerRow: nx * 4, rowsPerImage: ny }, [
    nx,
    ny,
    nz,
  ]);
  return texture;
}

let pipelines: Promise<{
  layout: GPUBindGroupLayout;
  byEntry: Map<string, GPUComputePipeline>;
}> | null = null;

async function gridPipelines(device: GPUDevice) {
  pipelines ??= (async () => {
    const code = await linkKernel(SHADER_LIBRARY, KERNEL);
    const storage = (type: GPUBufferBindingType): GPUBindGroupLayoutEntry['buffer'] => ({ type });
    const texture: GPUBindGroupLayoutEntry['texture'] = {
      sampleType: 'unfilterable-float',
      viewDimension: '3d',
    };
    const layout = device.createBindGroupLayout({
      entries: [
        { binding: 0, visibility: GPUShaderStage.COMPUTE, buffer: storage('read-only-storage') },
        { binding: 1, visibility: GPUShaderStage.COMPUTE, buffer: storage('read-only-storage') },
        { binding: 2, visibility: GPUShaderStage.COMPUTE, buffer: storage('storage') },
        { binding: 3, visibility: GPUShaderStage.COMPUTE, texture },
        { binding: 4, visibility: GPUShaderStage.COMPUTE, texture },
      ],
    });
    const byEntry = await withErrorScopes(device, 'grid kernel', () => {
      const core = gpuCore(device);
      const pipelineLayout = core.pipelineLayout([layout]);
      return new Map(
        Object.keys(OUTPUT_WORDS).map((entryPoint) => [
          entryPoint,
          core.computePipeline({ code, entryPoint, layout: pipelineLayout }),
        ]),
      );
    });
    return { layout, byEntry };
  })();
  return pipelines;
}

/** Runs one entry point over `records` (f32 words each) and returns its u32 output words. */
async function runGridKernel(
  entryPoint: EntryPoint,
  fine: DensityGridData,
  majorant: DensityGridData,
  records: readonly (readonly number[])[],
): Promise<Uint32Array> {
  const device = await nodeDevice();
  const { layout, byEntry } = await gridPipelines(device);
  const outputWords = records.length * OUTPUT_WORDS[entryPoint];
  const gridWords = new Uint32Array(20);
  packGrid(fine.grid, gridWords, 0);
  packGrid(majorant.grid, gridWords, 10);
  const recordData = new Float32Array(Math.max(records.flat().length, 1));
  recordData.set(records.flat());
  const made: (GPUBuffer | GPUTexture)[] = [];
  const buffer = (data: ArrayBufferView | null, size: number, usage: number): GPUBuffer => {
    const b = device.createBuffer({ size, usage });
    if (data) device.queue.writeBuffer(b, 0, data.buffer, data.byteOffset, data.byteLength);
    made.push(b);
    return b;
  };
  try {
    const readBack = await withErrorScopes(device, `grid kernel "${entryPoint}"`, () => {
      const fineTexture = volumeTexture(device, fine);
      const majorantTexture = volumeTexture(device, majorant);
      made.push(fineTexture, majorantTexture);
      const STORAGE = GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST;
      const output = buffer(
        null,
        outputWords * 4,
        GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC,
      );
      const read = buffer(null, outputWords * 4, GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST);
      const bindGroup = device.createBindGroup({
        layout,
        entries: [
          { binding: 0, resource: { buffer: buffer(gridWords, gridWords.byteLength, STORAGE) } },
          { binding: 1, resource: { buffer: buffer(recordData, recordData.byteLength, STORAGE) } },
          { binding: 2, resource: { buffer: output } },
          { binding: 3, resource: fineTexture.createView() },
          { binding: 4, resource: majorantTexture.createView() },
        ],
      });
      const encoder = device.createCommandEncoder();
      const pass = encoder.beginComputePass();
      pass.setPipeline(byEntry.get(entryPoint) as GPUComputePipeline);
      pass.setBindGroup(0, bindGroup);
      pass.dispatchWorkgroups(Math.ceil(records.length / 64));
      pass.end();
      encoder.copyBufferToBuffer(output, 0, read, 0, outputWords * 4);
      device.queue.submit([encoder.finish()]);
      return read;
    });
    await readBack.mapAsync(GPUMapMode.READ);
    const words = new Uint32Array(readBack.getMappedRange().slice(0));
    readBack.unmap();
    return words;
  } finally {
    for (const resource of made) resource.destroy();
  }
}

const asF32 = (words: Uint32Array): number[] => Array.from(new Float32Array(words.buffer));
const rayRecord = (r: Ray): number[] => [...r.origin, ...r.direction, r.tMin, r.tMax];
/** A vector as the GPU sees it. */
export const f32Vec = (v: readonly number[]): Vec3 => [
  Math.fround(v[0] ?? 0),
  Math.fround(v[1] ?? 0),
  Math.fround(v[2] ?? 0),
];
export const f32Ray = (r: Ray): Ray => ({
  origin: f32Vec(r.origin),
  direction: f32Vec(r.direction),
  tMin: Math.fround(r.tMin),
  tMax: Math.fround(r.tMax),
});

export async function gpuDensity(
  fine: DensityGridData,
  points: readonly Vec3[],
): Promise<number[]> {
  return asF32(await runGridKernel('density', fine, EMPTY_GRID, points));
}
export async function gpuMajorantLookup(
  majorant: DensityGridData,
  points: readonly Vec3[],
): Promise<number[]> {
  return asF32(await runGridKernel('majorantLookup', EMPTY_GRID, majorant, points));
}
export async function gpuMajorantAlongRay(
  majorant: DensityGridData,
  rays: readonly Ray[],
): Promise<GridMajorantSegment[]> {
  const words = await runGridKernel('majorantAlongRay', EMPTY_GRID, majorant, rays.map(rayRecord));
  const floats = new Float32Array(words.buffer);
  return rays.map((_, i) => ({
    majorant: floats[3 * i] ?? NaN,
    cellsVisited: words[3 * i + 1] ?? NaN,
    capped: words[3 * i + 2] ?? NaN,
  }));
}
/** gridMajorantAlongSegment on the GPU, for rays whose [tMin, tMax] lies in the majorant grid's box. */
export async function gpuMajorantAlongSegment(
  majorant: DensityGridData,
  rays: readonly Ray[],
): Promise<GridMajorantSegment[]> {
  const words = await runGridKernel(
    'majorantAlongSegment',
    EMPTY_GRID,
    majorant,
    rays.map(rayRecord),
  );
  const floats = new Float32Array(words.buffer);
  return rays.map((_, i) => ({
    majorant: floats[3 * i] ?? NaN,
    cellsVisited: words[3 * i + 1] ?? NaN,
    capped: words[3 * i + 2] ?? NaN,
  }));
}
export async function gpuOpticalDepthConstant(
  fine: DensityGridData,
  rays: readonly Ray[],
): Promise<number[]> {
  return asF32(await runGridKernel('opticalDepthConstant', fine, EMPTY_GRID, rays.map(rayRecord)));
}
export async function gpuSegmentInBounds(
  fine: DensityGridData,
  rays: readonly Ray[],
): Promise<[number, number][]> {
  const floats = asF32(
    await runGridKernel('segmentInBounds', fine, EMPTY_GRID, rays.map(rayRecord)),
  );
  return rays.map((_, i) => [floats[2 * i] ?? NaN, floats[2 * i + 1] ?? NaN]);
}

/** gridMajorantAlongRay of the twin over the majorant grid, for one ray. */
export const twinMajorantAlongRay = (majorant: DensityGridData, r: Ray): GridMajorantSegment =>
  gridMajorantAlongRay(majorant.grid, majorant.volume, r.origin, r.direction, r.tMin, r.tMax);
/** gridOpticalDepthConstant of the twin over the fine grid, for one ray. */
export const twinOpticalDepthConstant = (fine: DensityGridData, r: Ray): number =>
  gridOpticalDepthConstant(fine.grid, fine.volume, r.origin, r.direction, r.tMin, r.tMax);
/** gridSegmentInBounds of the twin for the fine grid's box, for one ray. */
export const twinSegmentInBounds = (fine: DensityGridData, r: Ray): [number, number] =>
  gridSegmentInBounds(fine.grid, r.origin, r.direction, r.tMin, r.tMax);
