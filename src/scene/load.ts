// Loading a validated scene's grid data: inline densities, or a raw float32 file under
// public/ read through a FileReader (Node: nodeFileReader in loadNode.ts; the browser:
// fetch). The grid fills the bounding box of its medium's bounds (a box, or the cube
// around a sphere); its majorant grid (medium.ts gridMajorantBuild) has one cell per
// MAJORANT_BLOCK³ samples. Problems with the data are reported like validation errors,
// naming the field.
import { gridMajorantBuild, makeDensityGrid, type DensityGridData } from '../reference/medium.ts';
import type { BoundsDescription, SceneDescription, Vec3 } from './types.ts';
import { SceneValidationError } from './validate.ts';

/** Samples per majorant cell along each axis. */
export const MAJORANT_BLOCK = 4;

export interface ResolvedGrid {
  /** Index of the grid medium in scene.media. */
  medium: number;
  fine: DensityGridData;
  majorant: DensityGridData;
  /** The largest density of the grid: a majorant everywhere. */
  maxDensity: number;
}

export interface ResolvedScene {
  scene: SceneDescription;
  grid: ResolvedGrid | null;
}

/** Reads a file under public/ by its relative path. */
export type FileReader = (path: string) => Promise<Uint8Array>;

/** The axis-aligned box the medium's grid fills. */
export function boundsBox(bounds: BoundsDescription): [Vec3, Vec3] {
  if (bounds.type === 'box') return [bounds.min, bounds.max];
  const { center: c, radius: r } = bounds;
  return [
    [c[0] - r, c[1] - r, c[2] - r],
    [c[0] + r, c[1] + r, c[2] + r],
  ];
}

/** Resolves the scene's grid medium, if any (reading its file with readFile). */
export async function resolveScene(
  scene: SceneDescription,
  readFile?: FileReader,
): Promise<ResolvedScene> {
  const index = scene.media.findIndex((m) => m.type === 'grid');
  const medium = scene.media[index];
  if (!medium || medium.type !== 'grid') return { scene, grid: null };
  const path = `media[${index}].grid`;
  const [nx, ny, nz] = medium.grid.dimensions;
  const count = nx * ny * nz;
  let values: Float32Array;
  if (medium.grid.file !== undefined) {
    const file = medium.grid.file;
    if (!readFile)
      throw new SceneValidationError([
        `${path}.file = "${file}": this renderer cannot read files; inline the densities`,
      ]);
    let bytes: Uint8Array;
    try {
      bytes = await readFile(file);
    } catch (error) {
      throw new SceneValidationError([
        `${path}.file = "${file}": cannot be read under public/ (${(error as Error).message})`,
      ]);
    }
    if (bytes.byteLength !== 4 * count)
      throw new SceneValidationError([
        `${path}.file = "${file}": holds ${bytes.byteLength} bytes; dimensions ${nx}×${ny}×${nz} need ${4 * count} (float32, x fastest)`,
      ]);
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    values = new Float32Array(count);
    for (let i = 0; i < count; i++) {
      const v = view.getFloat32(4 * i, true);
      if (!(Number.isFinite(v) && v >= 0))
        throw new SceneValidationError([
          `${path}.file = "${file}": density ${i} is ${v}; densities must be finite and ≥ 0`,
        ]);
      values[i] = v;
    }
  } else {
    values = Float32Array.from(medium.grid.density ?? []);
  }
  const [boxMin, boxMax] = boundsBox(medium.bounds);
  const fine = makeDensityGrid(values, [nx, ny, nz], boxMin, boxMax, 1);
  const majorant = gridMajorantBuild(fine.grid, fine.volume, MAJORANT_BLOCK);
  let maxDensity = 0;
  for (const v of fine.volume) maxDensity = Math.max(maxDensity, v);
  return { scene, grid: { medium: index, fine, majorant, maxDensity } };
}
