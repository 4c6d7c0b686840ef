// Forgets the shadow ray: the light is not attenuated on its way to the sample.
fn singleScatter(sigmaS: f32, sigmaA: f32, a: f32, b: f32, len: f32, steps: u32) -> f32 {
  let sigmaT = sigmaS + sigmaA;
  let h = len / f32(steps);
  var radiance = 0.0;
  for (var i = 0u; i < steps; i++) {
    let t = (f32(i) + 0.5) * h;
    radiance += sigmaS * exp(-sigmaT * t) * h;
  }
  return radiance;
}
