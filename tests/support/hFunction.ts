// Chandrasekhar's H-function for isotropic scattering, for the analytic benchmark of
// physics.md §7 C: the reflectance of a matched, isotropically scattering half-space
// lit by a collimated beam at cosine μ0 is R(μ0) = 1 − H(μ0)·√(1 − ϖ). H solves
// 1/H(μ) = √(1 − ϖ) + (ϖ/2)∫₀¹ μ′H(μ′)/(μ + μ′) dμ′, iterated to a fixed point on a
// 400-point Gauss–Legendre grid (as physics.md §7 describes; it reproduces H(1; 0.9) =
// 1.8500985168, see tests/reference/slab.test.ts). The iteration converges slowly as
// ϖ → 1; the tests use ϖ = 0.9.

/** n-point Gauss–Legendre nodes and weights on [0, 1] (Newton on P_n). */
export function gaussLegendre(n: number): { nodes: number[]; weights: number[] } {
  const nodes: number[] = [];
  const weights: number[] = [];
  for (let i = 1; i <= n; i++) {
    let z = Math.cos((Math.PI * (i - 0.25)) / (n + 0.5));
    let derivative = 1;
    for (let iteration = 0; iteration < 100; iteration++) {
      let p1 = 1;
      let p2 = 0;
      for (let j = 1; j <= n; j++) {
        const p3 = p2;
        p2 = p1;
        p1 = ((2 * j - 1) * z * p2 - (j - 1) * p3) / j;
      }
      derivative = (n * (z * p1 - p2)) / (z * z - 1);
      const step = p1 / derivative;
      z -= step;
      if (Math.abs(step) < 1e-16) break;
    }
    nodes.push((1 - z) / 2);
    weights.push(1 / ((1 - z * z) * derivative * derivative));
  }
  return { nodes, weights };
}

/** H(μ; ϖ) for isotropic scattering with single-scattering albedo ϖ ∈ (0, 1). */
export function chandrasekharH(albedo: number): (mu: number) => number {
  const { nodes, weights } = gaussLegendre(400);
  const root = Math.sqrt(1 - albedo);
  let h = nodes.map(() => 1);
  const inverse = (mu: number, values: readonly number[]): number => {
    let integral = 0;
    for (let k = 0; k < nodes.length; k++)
      integral += (weights[k]! * nodes[k]! * values[k]!) / (mu + nodes[k]!);
    return root + (albedo / 2) * integral;
  };
  for (let iteration = 0; iteration < 2000; iteration++) {
    const next = nodes.map((mu) => 1 / inverse(mu, h));
    const change = Math.max(...next.map((v, k) => Math.abs(v - h[k]!)));
    h = next;
    if (change < 1e-14) break;
  }
  return (mu) => 1 / inverse(mu, h);
}

/** Directional-hemispherical reflectance R(μ0) = 1 − H(μ0)√(1 − ϖ) (physics.md §7 C). */
export function halfSpaceReflectance(albedo: number, mu0: number): number {
  return 1 - chandrasekharH(albedo)(mu0) * Math.sqrt(1 - albedo);
}
