// Off-by-one step count: i <= steps marches one step beyond d.
fn marchTransmittance(sigma0: f32, amplitude: f32, d: f32, steps: u32) -> f32 {
  let h = d / f32(steps);
  var transmittance = 1.0;
  for (var i = 0u; i <= steps; i++) {
    transmittance *= exp(-extinction(sigma0, amplitude, (f32(i) + 0.5) * h) * h);
  }
  return transmittance;
}
