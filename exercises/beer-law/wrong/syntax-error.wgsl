// A missing semicolon on line 4.
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  let tau = max(sigmaT * d, 0.0);
  let t = exp(-tau)
  return t;
}
