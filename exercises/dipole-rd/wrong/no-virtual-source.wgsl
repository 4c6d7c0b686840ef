// Forgets the virtual source: only the real source below the surface.
fn dipoleRd(sigmaSPrime: f32, sigmaA: f32, eta: f32, r: f32) -> f32 {
  let st = sigmaSPrime + sigmaA;
  if (st <= 0.0) {
    return 0.0;
  }
  let alpha = sigmaSPrime / st;
  let sigmaTr = sqrt(3.0 * sigmaA * st);
  let zr = 1.0 / st;
  let dr = sqrt(r * r + zr * zr);
  return alpha / (4.0 * 3.14159265) * zr * (1.0 + sigmaTr * dr) * exp(-sigmaTr * dr) / (dr * dr * dr);
}
