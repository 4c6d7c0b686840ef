// exp of an averaged (one-sample Monte Carlo) optical depth: τ̂ = σt(ξd)·d is unbiased
// for τ, but E[exp(−τ̂)] > exp(−τ) (Jensen), and the result is not binary.
fn deltaTracking(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, state: ptr<function, u32>) -> f32 {
  let s = rngNextFloat(state) * d;
  return exp(-extinction(sigma0, amplitude, s) * d);
}
