// An endless loop: the grader must stop it and say so.
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  var t = 1.0;
  loop {
    t = t * 0.5;
  }
}
