// The hg-lobe widget's 3D lobe and error-versus-time sweep, as pure float64 logic:
// the latitude–longitude grid and the surface r(θ)·ω (src/widgets/hg-lobe/lobe3d.ts)
// against the polar plot's radius mapping and against geometry (unit normals
// perpendicular to the surface), the orbit camera's framing, and the sweep's error
// measure and its exact expectation (de Moivre's binomial mean absolute deviation).
import { describe, expect, it } from 'vitest';
import { hgEval, phaseIsotropic, rayleighEval } from '../../src/reference/phase.ts';
import { logLogSlope } from '../../src/widgets/base/sweep.ts';
import {
  sampleHistogramCpu,
  sampleHistogramCpuInChunks,
} from '../../src/widgets/hg-lobe/cpuBackend.ts';
import {
  DEFAULT_ORBIT,
  MAX_PITCH,
  PHI_SEGMENTS,
  THETA_SEGMENTS,
  azimuth,
  clampOrbit,
  compareLobeVertex,
  hgLobeVertex,
  hgPhaseSlope,
  lobeNode,
  lobeRadius,
  lobeWarp,
  orbitCamera,
  packView,
  project,
  sceneBounds,
  surfacePoint,
  toClip,
  type Vec3,
} from '../../src/widgets/hg-lobe/lobe3d.ts';
import {
  SWEEP_EXPONENTS,
  binomialMeanAbsoluteDeviation,
  expectedHistogramL1,
  hgBinProbabilities,
  histogramL1,
  median,
  polarLayout,
  radiusFor,
  type HgLobeInputs,
} from '../../src/widgets/hg-lobe/model.ts';

function inputs(
  g: number,
  scale: HgLobeInputs['scale'] = 'linear',
  compare: HgLobeInputs['compare'] = 'isotropic',
): HgLobeInputs {
  return { g: Math.fround(g), compare, scale, samplesExponent: 16, sampleCount: 65536, seed: 1 };
}

const G_VALUES = [-0.99, -0.3, 0, 0.6, 0.9, 0.99];
const norm = (v: Vec3): number => Math.hypot(v[0], v[1], v[2]);
const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];

describe('the latitude–longitude grid', () => {
  it('runs from θ = 0 to θ = π with exact complements at the poles, monotone in i, for both peak sides', () => {
    for (const g of G_VALUES) {
      const warp = lobeWarp(g);
      const backward = g < 0;
      const first = lobeNode(0, warp, backward);
      const last = lobeNode(THETA_SEGMENTS, warp, backward);
      expect(first.oneMinusMu).toBeLessThan(1e-30);
      expect(first.mu).toBeCloseTo(1, 15);
      expect(last.onePlusMu).toBeLessThan(1e-30);
      expect(last.mu).toBeCloseTo(-1, 15);
      let previous = -Infinity;
      for (let i = 0; i <= THETA_SEGMENTS; i++) {
        const node = lobeNode(i, warp, backward);
        // 1 − μ + 1 + μ = 2 and (1 − μ)(1 + μ) = sin²θ, to float64 rounding.
        expect(node.oneMinusMu + node.onePlusMu).toBeCloseTo(2, 14);
        expect(node.oneMinusMu * node.onePlusMu).toBeCloseTo(node.sinTheta ** 2, 14);
        expect(node.mu).toBeCloseTo(0.5 * (node.onePlusMu - node.oneMinusMu), 14);
        const theta = Math.atan2(node.sinTheta, node.mu);
        expect(theta).toBeGreaterThan(previous);
        previous = theta;
      }
    }
  });

  it('puts rings closer together at the peak the larger |g| is (the HG peak has width ~(1 − |g|))', () => {
    const firstRing = (g: number): number => Math.acos(lobeNode(1, lobeWarp(g), false).mu);
    expect(firstRing(0)).toBeCloseTo(Math.PI / THETA_SEGMENTS, 12);
    expect(firstRing(0.6)).toBeLessThan(0.5 * firstRing(0));
    expect(firstRing(0.99)).toBeLessThan(firstRing(0.6));
    // The mirrored grid for a backward lobe: ring i of −g is ring N − i of g, mirrored.
    for (const i of [0, 1, 7, 48, 95, 96]) {
      const forward = lobeNode(i, lobeWarp(0.6), false);
      const backward = lobeNode(THETA_SEGMENTS - i, lobeWarp(-0.6), true);
      expect(backward.oneMinusMu).toBeCloseTo(forward.onePlusMu, 14);
      expect(backward.mu).toBeCloseTo(-forward.mu, 14);
    }
  });

  it('has azimuths from −π to π on the unit circle', () => {
    expect(azimuth(0).cos).toBe(-1);
    expect(azimuth(PHI_SEGMENTS / 2)).toEqual({ cos: 1, sin: 0 });
    for (let j = 0; j <= PHI_SEGMENTS; j++) {
      const { cos, sin } = azimuth(j);
      expect(Math.hypot(cos, sin)).toBeCloseTo(1, 15);
    }
  });
});

