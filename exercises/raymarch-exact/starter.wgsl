// Ray marching the transmittance of a heterogeneous medium, with the exact
// per-step update. extinction(sigma0, amplitude, s) is provided: σt(s) in 1/m at
// distance s (m) along the ray. Use `steps` equal steps over [0, d], sampling σt
// at the midpoint of each step.
fn marchTransmittance(sigma0: f32, amplitude: f32, d: f32, steps: u32) -> f32 {
  var transmittance = 1.0;
  // Your loop here.
  return transmittance;
}
