// The measured materials of Jensen, Marschner, Levoy and Hanrahan 2001, "A Practical
// Model for Subsurface Light Transport" (physics.md §6.1 table), as presets for the
// dipole module, the slab Monte Carlo and the dipole-profile widget.
//
// UNITS: σs' and σa are per MILLIMETRE, per RGB channel, as the paper measured them
// (transcribed via pbrt-v3/v4 SubsurfaceParameterTable; η from Mitsuba 0.6: 1.3 for all
// but marble, 1.5). With these numbers every length is in mm and every profile R_d(r)
// is per mm²; materialInUnit converts to another length unit.
//
// Chicken1/Chicken2 σa(R): physics.md notes a transcription conflict (pbrt 0.015/0.018
// against Mitsuba 0.6's 0.0015/0.0018); the pbrt values are used, as in physics.md.

export type Rgb = readonly [number, number, number];

export interface SubsurfaceMaterial {
  /** Key, e.g. `skin1`. */
  name: string;
  /** Display name, e.g. `Skin 1`. */
  label: string;
  /** Reduced scattering coefficient σs' = σs(1 − g) per channel, in 1/mm. */
  sigmaSPrime: Rgb;
  /** Absorption coefficient σa per channel, in 1/mm. */
  sigmaA: Rgb;
  /** Relative index of refraction n_material/n_air. */
  eta: number;
}

const material = (
  name: string,
  label: string,
  sigmaSPrime: Rgb,
  sigmaA: Rgb,
  eta = 1.3,
): SubsurfaceMaterial => ({ name, label, sigmaSPrime, sigmaA, eta });

/** The twelve materials of the table, in its order (physics.md §6.1). */
export const JENSEN_2001_MATERIALS: readonly SubsurfaceMaterial[] = [
  material('apple', 'Apple', [2.29, 2.39, 1.97], [0.003, 0.0034, 0.046]),
  material('chicken1', 'Chicken 1', [0.15, 0.21, 0.38], [0.015, 0.077, 0.19]),
  material('chicken2', 'Chicken 2', [0.19, 0.25, 0.32], [0.018, 0.088, 0.2]),
  material('cream', 'Cream', [7.38, 5.47, 3.15], [0.0002, 0.0028, 0.0163]),
  material('ketchup', 'Ketchup', [0.18, 0.07, 0.03], [0.061, 0.97, 1.45]),
  material('marble', 'Marble', [2.19, 2.62, 3.0], [0.0021, 0.0041, 0.0071], 1.5),
  material('potato', 'Potato', [0.68, 0.7, 0.55], [0.0024, 0.009, 0.12]),
  material('skimmilk', 'Skim milk', [0.7, 1.22, 1.9], [0.0014, 0.0025, 0.0142]),
  material('skin1', 'Skin 1', [0.74, 0.88, 1.01], [0.032, 0.17, 0.48]),
  material('skin2', 'Skin 2', [1.09, 1.59, 1.79], [0.013, 0.07, 0.145]),
  material('spectralon', 'Spectralon', [11.6, 20.4, 14.9], [0, 0, 0]),
  material('wholemilk', 'Whole milk', [2.55, 3.21, 3.77], [0.0011, 0.0024, 0.014]),
];

export function findMaterial(name: string): SubsurfaceMaterial | undefined {
  return JENSEN_2001_MATERIALS.find((m) => m.name === name);
}

/**
 * The same material with coefficients per `unitInMm` millimetres (e.g. 1000 for metres,
 * 10 for centimetres): σ scales by unitInMm, so σ·r is unchanged when r is measured in
 * the new unit, and profiles per unit area scale by unitInMm² (physics.md §6.1 hazards).
 */
export function materialInUnit(m: SubsurfaceMaterial, unitInMm: number): SubsurfaceMaterial {
  const scale = (v: Rgb): Rgb => [v[0] * unitInMm, v[1] * unitInMm, v[2] * unitInMm];
  return { ...m, sigmaSPrime: scale(m.sigmaSPrime), sigmaA: scale(m.sigmaA) };
}
