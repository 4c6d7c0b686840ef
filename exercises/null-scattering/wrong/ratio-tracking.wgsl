// Ratio tracking: ignores the given P_n (takes every collision as null, P_n = 1) and
// multiplies σn/σ̄. Unbiased everywhere, but its mean square is ratio tracking's, not that
// of the estimator with the P_n asked for.
fn nullScattering(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, nullProbability: f32, state: ptr<function, u32>) -> f32 {
  if (sigmaMaj <= 0.0) {
    return 1.0;
  }
  var t = 0.0;
  var weight = 1.0;
  loop {
    t += -log(1.0 - rngNextFloat(state)) / sigmaMaj;
    if (t >= d) {
      break;
    }
    weight *= 1.0 - extinction(sigma0, amplitude, t) / sigmaMaj;
  }
  return weight;
}