describe('the surface r(θ)·ω', () => {
  it('has the polar plot’s radius: p on the linear scale, log₁₀ p above the floor on the log scale', () => {
    for (const g of G_VALUES)
      for (const scale of ['linear', 'log'] as const) {
        const input = inputs(g, scale);
        const layout = polarLayout(input, 960, 480);
        for (const i of [0, 5, 30, 48, 77, 96])
          for (const j of [0, 13, 32]) {
            const point = hgLobeVertex(input, layout.logFloor, i, j);
            const node = lobeNode(i, lobeWarp(input.g), input.g < 0);
            const p = hgEval(input.g, node.mu);
            // The polar plot draws radiusFor(p) pixels; at one pixel per unit it is the 3D radius.
            const expected = radiusFor(p, scale, layout) / layout.pixelsPerUnit;
            // hgEval takes μ, the grid the complements: they agree to ~1e-16/(1 − |g|)² relative.
            expect(norm(point.position)).toBeCloseTo(expected, 8);
          }
      }
  });

  it('reaches p(1) straight ahead and p(−1) straight back (physics.md §2.2)', () => {
    for (const g of [-0.3, 0.6, 0.9]) {
      const input = inputs(g);
      const ahead = hgLobeVertex(input, 0, 0, 0).position;
      const back = hgLobeVertex(input, 0, THETA_SEGMENTS, 0).position;
      const gc = input.g;
      expect(ahead[0]).toBeCloseTo((1 + gc) / (4 * Math.PI * (1 - gc) ** 2), 12);
      expect(back[0]).toBeCloseTo(-(1 - gc) / (4 * Math.PI * (1 + gc) ** 2), 12);
    }
  });

  it('has unit normals perpendicular to the surface along θ and φ, pointing outward', () => {
    // Central differences on the continuous grid (i and j need not be integers).
    for (const g of G_VALUES)
      for (const scale of ['linear', 'log'] as const) {
        const input = inputs(g, scale);
        const floor = polarLayout(input, 960, 480).logFloor;
        const at = (i: number, j: number): Vec3 => hgLobeVertex(input, floor, i, j).position;
        for (const i of [3.5, 20.25, 48.5, 80.75])
          for (const j of [5.5, 40.25]) {
            const point = hgLobeVertex(input, floor, i, j);
            if (norm(point.position) === 0) continue; // clamped at the log floor
            expect(norm(point.normal)).toBeCloseTo(1, 12);
            const h = 1e-5;
            const alongTheta = sub(at(i + h, j), at(i - h, j));
            const alongPhi = sub(at(i, j + h), at(i, j - h));
            expect(Math.abs(dot(point.normal, alongTheta)) / norm(alongTheta)).toBeLessThan(1e-6);
            expect(Math.abs(dot(point.normal, alongPhi)) / norm(alongPhi)).toBeLessThan(1e-6);
            // Outward: a star-shaped surface about the origin has n·position > 0.
            expect(dot(point.normal, point.position)).toBeGreaterThan(0);
          }
      }
  });

  it('draws the isotropic sphere of radius 1/(4π) and the Rayleigh peanut, 3(1 + μ²)/(16π)', () => {
    for (let i = 0; i <= THETA_SEGMENTS; i += 8) {
      const sphere = compareLobeVertex(inputs(0.6, 'linear', 'isotropic'), 0, i, 7);
      expect(norm(sphere.position)).toBeCloseTo(phaseIsotropic(), 15);
      // A sphere's normal is its radial direction.
      for (let k = 0; k < 3; k++)
        expect(sphere.normal[k]!).toBeCloseTo(sphere.position[k]! / phaseIsotropic(), 12);
      const peanut = compareLobeVertex(inputs(0.6, 'linear', 'rayleigh'), 0, i, 7);
      const mu = lobeNode(i, 0, false).mu;
      expect(norm(peanut.position)).toBeCloseTo(rayleighEval(mu), 15);
    }
  });

  it('gives the log radius no slope where it is clamped at the floor', () => {
    const node = lobeNode(60, 0, false);
    const slope = hgPhaseSlope(0.99, node);
    expect(lobeRadius(slope, 'log', Math.log10(slope.p) + 1)).toEqual({ r: 0, drdmu: 0 });
    const point = surfacePoint(node, azimuth(3), { r: 0, drdmu: 0 });
    expect(norm(point.normal)).toBeCloseTo(1, 15);
  });
});

