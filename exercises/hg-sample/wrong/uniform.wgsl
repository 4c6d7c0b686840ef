// A uniform sampler: its pdf 1/(4π) would be self-consistent, but it is not HG.
fn sampleHgMu(g: f32, xi: f32) -> f32 {
  return 2.0 * xi - 1.0;
}
