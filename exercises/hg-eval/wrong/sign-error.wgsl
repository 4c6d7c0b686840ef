// Sign error in HG: + 2gμ mirrors the lobe (peaks backwards for g > 0).
fn hgPhase(g: f32, mu: f32) -> f32 {
  let d = 1.0 + g * g + 2.0 * g * mu;
  return 0.0795774715 * (1.0 - g * g) / (d * sqrt(d));
}
