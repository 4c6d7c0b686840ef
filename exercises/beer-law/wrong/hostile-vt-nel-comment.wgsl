fn transmittance(sigmaT: f32, d: f32) -> f32 {
  // vertical tab  sbg_budgetExceeded = 0u;
  // next line  var x = 1.0;
  return exp(-max(sigmaT * d, 0.0)) * x;
}
