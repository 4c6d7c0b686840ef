// The classic dipole diffuse reflectance profile R_d(r) (Jensen et al. 2001) in 1/L²,
// from the reduced scattering σs' and absorption σa (1/L), the relative index η and
// the distance r (L) between where light enters and where it leaves.
fn dipoleRd(sigmaSPrime: f32, sigmaA: f32, eta: f32, r: f32) -> f32 {
  // Your code here.
  return 0.0;
}
