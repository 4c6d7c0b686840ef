// Float64 twin of shaders/medium.wesl: a 1D medium along a ray, answering σt(s),
// the exact τ(s0, s1) and a majorant on a segment. Same field names as the WGSL
// struct Medium1D; `cells` has at most GRID1D_MAX_CELLS entries.
import {
  GRID1D_MAX_CELLS,
  opticalThicknessGrid1D,
  opticalThicknessHomogeneous,
  opticalThicknessSine,
} from './transmittance.ts';

export const MEDIUM_HOMOGENEOUS = 0;
export const MEDIUM_SINE = 1;
export const MEDIUM_GRID = 2;

export interface Medium1D {
  kind: number;
  sigma0: number;
  amplitude: number;
  frequency: number;
  phase: number;
  cellSize: number;
  cellCount: number;
  cells: readonly number[];
}

export function homogeneousMedium(sigmaT: number): Medium1D {
  return {
    kind: MEDIUM_HOMOGENEOUS,
    sigma0: sigmaT,
    amplitude: 0,
    frequency: 0,
    phase: 0,
    cellSize: 0,
    cellCount: 0,
    cells: [],
  };
}

export function sineMedium(
  sigma0: number,
  amplitude: number,
  frequency: number,
  phase = 0,
): Medium1D {
  return {
    kind: MEDIUM_SINE,
    sigma0,
    amplitude,
    frequency,
    phase,
    cellSize: 0,
    cellCount: 0,
    cells: [],
  };
}

export function gridMedium(cells: readonly number[], cellSize: number): Medium1D {
  if (cells.length > GRID1D_MAX_CELLS)
    throw new Error(`a 1D grid has at most ${GRID1D_MAX_CELLS} cells`);
  return {
    kind: MEDIUM_GRID,
    sigma0: 0,
    amplitude: 0,
    frequency: 0,
    phase: 0,
    cellSize,
    cellCount: cells.length,
    cells,
  };
}

export function mediumExtinction(medium: Medium1D, s: number): number {
  switch (medium.kind) {
    case MEDIUM_SINE: {
      const a = Math.min(Math.max(medium.amplitude, 0), 1);
      return Math.max(medium.sigma0 * (1 + a * Math.sin(medium.frequency * s + medium.phase)), 0);
    }
    case MEDIUM_GRID: {
      if (s < 0 || medium.cellSize <= 0) return 0;
      const index = Math.floor(s / medium.cellSize);
      if (index >= Math.min(medium.cellCount, GRID1D_MAX_CELLS)) return 0;
      return Math.max(medium.cells[index] ?? 0, 0);
    }
    default:
      return Math.max(medium.sigma0, 0);
  }
}

export function mediumOpticalDepth(medium: Medium1D, s0: number, s1: number): number {
  switch (medium.kind) {
    case MEDIUM_SINE:
      return opticalThicknessSine(
        medium.sigma0,
        medium.amplitude,
        medium.frequency,
        medium.phase,
        s0,
        s1,
      );
    case MEDIUM_GRID:
      return opticalThicknessGrid1D(medium.cells, medium.cellCount, medium.cellSize, s0, s1);
    default:
      return opticalThicknessHomogeneous(medium.sigma0, s1 - s0);
  }
}

export function mediumMajorant(medium: Medium1D, s0: number, s1: number): number {
  switch (medium.kind) {
    case MEDIUM_SINE:
      return Math.max(medium.sigma0, 0) * (1 + Math.min(Math.max(medium.amplitude, 0), 1));
    case MEDIUM_GRID: {
      if (medium.cellSize <= 0) return 0;
      let majorant = 0;
      const count = Math.min(medium.cellCount, GRID1D_MAX_CELLS);
      for (let i = 0; i < count; i++) {
        if ((i + 1) * medium.cellSize > s0 && i * medium.cellSize < s1)
          majorant = Math.max(majorant, medium.cells[i] ?? 0);
      }
      return majorant;
    }
    default:
      return Math.max(medium.sigma0, 0);
  }
}
