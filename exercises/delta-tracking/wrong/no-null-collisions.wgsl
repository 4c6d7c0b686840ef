// Treats every tentative collision as real: estimates exp(−σ̄ d) instead of exp(−τ).
fn deltaTracking(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, state: ptr<function, u32>) -> f32 {
  if (sigmaMaj <= 0.0) {
    return 1.0;
  }
  let t = -log(1.0 - rngNextFloat(state)) / sigmaMaj;
  return select(0.0, 1.0, t >= d);
}
