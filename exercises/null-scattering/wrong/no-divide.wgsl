// Forgets the probability of the choice: a null vertex multiplies by σn/σ̄ only, so the
// expected factor is P_n·σn/σ̄ and the mean is biased low.
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
    let sigmaN = sigmaMaj - extinction(sigma0, amplitude, t);
    if (rngNextFloat(state) >= nullProbability) {
      weight = 0.0;
      break;
    }
    weight *= sigmaN / sigmaMaj;
  }
  return weight;
}
