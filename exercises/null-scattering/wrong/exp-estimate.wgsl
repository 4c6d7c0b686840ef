// exp(−τ̂) of an unbiased one-point estimate τ̂ = d·σt(ξd): biased high by Jensen's inequality
// (chapter 6, eq:jensen-gap), with a mean square far from the null-scattering estimator's.
fn nullScattering(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, nullProbability: f32, state: ptr<function, u32>) -> f32 {
  let s = rngNextFloat(state) * d;
  return exp(-d * extinction(sigma0, amplitude, s));
}
