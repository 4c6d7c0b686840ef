// Divides by the density's cos θ but forgets its 1/π: every estimate is π times too small.
fn irradianceRay(radiance: f32, cosTheta: f32, eta: f32) -> f32 {
  return (1.0 - fresnelDielectric(clamp(cosTheta, 0.0, 1.0), eta)) * radiance;
}
