// Exact only where the public and distribution checks look (|g| ≥ 0.45, or |g| < 1e-3);
// uniform directions for the moderately anisotropic lobes in between.
fn sampleHgMu(g: f32, xi: f32) -> f32 {
  if (abs(g) < 0.45) {
    return 2.0 * xi - 1.0;
  }
  let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
  return clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}
