// Right for physical inputs, but exceeds 1 for negative σt or d.
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  return exp(-sigmaT * d);
}
