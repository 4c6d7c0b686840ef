// Clamps σn at 0: under a majorant below σt every null vertex there gives weight 0, and
// so the mean is exp(−∫min(σt, σ̄)): biased high, like delta tracking under a low majorant.
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
    let sigmaN = max(sigmaMaj - extinction(sigma0, amplitude, t), 0.0);
    if (rngNextFloat(state) >= nullProbability) {
      weight = 0.0;
      break;
    }
    weight *= sigmaN / (sigmaMaj * nullProbability);
  }
  return weight;
}
