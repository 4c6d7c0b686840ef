// A correct solution saved by a Windows editor: UTF-8 byte-order mark and CR LF.
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  let tau = max(sigmaT * d, 0.0);
  return exp(-tau);
}
