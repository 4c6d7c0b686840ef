// The three extinction profiles of <sb-beer-law>, fixed in space so that the
// thickness slider selects how much of one medium the beam crosses. All have a
// mean (over their period / layers) of σ̄t = σa + σs; absorption and scattering
// follow the same density, so σa(s)/σt(s) is constant.
//
// The WGSL kernel (shaders/kernels/beer-law.wesl) evaluates the same profiles
// with the library's transmittance module; this file evaluates them with the
// float64 twins, for the CPU fallback and for the error readout.
import {
  GRID1D_MAX_CELLS,
  opticalThicknessGrid1D,
  opticalThicknessHomogeneous,
  opticalThicknessSine,
} from '../../reference/transmittance.ts';

export type ProfileName = 'homogeneous' | 'smooth' | 'layered';

export const PROFILE_IDS: Record<ProfileName, number> = { homogeneous: 0, smooth: 1, layered: 2 };

/** σt(s) = σ̄t·(1 + 0.8·sin(3s)): varies by a factor 9 between crests and troughs. */
export const SMOOTH_PROFILE = { amplitude: 0.8, frequency: 3, phase: 0 } as const;

/** Relative density of 16 layers of 0.625 m (10 m in all); their mean is exactly 1. */
export const LAYER_WEIGHTS: readonly number[] = [
  0.5, 1.5, 0.8, 1.2, 2.0, 0.2, 1.0, 0.8, 1.6, 0.4, 1.1, 0.9, 0.3, 1.7, 1.3, 0.7,
];
export const LAYER_THICKNESS = 0.625;

if (LAYER_WEIGHTS.length !== GRID1D_MAX_CELLS) {
  throw new Error('beer-law layers must fill the 1D grid of the transmittance module');
}

/** Extinction at depth s (1/m). */
export function extinctionAt(profile: ProfileName, meanSigmaT: number, s: number): number {
  switch (profile) {
    case 'homogeneous':
      return meanSigmaT;
    case 'smooth':
      return (
        meanSigmaT *
        (1 +
          SMOOTH_PROFILE.amplitude * Math.sin(SMOOTH_PROFILE.frequency * s + SMOOTH_PROFILE.phase))
      );
    case 'layered': {
      const index = Math.floor(s / LAYER_THICKNESS);
      return meanSigmaT * (LAYER_WEIGHTS[index] ?? 0);
    }
  }
}

/** Optical thickness τ(s0, s1) along the beam (physics.md §1), in float64. */
export function opticalDepth(
  profile: ProfileName,
  meanSigmaT: number,
  s0: number,
  s1: number,
): number {
  switch (profile) {
    case 'homogeneous':
      return opticalThicknessHomogeneous(meanSigmaT, s1 - s0);
    case 'smooth':
      return opticalThicknessSine(
        meanSigmaT,
        SMOOTH_PROFILE.amplitude,
        SMOOTH_PROFILE.frequency,
        SMOOTH_PROFILE.phase,
        s0,
        s1,
      );
    case 'layered':
      return opticalThicknessGrid1D(
        LAYER_WEIGHTS.map((w) => w * meanSigmaT),
        LAYER_WEIGHTS.length,
        LAYER_THICKNESS,
        s0,
        s1,
      );
  }
}
