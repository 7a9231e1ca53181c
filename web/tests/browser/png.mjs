// A PNG decoder for the tests' screenshots (8-bit RGB or RGBA, not
// interlaced: what Chromium writes), so that pictures are compared in node
// without a dependency.
import { inflateSync } from 'node:zlib';

/** `{ width, height, pixels }` with `pixels` RGBA bytes, row by row. */
export function decodePng(buf) {
  let width = 0, height = 0, channels = 0;
  const idat = [];
  for (let at = 8; at < buf.length;) {
    const len = buf.readUInt32BE(at);
    const type = buf.toString('latin1', at + 4, at + 8);
    const data = buf.subarray(at + 8, at + 8 + len);
    if (type === 'IHDR') {
      width = data.readUInt32BE(0); height = data.readUInt32BE(4);
      const [depth, color, , , interlace] = data.subarray(8, 13);
      if (depth !== 8 || interlace !== 0 || (color !== 2 && color !== 6)) throw new Error(`unsupported PNG (depth ${depth}, colour ${color})`);
      channels = color === 6 ? 4 : 3;
    } else if (type === 'IDAT') idat.push(data);
    at += 12 + len;
  }
  const raw = inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const out = Buffer.alloc(width * height * 4);
  let prev = Buffer.alloc(stride), cur = Buffer.alloc(stride);
  for (let y = 0; y < height; y++) {
    const filter = raw[y * (stride + 1)];
    const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let i = 0; i < stride; i++) {
      const a = i >= channels ? cur[i - channels] : 0, b = prev[i], c = i >= channels ? prev[i - channels] : 0;
      let p = line[i];
      if (filter === 1) p += a;
      else if (filter === 2) p += b;
      else if (filter === 3) p += (a + b) >> 1;
      else if (filter === 4) {
        const q = a + b - c, pa = Math.abs(q - a), pb = Math.abs(q - b), pc = Math.abs(q - c);
        p += pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      cur[i] = p & 255;
    }
    for (let x = 0; x < width; x++) {
      for (let k = 0; k < 4; k++) out[(y * width + x) * 4 + k] = k < channels ? cur[x * channels + k] : 255;
    }
    [prev, cur] = [cur, prev];
  }
  return { width, height, pixels: out };
}

/** Pixels whose colour differs from `b`'s by more than `tol` in a channel,
 * in the columns from `x0` on and the rows from `y0` on (all: 0, 0). */
export function differing(a, b, tol = 8, x0 = 0, y0 = 0) {
  if (a.width !== b.width || a.height !== b.height) throw new Error('pictures of different sizes');
  let n = 0;
  for (let i = 4 * y0 * a.width; i < a.pixels.length; i += 4) {
    if ((i / 4) % a.width < x0) continue;
    if (Math.abs(a.pixels[i] - b.pixels[i]) > tol || Math.abs(a.pixels[i + 1] - b.pixels[i + 1]) > tol
      || Math.abs(a.pixels[i + 2] - b.pixels[i + 2]) > tol) n++;
  }
  return n;
}
