// The constants of <sb-rayleigh-sky> that its definition (widget.ts, loaded by every
// page) names in readout labels and the cost line; model.ts re-exports them.

/** The panorama's size in pixels (120° of azimuth, elevation −5° … +85°). */
export const CANVAS_WIDTH = 640;
export const CANVAS_HEIGHT = 480;
/** Step count of the converged float64 reference (view and sun rays). */
export const REFERENCE_STEPS = 1024;
/**
 * The fits use N ≥ 16 only. Below it the sun ray keeps M = 4 samples, so its
 * midpoint error stops falling and the curve flattens (≈ 2–3 % at 20–30° from
 * N = 8 to 16); from N = 16 on, M = N/4 and both rules refine together.
 */
export const FIT_FROM_STEPS = 16;
