// Takes the optical thickness instead of σt and d.
fn transmittance(tau: f32) -> f32 {
  return exp(-max(tau, 0.0));
}
