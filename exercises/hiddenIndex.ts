// The hidden checks of every exercise, for the command line and the tests only:
// nothing the page bundles may import this file.
import type { CheckSpec } from '../src/grading/exercise.ts';

type Loader = () => Promise<{ HIDDEN_CHECKS: readonly CheckSpec[] }>;

export const HIDDEN_LOADERS: Record<string, Loader> = {
  'beer-law': () => import('./beer-law/hidden.ts'),
  'hg-eval': () => import('./hg-eval/hidden.ts'),
  'hg-sample': () => import('./hg-sample/hidden.ts'),
  'mie-sample': () => import('./mie-sample/hidden.ts'),
  'raymarch-exact': () => import('./raymarch-exact/hidden.ts'),
  'delta-tracking': () => import('./delta-tracking/hidden.ts'),
  'single-scatter-shadow': () => import('./single-scatter-shadow/hidden.ts'),
  'hash-encoding': () => import('./hash-encoding/hidden.ts'),
  'dipole-rd': () => import('./dipole-rd/hidden.ts'),
  'hero-weight': () => import('./hero-weight/hidden.ts'),
  'null-scattering': () => import('./null-scattering/hidden.ts'),
  'room-irradiance': () => import('./room-irradiance/hidden.ts'),
};
