// Importance sampling of Henyey–Greenstein: map a uniform ξ ∈ [0, 1) to a cosine μ
// distributed with the density 2π p_HG(μ; g) on [−1, 1], by inverting the CDF.
// μ must increase with ξ: ξ = 0 gives μ = −1 and ξ → 1 gives μ → 1.
fn sampleHgMu(g: f32, xi: f32) -> f32 {
  // Your code here.
  return 2.0 * xi - 1.0;
}
