// Divides by the hero's pdf only, f/p_h: the other channels' densities are ignored (hero
// sampling without MIS), right only when all three pdfs are equal.
fn heroWeight(p0: f32, p1: f32, p2: f32, hero: u32) -> f32 {
  let p = vec3f(p0, p1, p2)[hero];
  return select(0.0, 1.0 / p, p > 0.0);
}
