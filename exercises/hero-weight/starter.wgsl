// Hero-wavelength sampling of a chromatic medium: a path's distances were drawn with the
// extinction of one channel, the hero (index `hero`, chosen uniformly among 0, 1, 2), and
// p0, p1, p2 are the densities with which each channel's own sampling would have produced
// the same path (pdfs of the path, ≥ 0). Return the factor F such that f_c · F estimates
// every channel c: the one-sample multiple-importance-sampling weight of the hero's
// technique (balance heuristic) divided by the probability density of having drawn this path.
// Return 0 when no channel could have produced the path (p0 = p1 = p2 = 0).
fn heroWeight(p0: f32, p1: f32, p2: f32, hero: u32) -> f32 {
  // Your code here.
  return 0.0;
}
