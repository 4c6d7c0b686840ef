// The Henyey–Greenstein phase function p(μ; g) in sr⁻¹, where μ is the cosine of the
// angle between the incoming direction of travel and the scattered one and g ∈ (−1, 1)
// is the mean cosine (g > 0 scatters forward).
fn hgPhase(g: f32, mu: f32) -> f32 {
  // Your code here.
  return 0.0;
}
