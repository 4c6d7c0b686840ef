// The `1 − σΔs` update (forward Euler) instead of exp(−σΔs) (physics.md §1.1).
fn marchTransmittance(sigma0: f32, amplitude: f32, d: f32, steps: u32) -> f32 {
  let h = d / f32(steps);
  var transmittance = 1.0;
  for (var i = 0u; i < steps; i++) {
    transmittance *= 1.0 - extinction(sigma0, amplitude, (f32(i) + 0.5) * h) * h;
  }
  return transmittance;
}
