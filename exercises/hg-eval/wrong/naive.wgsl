// The textbook formula evaluated directly: right everywhere except where
// 1 + g² − 2gμ cancels in f32 near the forward peak (physics.md §2.5, §9 row 1).
fn hgPhase(g: f32, mu: f32) -> f32 {
  let d = 1.0 + g * g - 2.0 * g * mu;
  return 0.0795774715 * (1.0 - g * g) / pow(d, 1.5);
}
