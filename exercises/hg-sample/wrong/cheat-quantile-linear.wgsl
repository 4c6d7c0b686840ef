// Cheat: exact only at the 21 quantiles ξ = j/20 (the strata of the public test's
// uniforms and its χ² bin edges) and linear in ξ in between. Every public bin gets its
// exact count, but inside a bin μ is uniform instead of Henyey–Greenstein.
fn hgExact(g: f32, xi: f32) -> f32 {
  if (abs(g) < 1e-3) {
    return 2.0 * xi - 1.0;
  }
  let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
  return clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}
fn sampleHgMu(g: f32, xi: f32) -> f32 {
  let x = clamp(xi, 0.0, 1.0) * 20.0;
  let j = min(floor(x), 19.0);
  let lo = hgExact(g, j / 20.0);
  let hi = hgExact(g, (j + 1.0) / 20.0);
  return mix(lo, hi, x - j);
}
