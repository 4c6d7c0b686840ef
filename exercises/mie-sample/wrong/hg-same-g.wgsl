// Henyey–Greenstein with each table's mean cosine g instead of the table: the right g
// (0.805, 0.00003, 0.242, 0.881, the tables' exact ∫ μ p dω) and the right end points, but
// not the Mie lobe, whose forward peak is narrower and whose back is flatter than HG's.
// Sampled in the table's orientation, ξ = 0 forward (HG's inverse CDF at 1 − ξ).
fn sampleMieMu(table: u32, xi: f32) -> f32 {
  var g = 0.0;
  if (table == 0u) {
    g = 0.805460572;
  } else if (table == 1u) {
    g = 0.0000258728287;
  } else if (table == 2u) {
    g = 0.241844326;
  } else {
    g = 0.880519211;
  }
  let v = 1.0 - clamp(xi, 0.0, 1.0);
  if (abs(g) < 1e-3) {
    return 2.0 * v - 1.0;
  }
  let t = (1.0 - g * g) / (1.0 - g + 2.0 * g * v);
  return clamp((1.0 + g * g - t * t) / (2.0 * g), -1.0, 1.0);
}
