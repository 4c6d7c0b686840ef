// Wrong: levels counted from 1, N_l = ⌊4·2^{(l+1)/2}⌋ = 5, 8, 11, … instead of 4, 5, 8, ….
fn hashEncodeLevel(x: f32, y: f32, z: f32, level: u32, tableSize: u32, feature: u32) -> f32 {
  var n = 4u << ((level + 1u) / 2u);
  if ((level + 1u) % 2u == 1u) {
    n = (181u << ((level + 1u) / 2u)) / 32u;
  }
  let u = clamp((vec3f(x, y, z) + 1.0) * 0.5, vec3f(0.0), vec3f(1.0)) * f32(n);
  let base = min(vec3u(floor(u)), vec3u(n - 1u));
  let f = u - vec3f(base);
  let side = n + 1u;
  var sum = 0.0;
  for (var dz = 0u; dz < 2u; dz++) {
    for (var dy = 0u; dy < 2u; dy++) {
      for (var dx = 0u; dx < 2u; dx++) {
        let v = base + vec3u(dx, dy, dz);
        var entry: u32;
        if (side * side * side <= tableSize) {
          entry = v.x + side * (v.y + side * v.z);
        } else {
          entry = (v.x ^ (v.y * 2654435761u) ^ (v.z * 805459861u)) % tableSize;
        }
        let wx = select(1.0 - f.x, f.x, dx == 1u);
        let wy = select(1.0 - f.y, f.y, dy == 1u);
        let wz = select(1.0 - f.z, f.z, dz == 1u);
        sum += wx * wy * wz * tableFeature(level, entry, feature);
      }
    }
  }
  return sum;
}
