// A Medium1D (shaders/medium.wesl, src/reference/medium.ts) as the tests hand it to
// the GPU: flattened into the eight harness arguments that a wrapper rebuilds into
// the struct, or packed into the storage words of a custom kernel; and the medium as
// the GPU sees it, every coefficient rounded to f32, for the twin's replay.
import type { Medium1D } from '../../src/reference/medium.ts';
import type { Argument, ArgumentType } from './shaderHarness.ts';

/** The struct's array length (GRID1D_MAX_CELLS): shorter `cells` are padded with 0. */
const CELLS = 16;

// A Medium1D crosses the harness as its eight fields; the wrappers rebuild it.
export const MEDIUM_ARGUMENTS: ArgumentType[] = [
  'u32',
  'f32',
  'f32',
  'f32',
  'f32',
  'f32',
  'u32',
  'f32[16]',
];
/** WGSL parameters of a wrapper that takes the eight fields, in MEDIUM_ARGUMENTS order. */
export const MEDIUM_PARAMETERS =
  'kind: u32, sigma0: f32, amplitude: f32, frequency: f32, phase: f32, cellSize: f32, cellCount: u32, cells: array<f32, 16>';
/** The WGSL expression that rebuilds the struct from MEDIUM_PARAMETERS. */
export const MEDIUM_VALUE =
  'package::medium::Medium1D(kind, sigma0, amplitude, frequency, phase, cellSize, cellCount, cells)';

/** The eight harness arguments of a medium (MEDIUM_ARGUMENTS). */
export function mediumArguments(medium: Medium1D): Argument[] {
  const cells = Array.from({ length: CELLS }, (_, i) => medium.cells[i] ?? 0);
  return [
    medium.kind,
    medium.sigma0,
    medium.amplitude,
    medium.frequency,
    medium.phase,
    medium.cellSize,
    medium.cellCount,
    cells,
  ];
}

/** The medium from the first eight harness arguments (what a twin receives). */
export function mediumFromArguments(args: readonly Argument[]): Medium1D {
  const [kind, sigma0, amplitude, frequency, phase, cellSize, cellCount, cells] = args as [
    number,
    number,
    number,
    number,
    number,
    number,
    number,
    number[],
  ];
  return { kind, sigma0, amplitude, frequency, phase, cellSize, cellCount, cells };
}

/** 32-bit words of a Medium1D in a storage buffer: kind, five f32, cellCount, 16 cells. */
export const MEDIUM_WORDS = 7 + CELLS;

/** Writes `medium` into `words` from word `offset` on, in the WGSL struct's layout. */
export function packMedium(words: Uint32Array, offset: number, medium: Medium1D): void {
  const floats = new Float32Array(words.buffer, words.byteOffset, words.length);
  words[offset] = medium.kind;
  floats[offset + 1] = medium.sigma0;
  floats[offset + 2] = medium.amplitude;
  floats[offset + 3] = medium.frequency;
  floats[offset + 4] = medium.phase;
  floats[offset + 5] = medium.cellSize;
  words[offset + 6] = medium.cellCount;
  for (let k = 0; k < CELLS; k++) floats[offset + 7 + k] = medium.cells[k] ?? 0;
}

/** The medium as the GPU sees it (every coefficient rounded to f32). */
export function mediumAsF32(medium: Medium1D): Medium1D {
  return {
    ...medium,
    sigma0: Math.fround(medium.sigma0),
    amplitude: Math.fround(medium.amplitude),
    frequency: Math.fround(medium.frequency),
    phase: Math.fround(medium.phase),
    cellSize: Math.fround(medium.cellSize),
    cells: medium.cells.map(Math.fround),
  };
}
