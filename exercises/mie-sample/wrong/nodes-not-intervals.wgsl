// Off by one the other way: the bisection runs over the nodes (hi = MIE_TABLE_NODES), so
// ξ = 1 = C_K finds k = K, the "interval" after the last node, which has no mass; with
// no guard on the mass and no clamp, r = 0/0 is NaN and so is μ. Right for every ξ < 1.
fn sampleMieMu(table: u32, xi: f32) -> f32 {
  let u = clamp(xi, 0.0, 1.0);
  var lo = 0u;
  var hi = MIE_TABLE_NODES;
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
  let r = (u - c0) / mass;
  let a = tablePdf(table, lo);
  let b = tablePdf(table, lo + 1u);
  let d = a + sqrt(max(0.0, a * a + (b - a) * (a + b) * r));
  var s = r;
  if (d > 0.0) {
    s = r * (a + b) / d;
  }
  let mu0 = 1.0 - tableOneMinusMu(table, lo);
  let mu1 = 1.0 - tableOneMinusMu(table, lo + 1u);
  return mu0 + s * (mu1 - mu0);
}
