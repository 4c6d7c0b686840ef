// The textbook inverse CDF without the small-|g| branch: right distribution, but
// g = 1e-7 gives μ outside [−1, 1] in f32 (physics.md §9 row 6).
fn sampleHgMu(g: f32, xi: f32) -> f32 {
  let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
  return (1.0 + g * g - s * s) / (2.0 * g);
}
