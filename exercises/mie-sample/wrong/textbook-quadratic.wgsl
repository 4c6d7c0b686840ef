// The textbook root of a·s + (b − a)·s²/2 = r·(a + b)/2, s = (−a + √(a² + (b − a)(a + b) r))/(b − a),
// guarded only against b = a exactly. Where b − a is a rounding error's size relative to a
// (the near-Rayleigh table's middle interval, p_k and p_{k+1} equal to 4e-6), the numerator
// cancels to a few ulps of a and the quotient is noise.
fn sampleMieMu(table: u32, xi: f32) -> f32 {
  let u = clamp(xi, 0.0, 1.0);
  var lo = 0u;
  var hi = MIE_TABLE_INTERVALS;
  for (var step = 0u; step < 8u; step++) {
    if (hi - lo <= 1u) {
      break;
    }
    let mid = (lo + hi) / 2u;
    if (tableCdf(table, mid) <= u) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  let c0 = tableCdf(table, lo);
  let mass = tableCdf(table, lo + 1u) - c0;
  var r = 0.0;
  if (mass > 0.0) {
    r = clamp((u - c0) / mass, 0.0, 1.0);
  }
  let a = tablePdf(table, lo);
  let b = tablePdf(table, lo + 1u);
  var s = r;
  if (b != a) {
    s = clamp((-a + sqrt(max(0.0, a * a + (b - a) * (a + b) * r))) / (b - a), 0.0, 1.0);
  }
  let mu0 = 1.0 - tableOneMinusMu(table, lo);
  let mu1 = 1.0 - tableOneMinusMu(table, lo + 1u);
  return mu0 + s * (mu1 - mu0);
}
