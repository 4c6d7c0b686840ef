// An endless loop: the grader must stop it and say so.
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  var t = 1.0;
  loop {
    t = t * 0.5;
    // Never true (t stays ≥ 0); the return after the loop is for naga (Firefox),
    // which rejects a function that ends in a loop.
    if (t < 0.0) {
      break;
    }
  }
  return t;
}
