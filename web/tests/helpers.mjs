// Shared by the node tests: the package (target/web/pkg, or $SUBDIV_PKG)
// loaded the way a browser build is loaded, from its wasm bytes; an OBJ
// reader of our own (independent of the library's); OpenSubdiv's points.
import { readFileSync, existsSync } from 'node:fs';
import assert from 'node:assert/strict';
import { fileURLToPath } from 'node:url';

export const root = fileURLToPath(new URL('../../', import.meta.url));
const pkg = process.env.SUBDIV_PKG ?? `${root}target/web/pkg`;
const mod = await import(`${pkg}/subdiv.js`);
await mod.default({ module_or_path: readFileSync(`${pkg}/subdiv_bg.wasm`) });
export const subdiv = mod;

export const fixture = (path) => `${root}tests/fixtures/${path}`;

/** An OBJ text: positions, flat corners, face sizes, and OpenSubdiv's tags
 * (`t crease 2/1/0 a b s`, `t hole n/0/0 f...`; ids from 0). */
export function parseObj(text) {
  const v = [], corners = [], sizes = [], edges = [], sharpness = [], holes = [];
  for (const line of text.split('\n')) {
    const w = line.trim().split(/\s+/);
    if (w[0] === 'v') v.push(+w[1], +w[2], +w[3]);
    else if (w[0] === 'f') {
      const ids = w.slice(1).map((c) => parseInt(c.split('/')[0], 10));
      for (const i of ids) corners.push(i < 0 ? v.length / 3 + i : i - 1);
      sizes.push(ids.length);
    } else if (w[0] === 't' && w[1] === 'crease') {
      edges.push(+w[3], +w[4]);
      sharpness.push(+w[5]);
    } else if (w[0] === 't' && w[1] === 'hole') {
      holes.push(...w.slice(3).map(Number));
    }
  }
  return {
    positions: new Float32Array(v),
    indices: new Uint32Array(corners),
    faceSizes: new Uint32Array(sizes),
    creases: { edges: new Uint32Array(edges), sharpness: new Float32Array(sharpness) },
    holes: new Uint32Array(holes),
  };
}

export const readObj = (path) => parseObj(readFileSync(path, 'utf8'));

/** The points OpenSubdiv wrote (`v x y z` lines) and its face count. */
export function readOsd(path) {
  const text = readFileSync(path, 'utf8');
  const { positions } = parseObj(text);
  const faces = Number(/^# faces (\d+)/m.exec(text)?.[1] ?? NaN);
  return { positions, faces };
}

/** The largest extent of the points (flat xyz). */
function extent(p) {
  let size = 0;
  for (let k = 0; k < 3; k++) {
    let lo = Infinity, hi = -Infinity;
    for (let i = k; i < p.length; i += 3) { lo = Math.min(lo, p[i]); hi = Math.max(hi, p[i]); }
    size = Math.max(size, hi - lo);
  }
  return size;
}

/** Every point of `ours` matched to its own point of `theirs` within `rel`
 * of the mesh's size (any order: OpenSubdiv numbers vertices its own way). */
export function assertSamePointSets(ours, theirs, what, rel = 1e-5) {
  assert.equal(ours.length, theirs.length, `${what}: vertex counts`);
  const tol = rel * Math.max(1, extent(theirs));
  const n = theirs.length / 3, used = new Uint8Array(n);
  for (let i = 0; i < ours.length / 3; i++) {
    let best = -1, bd = Infinity;
    for (let j = 0; j < n; j++) {
      if (used[j]) continue;
      const d = Math.hypot(ours[3 * i] - theirs[3 * j], ours[3 * i + 1] - theirs[3 * j + 1], ours[3 * i + 2] - theirs[3 * j + 2]);
      if (d < bd) { bd = d; best = j; }
    }
    assert.ok(bd <= tol, `${what}: our vertex ${i} has no OpenSubdiv point within ${tol} (nearest ${bd})`);
    used[best] = 1;
  }
}

/** Row for row within `rel` of the mesh's size. */
export function assertClosePoints(ours, theirs, what, rel = 1e-5) {
  assert.equal(ours.length, theirs.length, `${what}: lengths`);
  const tol = rel * Math.max(1, extent(theirs));
  for (let i = 0; i < ours.length; i++) {
    const d = Math.abs(ours[i] - theirs[i]);
    assert.ok(d <= tol, `${what}: value ${i} (vertex ${Math.floor(i / 3)}): ${ours[i]} vs ${theirs[i]}`);
  }
}

/** The same bits, value for value. */
export function assertSameBits(a, b, what) {
  assert.equal(a.length, b.length, `${what}: lengths`);
  const x = new Uint32Array(a.buffer, a.byteOffset, a.length), y = new Uint32Array(b.buffer, b.byteOffset, b.length);
  for (let i = 0; i < x.length; i++) assert.equal(x[i], y[i], `${what}: value ${i}: ${a[i]} vs ${b[i]}`);
}

/** The release command line of the root build ($SUBDIV_BIN), or null. */
export function nativeCli() {
  const bin = process.env.SUBDIV_BIN ?? `${root}target/release/subdiv`;
  return existsSync(bin) ? bin : null;
}
