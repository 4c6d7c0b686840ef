// Scenes with analytic answers for the renderer tests (CPU twin and GPU alike).
import { mieTabulatePhase, miePhase, phaseTabulatedEval } from '../../src/reference/mie.ts';
import { hgEval } from '../../src/reference/phase.ts';
import { singleScatterHomogeneousSlab } from '../../src/reference/scatter.ts';
import { simpson } from './quadrature.ts';

const f32 = Math.fround;

// §5 slab: y ∈ [0, 1], camera inside at depth d0 looking straight down, light at θ from the
// vertical; at view distance t the light path is (d0 + t)/cos θ, so a = d0/cos θ, b = 1/cos θ.
const THETA = (40 * Math.PI) / 180;
const DEPTH = 0.3;
const SIGMA_A = [0.2, 0.1, 0.4];
const SIGMA_S = [0.8, 0.5, 1.2];
const IRRADIANCE = [1, 2, 0.5];
const G = 0.3;

/** μ = −wo·wi of the slab's single scattering: camera straight down, light at θ. */
export const SLAB_SCATTERING_COSINE = -Math.cos(THETA);

/**
 * The physics.md §5 setting as a scene: a homogeneous (or constant-grid) slab, camera
 * inside; HG with g = 0.3 unless `phase` is given.
 */
export function slabScene(
  kind: 'homogeneous' | 'grid',
  order: number | 'unlimited' = 1,
  phase: Record<string, unknown> = { type: 'henyey-greenstein', g: G },
) {
  return {
    image: { width: 4, height: 4 },
    samplesPerPixel: 64,
    seed: 11,
    scatteringOrder: order,
    camera: {
      type: 'orthographic',
      position: [0, 1 - DEPTH, 0],
      direction: [0, -1, 0],
      up: [0, 0, -1],
      width: 0.5,
      height: 0.5,
    },
    media: [
      {
        type: kind,
        bounds: { type: 'box', min: [-1000, 0, -1000], max: [1000, 1, 1000] },
        sigmaA: SIGMA_A,
        sigmaS: SIGMA_S,
        phase,
        ...(kind === 'grid' ? { grid: { dimensions: [1, 1, 1], density: [1] } } : {}),
      },
    ],
    lights: [
      {
        type: 'directional',
        direction: [Math.sin(THETA), -Math.cos(THETA), 0],
        irradiance: IRRADIANCE,
      },
    ],
  };
}

/**
 * physics.md §5 closed form per channel, on the f32 inputs the renderer sees; `phase` is
 * p(SLAB_SCATTERING_COSINE) in 1/sr (the default scene's HG g = 0.3).
 */
export function slabExact(channel: number, phase = hgEval(f32(G), SLAB_SCATTERING_COSINE)): number {
  const cos = Math.cos(THETA);
  return singleScatterHomogeneousSlab(
    f32(SIGMA_S[channel]!),
    f32(SIGMA_A[channel]!),
    phase,
    f32(IRRADIANCE[channel]!),
    DEPTH / cos,
    1 / cos,
    1 - DEPTH,
  );
}

/** Bohren & Huffman's sphere (x = 3, m = 1.55) as a scene phase function: a smooth lobe. */
export const BH_SPHERE = { type: 'mie', sizeParameter: 3, indexReal: 1.55, indexImaginary: 0 };

/**
 * BH_SPHERE's phase function from the Mie series at the slab's scattering angle, and the
 * deviation of its 513-node table (src/reference/mie.ts mieTabulatePhase, which the
 * renderer reads) from it there: interpolation and normalisation of the table.
 */
export function bhSphereSlabPhase(): { series: number; tableError: number } {
  const m = { n: BH_SPHERE.indexReal, kappa: BH_SPHERE.indexImaginary };
  const series = miePhase(BH_SPHERE.sizeParameter, m, SLAB_SCATTERING_COSINE);
  const table = phaseTabulatedEval(
    mieTabulatePhase(BH_SPHERE.sizeParameter, m),
    SLAB_SCATTERING_COSINE,
  );
  return { series, tableError: Math.abs(table - series) };
}

/**
 * The systematic allowance of a BH_SPHERE slab render against slabExact with the series
 * phase: the table's relative error at that angle (L ∝ p) plus `arithmetic` (relative; f32
 * or f64 rounding), times the largest channel.
 */
export function mieSlabSystematic(arithmetic: number): number {
  const { series, tableError } = bhSphereSlabPhase();
  const largest = Math.max(...[0, 1, 2].map((c) => slabExact(c, series)));
  return ((tableError / series) * 1.01 + arithmetic) * largest;
}

const H = 0.5;
const SIGMA_T = [0.3, 0.6, 1.2];
const ALBEDO = 0.7;
const INTENSITY = [2, 1, 3];

/** A point light 0.5 m off the camera ray in a large homogeneous medium, one tiny pixel. */
export const pointLightScene = {
  image: { width: 1, height: 1 },
  samplesPerPixel: 4096,
  seed: 3,
  scatteringOrder: 1,
  camera: {
    type: 'orthographic',
    position: [0, 0, 0],
    direction: [0, 0, -1],
    up: [0, 1, 0],
    width: 1e-5,
    height: 1e-5,
  },
  media: [
    {
      type: 'homogeneous',
      bounds: { type: 'box', min: [-20, -20, -20], max: [20, 20, 1] },
      sigmaA: SIGMA_T.map((s) => (1 - ALBEDO) * s),
      sigmaS: SIGMA_T.map((s) => ALBEDO * s),
    },
  ],
  lights: [{ type: 'point', position: [0, H, -1], intensity: INTENSITY }],
};

/** L = ∫₀²⁰ e^{−σt t} σs p I e^{−σt r}/r² dt, r² = h² + (t − 1)²; Simpson on pieces around the peak. */
export const pointLightExact = (c: number): number => {
  const sigmaS = f32(f32(ALBEDO * SIGMA_T[c]!));
  const sigmaTotal = f32(f32((1 - ALBEDO) * SIGMA_T[c]!) + sigmaS);
  const integrand = (t: number): number => {
    const r2 = H * H + (t - 1) ** 2;
    return (
      (Math.exp(-sigmaTotal * t) *
        sigmaS *
        (1 / (4 * Math.PI)) *
        f32(INTENSITY[c]!) *
        Math.exp(-sigmaTotal * Math.sqrt(r2))) /
      r2
    );
  };
  return [
    [0, 0.5],
    [0.5, 1.5],
    [1.5, 4],
    [4, 20],
  ].reduce((sum, [a, b]) => sum + simpson(integrand, a!, b!, 20000), 0);
};
