// Sign error in the exponent: light grows through the medium.
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  return exp(sigmaT * d);
}
