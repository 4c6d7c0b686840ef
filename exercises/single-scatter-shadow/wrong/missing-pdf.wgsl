// Missing pdf division: the samples are summed without their weight h = len/N.
fn singleScatter(sigmaS: f32, sigmaA: f32, a: f32, b: f32, len: f32, steps: u32) -> f32 {
  let sigmaT = sigmaS + sigmaA;
  let h = len / f32(steps);
  var radiance = 0.0;
  for (var i = 0u; i < steps; i++) {
    let t = (f32(i) + 0.5) * h;
    radiance += sigmaS * exp(-sigmaT * t) * exp(-sigmaT * (a + b * t));
  }
  return radiance;
}
