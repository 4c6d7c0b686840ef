// Single scattering along a view ray of length len through a homogeneous medium
// (σs, σa in 1/m), lit by a distant light whose shadow ray from the point at
// distance t crosses a + b·t metres of the medium. Phase function × irradiance = 1.
// March `steps` equal steps, one shadow ray at each step's midpoint.
fn singleScatter(sigmaS: f32, sigmaA: f32, a: f32, b: f32, len: f32, steps: u32) -> f32 {
  var radiance = 0.0;
  // Your loop here.
  return radiance;
}
