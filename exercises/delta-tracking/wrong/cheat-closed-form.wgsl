// Cheat: τ in closed form for the statement's medium σ0(1 + a sin 3s), then one coin
// with probability exp(−τ). Binary with the right mean on that medium, but no tracking.
fn deltaTracking(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, state: ptr<function, u32>) -> f32 {
  let tau = sigma0 * (d + amplitude * (1.0 - cos(3.0 * d)) / 3.0);
  return select(0.0, 1.0, rngNextFloat(state) < exp(-tau));
}
