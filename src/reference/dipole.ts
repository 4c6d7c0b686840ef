// Float64 twin of shaders/dipole.wesl (physics.md §6): the classic dipole (§6.1), the
// better dipole (§6.2) and the Christensen–Burley profile (§6.3). Units as in the
// shader: coefficients in 1/L, lengths in L, profiles in 1/L² for any one length unit L
// (the Jensen et al. 2001 table is per millimetre).
//
// Written from the formulas, not from the shader: the profiles divide by d³ directly
// (float64 has the range), the better dipole's fluence term is the plain difference of
// its two sources (float64 keeps enough digits for the radii the tests use, and the
// tests check the shader's stable form against it), its total takes the α' = 1 limit
// 4AD by a branch instead of a stable quotient, and the Fresnel moments come from the
// adaptive quadrature of src/reference/fresnel.ts. The domain conventions (no medium,
// α' = 0, the σt' range, saturation of profile values at the largest f32) are shared,
// because the tests compare the two there.
//
// Units do not matter (σ → kσ, r → r/k: α', A and totals unchanged, profiles × k²), so no
// coefficient or length is clamped on its own; float64 forms the squares and cubes
// directly for any f32 inputs.
import { fresnelMoment } from './fresnel.ts';
import { F32_MAX } from './transmittance.ts';

/** Same conventions as the shader (see the constants of shaders/dipole.wesl). */
export const DIPOLE_MIN_EXTINCTION = 2 ** -120;
export const DIPOLE_MAX_EXTINCTION = 2 ** 120;
export const DIPOLE_FIT_MIN_ETA = 0.5;
export const DIPOLE_FIT_MAX_ETA = 2.5;
export const BURLEY_MIN_RADIUS_FRACTION = 1e-6;
/** A Burley shape length below the smallest normal f32 is no spread. */
const BURLEY_MIN_SHAPE_LENGTH = 2 ** -126;

/** Same fields as the WGSL struct DipoleParameters. */
export interface DipoleParameters {
  albedoPrime: number;
  sigmaTPrime: number;
  sigmaTr: number;
  zr: number;
  zv: number;
  boundaryA: number;
}

/** Same fields as the WGSL struct BetterDipoleParameters (zv signed, negative). */
export interface BetterDipoleParameters {
  albedoPrime: number;
  sigmaTr: number;
  diffusion: number;
  zr: number;
  zv: number;
  cPhi: number;
  cE: number;
}

const clamp = (x: number, lo: number, hi: number): number => Math.min(Math.max(x, lo), hi);
const nonNegative = (x: number): number => (x > 0 ? x : 0);
const capF32 = (x: number): number => Math.min(x, F32_MAX);

/**
 * σs' and σa (negative counting as 0) as the shader's domain sees them: null when σt' is
 * below DIPOLE_MIN_EXTINCTION (no medium), and both scaled by one factor when σt' exceeds
 * DIPOLE_MAX_EXTINCTION (a change of units, which keeps α').
 */
function dipoleCoefficients(sigmaSPrime: number, sigmaA: number): [number, number] | null {
  const sp = nonNegative(sigmaSPrime);
  const sa = nonNegative(sigmaA);
  const st = sp + sa;
  if (!(st >= DIPOLE_MIN_EXTINCTION)) return null;
  const scale = st > DIPOLE_MAX_EXTINCTION ? DIPOLE_MAX_EXTINCTION / st : 1;
  return [sp * scale, sa * scale];
}

/** Jensen et al. 2001 fit for η ≥ 1, pbrt-v2's external-side fit for η < 1 (physics.md §6.1, §9 row 23). */
export function fresnelDiffuseReflectanceFit(eta: number): number {
  const e = clamp(eta, DIPOLE_FIT_MIN_ETA, DIPOLE_FIT_MAX_ETA);
  if (e < 1) return -0.4399 + 0.7099 / e - 0.3319 / e ** 2 + 0.0636 / e ** 3;
  return -1.44 / e ** 2 + 0.71 / e + 0.668 + 0.0636 * e;
}

/** A = (1 + F_dr)/(1 − F_dr) with the fit (physics.md §6.1). */
export function dipoleBoundary(eta: number): number {
  const fdr = fresnelDiffuseReflectanceFit(eta);
  return (1 + fdr) / (1 - fdr);
}

