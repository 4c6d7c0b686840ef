// Keeps the integrand's cos θ that the cosine-weighted density already cancelled.
fn irradianceRay(radiance: f32, cosTheta: f32, eta: f32) -> f32 {
  let c = clamp(cosTheta, 0.0, 1.0);
  return 3.14159265 * c * (1.0 - fresnelDielectric(c, eta)) * radiance;
}
