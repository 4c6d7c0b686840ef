enable f16;
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  return f32(exp(-max(f16(sigmaT) * f16(d), 0.0h)));
}
