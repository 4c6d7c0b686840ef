// Uses σt/σ̄ (the real-collision probability of delta tracking) as the weight of a null
// vertex instead of σn/σ̄: the mean is exp(−∫(σ̄ − σt)), not exp(−τ).
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
    let sigmaT = extinction(sigma0, amplitude, t);
    if (rngNextFloat(state) >= nullProbability) {
      weight = 0.0;
      break;
    }
    weight *= sigmaT / (sigmaMaj * nullProbability);
  }
  return weight;
}
