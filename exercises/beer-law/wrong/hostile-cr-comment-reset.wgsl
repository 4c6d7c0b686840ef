fn transmittance(sigmaT: f32, d: f32) -> f32 {
  var t = 1.0;
  loop {
    // keep going    sbg_iterations = 0u;
    t = t * 0.5;
    if (t < 0.0) { break; }
  }
  return t;
}
