// Float64 twin of shaders/fresnel.wesl: the unpolarised Fresnel reflectance of a
// smooth boundary and its internal hemispherical moments (physics.md §6.1, §6.2).
// Convention: the one stated at the top of shaders/fresnel.wesl — eta is the relative
// index n_t/n_i of the side the light goes to over the side it comes from, and the
// moments are internal (light inside a medium of relative index eta).
//
// Written from the formulas, not from the shader: the reflectance is taken from the
// Fresnel amplitude coefficients in terms of the two angles' sines and cosines, and
// the moments are integrated in μ itself by adaptive Simpson quadrature to 1e-14, with
// the substitution μ = μc + (1 − μc)s² that removes the square-root kink at the
// critical angle (the shader instead changes variable to the outside cosine and uses
// a fixed 16-point Gauss–Legendre rule). The clamps are shared.

/** Same clamps of the relative index as the shader. */
export const FRESNEL_MIN_ETA = 0.015625;
export const FRESNEL_MAX_ETA = 64;

const clamp = (x: number, lo: number, hi: number): number => Math.min(Math.max(x, lo), hi);

/**
 * F = ½(r∥² + r⊥²), with r⊥ = (n_i cos θi − n_t cos θt)/(n_i cos θi + n_t cos θt) and
 * r∥ = (n_t cos θi − n_i cos θt)/(n_t cos θi + n_i cos θt), taking n_i = 1 and n_t = η.
 * Total internal reflection (sin θt ≥ 1) gives 1; η = 1 gives 0 (physics.md §9 row 22).
 */
export function fresnelDielectric(cosThetaI: number, eta: number): number {
  const e = clamp(eta, FRESNEL_MIN_ETA, FRESNEL_MAX_ETA);
  if (e === 1) return 0;
  const cosI = clamp(cosThetaI, 0, 1);
  const sinI = Math.sqrt(Math.max(0, 1 - cosI * cosI));
  const sinT = sinI / e;
  if (sinT >= 1) return 1;
  const cosT = Math.sqrt(1 - sinT * sinT);
  const perpendicular = (cosI - e * cosT) / (cosI + e * cosT);
  const parallel = (e * cosI - cosT) / (e * cosI + cosT);
  return (perpendicular * perpendicular + parallel * parallel) / 2;
}

/** x^k for an integer k ≥ 0, capped at 8 as in the shader. */
export function fresnelIntegerPower(x: number, k: number): number {
  return x ** Math.min(Math.max(Math.trunc(k), 0), 8);
}

/** Adaptive Simpson quadrature of f on [a, b] to an absolute tolerance. */
export function adaptiveSimpson(
  f: (x: number) => number,
  a: number,
  b: number,
  tolerance = 1e-14,
  maxDepth = 40,
): number {
  const step = (
    lo: number,
    hi: number,
    fLo: number,
    fMid: number,
    fHi: number,
    whole: number,
    eps: number,
    depth: number,
  ): number => {
    const mid = (lo + hi) / 2;
    const leftMid = (lo + mid) / 2;
    const rightMid = (mid + hi) / 2;
    const fLeft = f(leftMid);
    const fRight = f(rightMid);
    const left = ((mid - lo) / 6) * (fLo + 4 * fLeft + fMid);
    const right = ((hi - mid) / 6) * (fMid + 4 * fRight + fHi);
    const sum = left + right;
    if (depth <= 0 || Math.abs(sum - whole) <= 15 * eps) return sum + (sum - whole) / 15;
    return (
      step(lo, mid, fLo, fLeft, fMid, left, eps / 2, depth - 1) +
      step(mid, hi, fMid, fRight, fHi, right, eps / 2, depth - 1)
    );
  };
  const fa = f(a);
  const fb = f(b);
  const fm = f((a + b) / 2);
  return step(a, b, fa, fm, fb, ((b - a) / 6) * (fa + 4 * fm + fb), tolerance, maxDepth);
}

/**
 * C_k(η) = ∫₀¹ F_r(μ) μ^k dμ with F_r(μ) = fresnelDielectric(μ, 1/η), the light inside a
 * medium of relative index η (physics.md §6.2). Below the critical cosine μc the
 * reflectance is 1 and the integral is μc^{k+1}/(k+1); above it, μ = μc + (1 − μc)s².
 */
export function fresnelMoment(eta: number, k: number): number {
  const e = clamp(eta, FRESNEL_MIN_ETA, FRESNEL_MAX_ETA);
  if (e === 1) return 0;
  const power = Math.min(Math.max(Math.trunc(k), 0), 8);
  const muCritical = e > 1 ? Math.sqrt(1 - 1 / (e * e)) : 0;
  const totallyReflected = muCritical ** (power + 1) / (power + 1);
  const span = 1 - muCritical;
  const integrand = (s: number): number => {
    const mu = muCritical + span * s * s;
    return fresnelDielectric(mu, 1 / e) * mu ** power * 2 * s * span;
  };
  return totallyReflected + adaptiveSimpson(integrand, 0, 1);
}

/**
 * The exact internal diffuse Fresnel reflectance F_dr(η) = 2∫₀¹ F_r(μ) μ dμ = 2C₁(η), the
 * quantity the Jensen fit approximates (physics.md §6.1 table, "exact internal": 0.444457
 * at η = 1.3). Twin only: the shader uses the fit (shaders/dipole.wesl).
 */
export function fresnelDiffuseReflectanceExact(eta: number): number {
  return 2 * fresnelMoment(eta, 1);
}

/**
 * The exact EXTERNAL diffuse reflectance 2∫₀¹ F(μ; η) μ dμ, light arriving from outside
 * (physics.md §6.1 table, "exact external": 0.061132 at η = 1.3). Twin only.
 */
export function fresnelDiffuseReflectanceExternal(eta: number): number {
  const e = clamp(eta, FRESNEL_MIN_ETA, FRESNEL_MAX_ETA);
  if (e === 1) return 0;
  if (e < 1) return fresnelDiffuseReflectanceExact(1 / e);
  // Seen from outside a denser medium there is no critical angle, but F rises steeply
  // near grazing incidence; μ = s² concentrates the points there.
  return 2 * adaptiveSimpson((s) => fresnelDielectric(s * s, e) * s * s * 2 * s, 0, 1);
}
