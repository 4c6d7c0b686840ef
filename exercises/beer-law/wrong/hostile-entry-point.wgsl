fn transmittance(sigmaT: f32, d: f32) -> f32 {
  return exp(-max(sigmaT * d, 0.0));
}
@compute @workgroup_size(1)
fn main() {
}
