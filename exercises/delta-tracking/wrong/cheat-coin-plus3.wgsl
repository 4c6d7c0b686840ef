// Cheat with a bias: the closed-form coin of cheat-closed-form.wgsl with probability
// 1.03·exp(−τ), a relative bias of +3 %.
fn deltaTracking(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, state: ptr<function, u32>) -> f32 {
  let tau = sigma0 * (d + amplitude * (1.0 - cos(3.0 * d)) / 3.0);
  return select(0.0, 1.0, rngNextFloat(state) < 1.03 * exp(-tau));
}
