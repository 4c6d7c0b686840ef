// Delta tracking: ignores the given P_n and takes a collision as null with probability
// σn/σ̄ (clamped to [0, 1]), weight 1. Unbiased under a valid majorant but with another
// variance than the P_n asked for, and biased under a majorant below σt.
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
    if (rngNextFloat(state) * sigmaMaj < extinction(sigma0, amplitude, t)) {
      weight = 0.0;
      break;
    }
  }
  return weight;
}
