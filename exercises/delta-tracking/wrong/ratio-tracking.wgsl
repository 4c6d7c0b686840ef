// Ratio tracking: unbiased, but returns a weight, not 0 or 1, so its variance is
// lower than T(1 − T). Right mean, wrong estimator for this exercise.
fn deltaTracking(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, state: ptr<function, u32>) -> f32 {
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
