// The book's static diagrams, by the name a chapter uses in a ```figure NAME``` block.
// Each generator draws from its own geometry parameters (see its module); the build
// calls it once per page (src/book/build/figures.ts).
import type { Diagram } from './svg.ts';
import { beerSlab } from './beer-slab.ts';
import { bssrdfFigure } from './bssrdf.ts';
import { dipoleFigure } from './dipole.ts';
import { nullCollisions } from './null-collisions.ts';
import { nullScatteringPaths } from './null-scattering-paths.ts';
import { rteVolume } from './rte-volume.ts';
import { singleScatterLoops } from './single-scatter-loops.ts';

export const FIGURES: Readonly<Record<string, () => Diagram>> = {
  'beer-slab': () => beerSlab(),
  'rte-volume': () => rteVolume(),
  'null-collisions': () => nullCollisions(),
  'single-scatter-loops': () => singleScatterLoops(),
  bssrdf: () => bssrdfFigure(),
  dipole: () => dipoleFigure(),
  'null-scattering-paths': () => nullScatteringPaths(),
};
