// Importance sampling of a tabulated phase function: map a uniform ξ ∈ [0, 1] to a
// cosine μ distributed as table `table` (0 … 3), by inverting the table's CDF. The
// tables come from the book's Mie solver; read them with tableOneMinusMu(table, k),
// tableOnePlusMu(table, k), tablePdf(table, k) and tableCdf(table, k), k = 0 …
// MIE_TABLE_INTERVALS. The density is linear in μ between nodes, and the CDF runs
// from the forward direction: ξ = 0 gives μ = 1 and ξ = 1 gives μ = −1.
fn sampleMieMu(table: u32, xi: f32) -> f32 {
  // Your code here.
  return 1.0 - 2.0 * xi;
}
