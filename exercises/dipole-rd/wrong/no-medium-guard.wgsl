// Correct formula without the "no medium" guard: σt' = 0 divides by zero (NaN).
fn dipoleRd(sigmaSPrime: f32, sigmaA: f32, eta: f32, r: f32) -> f32 {
  let st = sigmaSPrime + sigmaA;
  let alpha = sigmaSPrime / st;
  let sigmaTr = sqrt(3.0 * sigmaA * st);
  let fdr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
  let boundary = (1.0 + fdr) / (1.0 - fdr);
  let zr = 1.0 / st;
  let zv = zr * (1.0 + 4.0 * boundary / 3.0);
  let dr = sqrt(r * r + zr * zr);
  let dv = sqrt(r * r + zv * zv);
  let real = zr * (1.0 + sigmaTr * dr) * exp(-sigmaTr * dr) / (dr * dr * dr);
  let imageSource = zv * (1.0 + sigmaTr * dv) * exp(-sigmaTr * dv) / (dv * dv * dv);
  return alpha / (4.0 * 3.14159265) * (real + imageSource);
}
