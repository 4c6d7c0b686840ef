// Uses the reflected fraction F instead of the transmitted 1 − F.
fn irradianceRay(radiance: f32, cosTheta: f32, eta: f32) -> f32 {
  return 3.14159265 * fresnelDielectric(clamp(cosTheta, 0.0, 1.0), eta) * radiance;
}
