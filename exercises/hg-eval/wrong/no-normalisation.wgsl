// Forgets the 1/(4π): the lobe has the right shape but integrates to 4π.
fn hgPhase(g: f32, mu: f32) -> f32 {
  let d = (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - mu);
  return (1.0 - g * g) / (d * sqrt(d));
}