describe('the scene and the orbit camera', () => {
  it('puts the beam behind the lobes and the forward guide past them', () => {
    for (const g of G_VALUES)
      for (const scale of ['linear', 'log'] as const) {
        const input = inputs(g, scale, 'rayleigh');
        const floor = polarLayout(input, 960, 480).logFloor;
        const bounds = sceneBounds(input, floor);
        const reach = hgLobeVertex(input, floor, 0, 0).position[0];
        const back = hgLobeVertex(input, floor, THETA_SEGMENTS, 0).position[0];
        expect(bounds.forwardExtent).toBeGreaterThan(reach);
        expect(bounds.arrow.tailX).toBeLessThan(Math.min(back, 0));
        expect(bounds.arrow.headBaseX).toBeLessThan(0);
        expect(bounds.arrow.headBaseX).toBeGreaterThan(bounds.arrow.tailX);
        expect(bounds.arrow.headRadius).toBeGreaterThan(bounds.arrow.shaftRadius);
      }
  });

  it('frames every fit point inside the picture, tightly, from any orbit', () => {
    for (const g of [-0.3, 0.6, 0.99])
      for (const orbit of [DEFAULT_ORBIT, { yaw: 0, pitch: 0 }, { yaw: 2.5, pitch: -1.2 }])
        for (const aspect of [16 / 9, 1, 0.6]) {
          const input = inputs(g);
          const bounds = sceneBounds(input, 0);
          const camera = orbitCamera(bounds, orbit, aspect);
          let largest = 0;
          for (const point of bounds.fitPoints) {
            const [x, y, z, w] = toClip(camera.viewProjection, point);
            expect(w).toBeGreaterThan(0);
            expect(z / w).toBeGreaterThan(0);
            expect(z / w).toBeLessThan(1);
            largest = Math.max(largest, Math.abs(x / w), Math.abs(y / w));
            // The matrix is f32: 1e-6 covers its rounding.
            expect(Math.abs(x / w)).toBeLessThanOrEqual(0.9 + 1e-6);
            expect(Math.abs(y / w)).toBeLessThanOrEqual(0.9 + 1e-6);
          }
          // Tight: some point reaches the 90% margin.
          expect(largest).toBeGreaterThan(0.89);
        }
  });

  it('shows the beam travelling left to right from the default view, with the light above', () => {
    const input = inputs(0.6);
    const bounds = sceneBounds(input, 0);
    const camera = orbitCamera(bounds, DEFAULT_ORBIT, 16 / 9);
    const tail = project(camera.viewProjection, [bounds.arrow.tailX, 0, 0], 1600, 900);
    const tip = project(camera.viewProjection, [bounds.forwardExtent, 0, 0], 1600, 900);
    expect(tip.x).toBeGreaterThan(tail.x);
    expect(camera.light[1]).toBeGreaterThan(0.5);
    expect(norm(camera.light)).toBeCloseTo(1, 12);
  });

  it('wraps the yaw and keeps the pitch within ±85°', () => {
    expect(clampOrbit({ yaw: 7, pitch: 3 })).toEqual({ yaw: 7 - 2 * Math.PI, pitch: MAX_PITCH });
    expect(clampOrbit({ yaw: -0.5, pitch: -3 }).pitch).toBe(-MAX_PITCH);
  });

  it('packs the uniform in the kernel’s LobeView layout', () => {
    const input = inputs(-0.3, 'log', 'rayleigh');
    const bounds = sceneBounds(input, -2);
    const camera = orbitCamera(bounds, DEFAULT_ORBIT, 2);
    const words = packView(input, -2, bounds, camera);
    const f32 = new Float32Array(words.buffer);
    expect(words.byteLength).toBe(128);
    expect([...f32.subarray(0, 16)]).toEqual([...camera.viewProjection]);
    expect(f32[19]).toBe(input.g);
    expect(words[23]).toBe(1);
    expect(f32[24]).toBe(Math.fround(bounds.arrow.tailX));
    expect(f32[28]).toBe(-2);
    expect(words[29]).toBe(2);
    expect(f32[31]).toBe(Math.fround(0.3));
  });
});

