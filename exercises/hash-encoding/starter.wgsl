// Feature `feature` (0 or 1) of level `level` (0 … 7) of Instant-NGP's hash encoding at
// the point p = (x, y, z) of the box [−1, 1]³, with T = tableSize entries per level (a
// power of two). tableFeature(level, entry, feature) reads entry 0 … T − 1 of the level.
fn hashEncodeLevel(x: f32, y: f32, z: f32, level: u32, tableSize: u32, feature: u32) -> f32 {
  // Your code here: N_l, the cell of p and its place in it, the eight vertices'
  // entries (dense or hashed), and their trilinear interpolation.
  return tableFeature(level, 0u, feature);
}
