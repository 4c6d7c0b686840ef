// Image files for renders: PFM (linear float RGB, the format's own convention of rows
// stored BOTTOM row first, little-endian, scale −1) and a tone map to 8-bit sRGB for
// PNG previews. Images in memory are RGB interleaved with row 0 at the TOP (the
// camera's pixel convention, shaders/camera.wesl).

/** Encodes a width × height RGB image (row 0 at the top) as a little-endian PFM. */
export function encodePfm(width: number, height: number, rgb: ArrayLike<number>): Uint8Array {
  const header = new TextEncoder().encode(`PF\n${width} ${height}\n-1.0\n`);
  const bytes = new Uint8Array(header.length + 12 * width * height);
  bytes.set(header);
  const view = new DataView(bytes.buffer, header.length);
  let offset = 0;
  // PFM stores the bottom row first: write rows from the last (bottom) to row 0 (top).
  for (let y = height - 1; y >= 0; y--) {
    for (let k = 3 * y * width; k < 3 * (y + 1) * width; k++) {
      view.setFloat32(offset, rgb[k] ?? 0, true);
      offset += 4;
    }
  }
  return bytes;
}

/** Decodes a PFM written by encodePfm (or any RGB PFM) into row-0-at-the-top RGB. */
export function decodePfm(bytes: Uint8Array): { width: number; height: number; rgb: Float32Array } {
  let position = 0;
  const token = (): string => {
    while (/\s/.test(String.fromCharCode(bytes[position] ?? 32)) && position < bytes.length)
      position++;
    let text = '';
    while (position < bytes.length && !/\s/.test(String.fromCharCode(bytes[position]!)))
      text += String.fromCharCode(bytes[position++]!);
    return text;
  };
  if (token() !== 'PF') throw new Error('not an RGB PFM (expected "PF")');
  const width = Number(token());
  const height = Number(token());
  const scale = Number(token());
  position++; // the single whitespace character after the scale
  if (!(width > 0 && height > 0 && Number.isFinite(scale) && scale !== 0))
    throw new Error('malformed PFM header');
  const little = scale < 0;
  const view = new DataView(bytes.buffer, bytes.byteOffset + position);
  const rgb = new Float32Array(3 * width * height);
  let offset = 0;
  for (let y = height - 1; y >= 0; y--)
    for (let k = 3 * y * width; k < 3 * (y + 1) * width; k++) {
      rgb[k] = view.getFloat32(offset, little);
      offset += 4;
    }
  return { width, height, rgb };
}

/** The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1]. */
export function srgbEncode(linear: number): number {
  const x = Math.min(Math.max(linear, 0), 1);
  return x <= 0.0031308 ? 12.92 * x : 1.055 * x ** (1 / 2.4) - 0.055;
}

/**
 * Tone map for previews: radiance × 2^exposure, clamped to [0, 1], sRGB-encoded to 8
 * bits; returns RGBA8 (alpha 255), row 0 at the top.
 */
export function toneMapRgba8(
  width: number,
  height: number,
  rgb: ArrayLike<number>,
  exposure = 0,
): Uint8Array {
  const scale = 2 ** exposure;
  const out = new Uint8Array(4 * width * height);
  for (let i = 0; i < width * height; i++) {
    for (let c = 0; c < 3; c++)
      out[4 * i + c] = Math.round(255 * srgbEncode(scale * (rgb[3 * i + c] ?? 0)));
    out[4 * i + 3] = 255;
  }
  return out;
}
