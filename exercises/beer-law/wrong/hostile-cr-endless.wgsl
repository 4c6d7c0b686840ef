fn transmittance(sigmaT: f32, d: f32) -> f32 {
  var t = exp(-max(sigmaT * d, 0.0));
  // nothing to see here  loop { t = t + 0.0; }
  return t;
}