/** σt', α', σtr, z_r, z_v and A of the classic dipole (physics.md §6.1). */
export function dipoleParameters(
  sigmaSPrime: number,
  sigmaA: number,
  eta: number,
): DipoleParameters {
  const boundaryA = dipoleBoundary(eta);
  const coefficients = dipoleCoefficients(sigmaSPrime, sigmaA);
  if (coefficients === null)
    return { albedoPrime: 0, sigmaTPrime: 0, sigmaTr: 0, zr: 0, zv: 0, boundaryA };
  const [sp, sa] = coefficients;
  const sigmaTPrime = sp + sa;
  const zr = 1 / sigmaTPrime;
  return {
    albedoPrime: sp / sigmaTPrime,
    sigmaTPrime,
    sigmaTr: Math.sqrt(3 * sa * sigmaTPrime),
    zr,
    // z_v = z_r + 4AD with D = 1/(3σt') (§6.1).
    zv: zr + (4 * boundaryA) / (3 * sigmaTPrime),
    boundaryA,
  };
}

/** √(r² + z²), capped at the largest f32 (float64 forms the squares without overflow). */
export function dipoleDistance(r: number, z: number): number {
  return capF32(Math.hypot(r, z));
}

/** z(1 + σd)e^{−σd}/d³ with d = √(r² + z²); 0 for z ≤ 0; capped at the largest f32. */
export function dipoleSourceTerm(z: number, sigma: number, r: number): number {
  if (!(z > 0)) return 0;
  const d = Math.hypot(r, z);
  const sd = nonNegative(sigma) * d;
  // e^{−σd} is 0 long before 1 + σd matters; skip the product there (∞·0 for huge σd).
  const attenuation = sd > 800 ? 0 : (1 + sd) * Math.exp(-sd);
  return capF32((z * attenuation) / d ** 3);
}

/** R_d(r) of the classic dipole (physics.md §6.1), in 1/L². */
export function dipoleProfile(p: DipoleParameters, r: number): number {
  if (p.albedoPrime <= 0 || p.zr <= 0) return 0;
  const radius = Math.abs(r);
  return (
    (p.albedoPrime / (4 * Math.PI)) *
    capF32(dipoleSourceTerm(p.zr, p.sigmaTr, radius) + dipoleSourceTerm(p.zv, p.sigmaTr, radius))
  );
}

/**
 * (α'/2)(1 + e^{−(4/3)A s}) e^{−s} with s = √(3(1 − α')) (physics.md §6.1), the α' form.
 * s is taken as σtr·z_r = √(3σa/σt'), equal to √(3(1 − α')) without the cancellation of
 * 1 − α' near α' = 1 (even float64 loses all digits of 1 − α' = 1e-16 there). The shader
 * evaluates the source form (α'/2)(e^{−σtr z_r} + e^{−σtr z_v}).
 */
export function dipoleTotalReflectance(p: DipoleParameters): number {
  if (p.albedoPrime <= 0 || p.zr <= 0) return 0;
  const a = clamp(p.albedoPrime, 0, 1);
  const s = p.sigmaTr * p.zr;
  return (a / 2) * (1 + Math.exp((-4 / 3) * Math.max(p.boundaryA, 0) * s)) * Math.exp(-s);
}

/** ∫_R^∞ R_d 2πr dr = (α'/2)Σ z e^{−σtr d(R)}/d(R) over both sources. */
export function dipoleReflectanceBeyond(p: DipoleParameters, radius: number): number {
  if (p.albedoPrime <= 0 || p.zr <= 0) return 0;
  const r = Math.abs(radius);
  const tail = (z: number): number => {
    const d = Math.hypot(r, z);
    return (z / d) * Math.exp(-p.sigmaTr * d);
  };
  return (p.albedoPrime / 2) * (tail(p.zr) + tail(p.zv));
}

/** (e^{−σa} − e^{−σb})/σ, and its limit b − a at σ = 0. */
export function exponentialDifferenceOverRate(rate: number, near: number, far: number): number {
  const sigma = Math.max(rate, 0);
  const a = Math.max(near, 0);
  const b = Math.max(far, a);
  if (sigma === 0) return b - a;
  // expm1 keeps the digits of 1 − e^{−σ(b−a)} for small σ(b − a).
  return (Math.exp(-sigma * a) * -Math.expm1(-sigma * (b - a))) / sigma;
}

/** Grosjean D, σtr, z_r, z_v, C_φ, C_E of the better dipole with exact Fresnel moments (physics.md §6.2). */
export function betterDipoleParameters(
  sigmaSPrime: number,
  sigmaA: number,
  eta: number,
): BetterDipoleParameters {
  const c1 = fresnelMoment(eta, 1);
  const c2 = fresnelMoment(eta, 2);
  const cPhi = (1 - 2 * c1) / 4;
  const cE = (1 - 3 * c2) / 2;
  const coefficients = dipoleCoefficients(sigmaSPrime, sigmaA);
  if (coefficients === null)
    return { albedoPrime: 0, sigmaTr: 0, diffusion: 0, zr: 0, zv: 0, cPhi, cE };
  const [sp, sa] = coefficients;
  const st = sp + sa;
  const boundaryA = (1 + 3 * c2) / (1 - 2 * c1);
  const diffusion = (2 * sa + sp) / (3 * st * st);
  const zr = 1 / st;
  const zb = 2 * boundaryA * diffusion;
  return {
    albedoPrime: sp / st,
    sigmaTr: Math.sqrt(sa / diffusion),
    diffusion,
    zr,
    zv: -zr - 2 * zb,
    cPhi,
    cE,
  };
}