describe('the error-versus-time sweep', () => {
  it('de Moivre’s E|X − Np| equals the sum over the binomial distribution', () => {
    for (const n of [1, 2, 3, 10, 37])
      for (const p of [0.001, 0.05, 0.3, 0.5, 0.77, 0.999]) {
        let brute = 0;
        let logProbability = n * Math.log1p(-p); // k = 0
        for (let k = 0; k <= n; k++) {
          if (k > 0) logProbability += Math.log(((n - k + 1) / k) * (p / (1 - p)));
          brute += Math.exp(logProbability) * Math.abs(k - n * p);
        }
        expect(binomialMeanAbsoluteDeviation(n, p)).toBeCloseTo(brute, 12);
      }
    expect(binomialMeanAbsoluteDeviation(100, 0)).toBe(0);
    expect(binomialMeanAbsoluteDeviation(100, 1)).toBe(0);
  });

  it('the expected L1 error approaches √(2/(πN))·Σ√(P(1 − P)) and falls as N^(−½) over 2¹⁰ … 2²⁰', () => {
    const probabilities = hgBinProbabilities(Math.fround(0.6));
    const n = 2 ** 20;
    let asymptote = 0;
    for (const p of probabilities) asymptote += Math.sqrt(p * (1 - p));
    asymptote *= Math.sqrt(2 / (Math.PI * n));
    expect(expectedHistogramL1(probabilities, n) / asymptote).toBeCloseTo(1, 2);
    const counts = SWEEP_EXPONENTS.map((k) => 2 ** k);
    const slope = logLogSlope(
      counts,
      counts.map((c) => expectedHistogramL1(probabilities, c)),
    );
    expect(slope).toBeCloseTo(-0.5, 2);
    // Where most bins are nearly empty (g = 0.99 at small N) the law bends: the slope is shallower.
    const peaked = hgBinProbabilities(Math.fround(0.99));
    expect(
      logLogSlope(
        [2 ** 10, 2 ** 11],
        [expectedHistogramL1(peaked, 2 ** 10), expectedHistogramL1(peaked, 2 ** 11)],
      )!,
    ).toBeGreaterThan(-0.5);
  });

  it('measures the L1 distance of a histogram to the bin probabilities, and the twin’s meets its expectation', () => {
    const probabilities = hgBinProbabilities(Math.fround(0.6));
    expect(histogramL1([3, 1], [0.75, 0.25], 4)).toBe(0);
    expect(histogramL1([4, 0], [0.75, 0.25], 4)).toBeCloseTo(0.5, 15);
    // 2^16 samples of the CPU twin, three seeds: their mean L1 is within 10% of the expectation
    // (each L1 sums 64 nearly independent |deviations|; its relative spread is ≈ 3%).
    const n = 2 ** 16;
    const errors = [1, 2, 3].map((seed) =>
      histogramL1(sampleHistogramCpu(Math.fround(0.6), n, seed).bins, probabilities, n),
    );
    const mean = errors.reduce((a, b) => a + b, 0) / errors.length;
    expect(Math.abs(mean / expectedHistogramL1(probabilities, n) - 1)).toBeLessThan(0.1);
  });

  it('the chunked CPU sampler gives the one-pass histogram', async () => {
    const whole = sampleHistogramCpu(Math.fround(-0.3), 10_000, 5);
    const chunked = await sampleHistogramCpuInChunks(Math.fround(-0.3), 10_000, 5, 3000);
    expect([...chunked.bins]).toEqual([...whole.bins]);
    expect(chunked.sumMu).toBeCloseTo(whole.sumMu, 9);
    expect(chunked.sumMuSquared).toBeCloseTo(whole.sumMuSquared, 9);
  });

  it('takes the median of the repetitions', () => {
    expect(median([3, 1, 2])).toBe(2);
    expect(median([4, 1, 3, 2])).toBe(2.5);
  });
});
