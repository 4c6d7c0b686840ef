// The cosine convention of pbrt (cos θ = −μ): the right sampler, but μ returned with the
// wrong sign, which mirrors every lobe. Only the near-Rayleigh lobe, symmetric in μ, keeps
// its distribution; every point case is mirrored.
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
  let d = a + sqrt(max(0.0, a * a + (b - a) * (a + b) * r));
  var s = r;
  if (d > 0.0) {
    s = clamp(r * (a + b) / d, 0.0, 1.0);
  }
  let mu0 = 1.0 - tableOneMinusMu(table, lo);
  let mu1 = 1.0 - tableOneMinusMu(table, lo + 1u);
  return -(mu0 + s * (mu1 - mu0));
}