/** R(r) of the better dipole (physics.md §6.2), in 1/L², in the form printed there. */
export function betterDipoleProfile(p: BetterDipoleParameters, r: number): number {
  if (p.albedoPrime <= 0 || p.zr <= 0) return 0;
  const radius = Math.abs(r);
  const dr = Math.hypot(radius, p.zr);
  const dv = Math.hypot(radius, p.zv);
  const s = p.sigmaTr;
  const real =
    ((p.cE * p.zr * (1 + s * dr)) / dr ** 2 + p.cPhi / p.diffusion) * (Math.exp(-s * dr) / dr);
  const image =
    ((p.cE * p.zv * (1 + s * dv)) / dv ** 2 + p.cPhi / p.diffusion) * (Math.exp(-s * dv) / dv);
  return ((p.albedoPrime * p.albedoPrime) / (4 * Math.PI)) * capF32(real - image);
}

/** Total of the better dipole (physics.md §6.2 [der]); at σtr = 0 the quotient is its limit 4AD. */
export function betterDipoleTotalReflectance(p: BetterDipoleParameters): number {
  if (p.albedoPrime <= 0 || p.zr <= 0) return 0;
  const zv = Math.abs(p.zv);
  const s = p.sigmaTr;
  const current = Math.exp(-s * p.zr) + Math.exp(-s * zv);
  // At σtr = 0 the quotient is its limit |z_v| − z_r = 4AD; near it, expm1 keeps its digits.
  const fluence = s === 0 ? zv - p.zr : (Math.exp(-s * p.zr) * -Math.expm1(-s * (zv - p.zr))) / s;
  return (
    ((p.albedoPrime * p.albedoPrime) / 2) * (p.cE * current + (p.cPhi / p.diffusion) * fluence)
  );
}

/** s = 1.85 − A + 7|A − 0.8|³ (physics.md §6.3, searchlight, mean free path). */
export function burleyShapeSearchlight(albedo: number): number {
  const a = clamp(albedo, 0, 1);
  return 1.85 - a + 7 * Math.abs(a - 0.8) ** 3;
}

/** s = 1.9 − A + 3.5(A − 0.8)² (physics.md §6.3, diffuse surface transmission). */
export function burleyShapeDiffuse(albedo: number): number {
  const a = clamp(albedo, 0, 1);
  return 1.9 - a + 3.5 * (a - 0.8) ** 2;
}

/** s = 3.5 + 100(A − 0.33)⁴ (physics.md §6.3, searchlight, diffuse mean free path). */
export function burleyShapeDmfp(albedo: number): number {
  const a = clamp(albedo, 0, 1);
  return 3.5 + 100 * (a - 0.33) ** 4;
}

/**
 * A(e^{−r/d} + e^{−r/(3d)})/(8πdr), r raised to 1e-6·d (physics.md §6.3, §9 row 19); 0 for
 * d below the smallest normal f32 (no spread); capped at the largest f32.
 */
export function burleyProfile(albedo: number, d: number, r: number): number {
  const a = clamp(albedo, 0, 1);
  if (!(d >= BURLEY_MIN_SHAPE_LENGTH)) return 0;
  const radius = Math.max(Math.abs(r), BURLEY_MIN_RADIUS_FRACTION * d);
  return capF32(
    (a * (Math.exp(-radius / d) + Math.exp(-radius / (3 * d)))) / (8 * Math.PI * d * radius),
  );
}

/** 2πr·R(r) = A(e^{−r/d} + e^{−r/(3d)})/(4d), finite at r = 0; 0 without spread. */
export function burleyRadialDensity(albedo: number, d: number, r: number): number {
  const a = clamp(albedo, 0, 1);
  if (!(d >= BURLEY_MIN_SHAPE_LENGTH)) return 0;
  const radius = Math.abs(r);
  return capF32((a * (Math.exp(-radius / d) + Math.exp(-radius / (3 * d)))) / (4 * d));
}

/** 1 − ¼e^{−r/d} − ¾e^{−r/(3d)} (physics.md §6.3); 1 without spread (d ≤ 0). */
export function burleyRadialCdf(r: number, d: number): number {
  if (!(d >= BURLEY_MIN_SHAPE_LENGTH)) return 1;
  const x = Math.abs(r) / d;
  // 1 − ¼e^{−x} − ¾e^{−x/3} = −¼expm1(−x) − ¾expm1(−x/3): no cancellation near 0.
  return -0.25 * Math.expm1(-x) - 0.75 * Math.expm1(-x / 3);
}
