// Delta (Woodcock) tracking of the transmittance through [0, d] of the medium
// σt(s) = extinction(sigma0, amplitude, s), with majorant sigmaMaj ≥ σt(s).
// rngNextFloat(state) returns the next uniform number in [0, 1).
// Return 1.0 if the walk leaves the segment, 0.0 if it is absorbed by a real collision.
fn deltaTracking(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, state: ptr<function, u32>) -> f32 {
  var t = 0.0;
  // Your loop here.
  return 1.0;
}
