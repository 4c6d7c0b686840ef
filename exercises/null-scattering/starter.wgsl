// Transmittance through [0, d] of the medium σt(s) = extinction(sigma0, amplitude, s) by the
// null-scattering path integral: tentative collisions at rate sigmaMaj (σ̄); each is a null
// vertex with probability nullProbability (P_n), else a real vertex that ends the shadow path.
// σn = σ̄ − σt may be negative (σ̄ below σt). rngNextFloat(state) returns a uniform in [0, 1).
fn nullScattering(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, nullProbability: f32, state: ptr<function, u32>) -> f32 {
  var t = 0.0;
  var weight = 1.0;
  // Your loop here.
  return weight;
}
