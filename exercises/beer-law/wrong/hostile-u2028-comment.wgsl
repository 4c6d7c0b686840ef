fn transmittance(sigmaT: f32, d: f32) -> f32 {
  var t = exp(-max(sigmaT * d, 0.0));
  // a line separator ends this comment   while (t > -1.0) { t = t * 1.0; }
  return t;
}
