// One cosine-weighted ray's estimate of the irradiance transmitted into a translucent object
// (chapter 12, eq:room-irradiance): the ray arrives with radiance L at angle θ to the normal
// (cosTheta = cos θ ∈ [0, 1]) on a smooth boundary of relative index η, and was drawn with
// density cos θ / π. fresnelDielectric(cosThetaI, eta) (chapter 11's Fresnel reflectance) is provided.
fn irradianceRay(radiance: f32, cosTheta: f32, eta: f32) -> f32 {
  // Your code here.
  return 0.0;
}
