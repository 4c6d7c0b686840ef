// The attribute name hidden behind a comment between '@' and 'group'.
@/* still an attribute */group(0) @ binding(3) var<uniform> k: vec4f;
fn transmittance(sigmaT: f32, d: f32) -> f32 {
  return exp(-max(sigmaT * d, 0.0)) * k.x;
}
