// A second bind group the harness never binds.
@group(1) @binding(0) var<storage, read> table: array<f32>;
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  return table[0];
}
