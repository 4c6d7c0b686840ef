// The linearised step 1 − σt d instead of exp(−σt d) (physics.md §1.1).
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  return 1.0 - sigmaT * d;
}
