// Forgets that the hero is chosen with probability 1/3: divides by p_h, not p_h/3.
fn heroWeight(p0: f32, p1: f32, p2: f32, hero: u32) -> f32 {
  let total = p0 + p1 + p2;
  return select(0.0, 1.0 / total, total > 0.0);
}
