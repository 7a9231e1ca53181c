// The package's entries beyond the OpenSubdiv comparisons: errors thrown
// as Error (never a trap), the Refiner's edits, load from bytes, limit.
import test from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { subdiv, fixture, readObj, parseObj, assertClosePoints, assertSameBits } from './helpers.mjs';

const tet = {
  positions: new Float32Array([1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1]),
  indices: new Uint32Array([0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2]),
};

/** `f` throws an Error (not a WebAssembly.RuntimeError) whose message matches. */
function throwsError(f, pattern, what) {
  assert.throws(f, (e) => {
    assert.ok(e instanceof Error, `${what}: an Error`);
    assert.ok(!(e instanceof WebAssembly.RuntimeError), `${what}: not a trap: ${e}`);
    assert.match(e.message, pattern, what);
    return true;
  });
}

test('bad input throws an Error with the library message, and the module keeps working', () => {
  const { positions: P, indices: I } = tet;
  throwsError(() => subdiv.subdivide(P, new Uint32Array([0, 1, 7, 0, 2, 3, 0, 3, 1, 1, 3, 2]), 1, 'loop'),
    /face 0 uses vertex index 7, but there are only 4 vertices/, 'index out of range');
  throwsError(() => subdiv.subdivide(new Float32Array([NaN, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1]), I, 1, 'loop'),
    /vertex 0/, 'NaN');
  throwsError(() => subdiv.subdivide(P, I, 1, 'lop'), /unknown scheme 'lop'/, 'scheme');
  throwsError(() => subdiv.subdivide(P, I, 1, 'loop', { boundary: 'sharp' }), /sharp/, 'boundary name');
  throwsError(() => subdiv.subdivide(P, I, 1, 'loop', { boundry: 'edge' }), /unknown option "boundry"/, 'key');
  throwsError(() => subdiv.subdivide(P, I, -1, 'loop'), /levels must be a whole number/, 'levels');
  throwsError(() => subdiv.subdivide(P, I, 1.5, 'loop'), /levels must be a whole number/, 'levels');
  throwsError(() => subdiv.subdivide(P, I, 14, 'loop'), /limit is 2\.0 GiB.*options\.maxMemory/, 'memory');
  throwsError(() => subdiv.subdivide(P, I.subarray(0, 10), 1, 'loop'), /3 corners per triangle/, 'length');
  throwsError(() => subdiv.subdivide(P, I, 1, 'loop', { faceSizes: [4, 4, 4] }), /takes triangles/, 'polygons');
  throwsError(() => subdiv.subdivide(P, I, 1, 'catmull-clark', { faceSizes: [3, 3, 3] }), /add up to 9 corners/, 'sizes');
  throwsError(() => subdiv.subdivide(P, I, 1, 'loop', { holes: [4] }), /hole 0 names face 4/, 'hole');
  throwsError(() => subdiv.subdivide(P, I, 1, 'loop', { creases: { edges: [0, 9], sharpness: [2] } }), /crease 0/, 'crease');
  throwsError(() => subdiv.subdivide(P, I, 1, 'loop', { creases: { edges: [0, 1], sharpness: [-1] } }), /crease 0/, 'sharpness');
  // a non-manifold edge: three triangles on 0-1
  const fan = new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0]);
  throwsError(() => subdiv.subdivide(fan, new Uint32Array([0, 1, 2, 1, 0, 3, 0, 1, 4]), 1, 'loop'), /edge/, 'non-manifold');
  throwsError(() => subdiv.load(new TextEncoder().encode('v 0 0\nf 1 2 3\n'), 'bad.obj'), /bad\.obj:1/, 'load');
  throwsError(() => subdiv.load(new Uint8Array([1, 2, 3]), 'x.unknown'), /unknown|extension|format/i, 'format');
  throwsError(() => new subdiv.Refiner(P, I, 1, 'loop').move([9], [0, 0, 0]), /vertex 9/, 'move id');
  throwsError(() => new subdiv.Refiner(P, I, 1, 'loop').move([0], [0, 0]), /3 coordinates/, 'move row');
  throwsError(() => new subdiv.Refiner(P, I, 1, 'loop').setSharpness(0, 1, NaN), /edge 0-1/, 'sharpness');
  // after all of that the module still subdivides
  const out = subdiv.subdivide(P, I, 1, 'loop');
  assert.equal(out.positions.length, 3 * 10);
  assert.equal(out.indices.length, 3 * 16);
});

test('vertices no face uses are carried in place, as in Python', () => {
  // vertex 2 is in no face; the others form the tetrahedron
  const P = new Float32Array([1, 1, 1, 1, -1, -1, 7, 8, 9, -1, 1, -1, -1, -1, 1]);
  const I = new Uint32Array([0, 1, 3, 0, 3, 4, 0, 4, 1, 1, 4, 3]);
  const a = subdiv.subdivide(P, I, 2, 'loop');
  const b = subdiv.subdivide(tet.positions, tet.indices, 2, 'loop');
  assert.deepEqual(Array.from(a.positions.subarray(6, 9)), [7, 8, 9]);
  const back = (i) => (i < 2 ? i : i === 2 ? -1 : i - 1);
  for (let i = 0; i < a.positions.length / 3; i++) {
    if (i === 2) continue;
    const j = back(i);
    assert.deepEqual(Array.from(a.positions.subarray(3 * i, 3 * i + 3)), Array.from(b.positions.subarray(3 * j, 3 * j + 3)));
  }
  assert.deepEqual(Array.from(a.indices).map(back), Array.from(b.indices));
});

test('Refiner: move then undo restores every bit; the move equals a fresh subdivide of the moved cage', () => {
  for (const [name, scheme] of [['creases/ico_crease.obj', 'loop'], ['catmark/ngons.obj', 'catmull-clark']]) {
    const m = readObj(fixture(name));
    const opts = scheme === 'loop' ? { creases: m.creases } : { faceSizes: m.faceSizes };
    const r = new subdiv.Refiner(m.positions, m.indices, 2, scheme, opts);
    const fresh = subdiv.subdivide(m.positions, m.indices, 2, scheme, opts);
    const before = r.positions;
    assertClosePoints(before, fresh.positions, `${name}: the refiner's levels`);
    assert.equal(r.faceSize, scheme === 'loop' ? 3 : 4);
    assert.equal(r.indices.length, fresh.indices.length);
    const ids = new Uint32Array([0, 5]);
    const to = new Float32Array([0.3, -0.2, 0.9, 1.5, 0.25, -0.5]);
    const changed = r.move(ids, to);
    assert.ok(changed.length > 0 && changed.length < before.length / 3, `${name}: only the support changes`);
    const moved = m.positions.slice();
    moved.set(to.subarray(0, 3), 0);
    moved.set(to.subarray(3, 6), 15);
    const want = subdiv.subdivide(moved, m.indices, 2, scheme, opts).positions;
    const after = r.positions;
    assertClosePoints(after, want, `${name}: after the move`);
    // the rows reported changed are the rows that differ
    const differ = [];
    for (let i = 0; i < after.length / 3; i++) {
      if ([0, 1, 2].some((k) => after[3 * i + k] !== before[3 * i + k])) differ.push(i);
    }
    const reported = new Set(changed);
    assert.ok(differ.every((i) => reported.has(i)), `${name}: every changed row is reported`);
    assert.equal(r.undo(), true);
    assertSameBits(r.positions, before, `${name}: undone`);
    assert.equal(r.redo(), true);
    assertSameBits(r.positions, after, `${name}: redone`);
    assert.equal(r.redo(), false);
    r.free();
  }
});

test('Refiner: setSharpness equals subdividing with that crease', () => {
  const m = readObj(fixture('creases/ico_crease.obj'));
  const r = new subdiv.Refiner(m.positions, m.indices, 2, 'loop', { creases: m.creases });
  const before = r.positions;
  // the last tag is edge 13-25 at 0.7; make it 3
  const rows = r.setSharpness(13, 25, 3);
  assert.ok(rows.length > 0);
  const sharp = m.creases.sharpness.slice();
  sharp[sharp.length - 1] = 3;
  const want = subdiv.subdivide(m.positions, m.indices, 2, 'loop', { creases: { edges: m.creases.edges, sharpness: sharp } });
  assertClosePoints(r.positions, want.positions, 'sharpness 3');
  assert.ok(r.undo());
  assertSameBits(r.positions, before, 'sharpness undone');
  assert.throws(() => r.setSharpness(0, 40, 1), /0-40/);
});

test('load reads an OBJ and a PLY given as bytes', () => {
  const path = fixture('catmark/ngons.obj');
  const ours = parseObj(readFileSync(path, 'utf8'));
  const obj = subdiv.load(new Uint8Array(readFileSync(path)), 'ngons.obj');
  assertSameBits(obj.positions, ours.positions, 'OBJ positions');
  assert.deepEqual(Array.from(obj.faceSizes), Array.from(ours.faceSizes));
  assert.deepEqual(Array.from(obj.indices), Array.from(ours.indices));
  assert.equal(obj.triangles.length % 3, 0);
  // it subdivides as the arrays do
  const a = subdiv.subdivide(obj.positions, obj.indices, 1, 'catmull-clark', { faceSizes: obj.faceSizes });
  const b = subdiv.subdivide(ours.positions, ours.indices, 1, 'catmull-clark', { faceSizes: ours.faceSizes });
  assertSameBits(a.positions, b.positions, 'subdivided');
  // a binary little-endian PLY of the tetrahedron, written here
  const header = 'ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n' +
    'property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n';
  const head = new TextEncoder().encode(header);
  const body = new DataView(new ArrayBuffer(4 * 12 + 4 * 13));
  tet.positions.forEach((x, i) => body.setFloat32(4 * i, x, true));
  for (let f = 0; f < 4; f++) {
    const at = 48 + 13 * f;
    body.setUint8(at, 3);
    for (let k = 0; k < 3; k++) body.setInt32(at + 1 + 4 * k, tet.indices[3 * f + k], true);
  }
  const ply = new Uint8Array(head.length + body.byteLength);
  ply.set(head);
  ply.set(new Uint8Array(body.buffer), head.length);
  const loaded = subdiv.load(ply, 'tet.ply');
  assertSameBits(loaded.positions, tet.positions, 'PLY positions');
  assert.deepEqual(Array.from(loaded.indices), Array.from(tet.indices));
  assert.equal(loaded.faceSizes, undefined);
  // the tags an OBJ carries come back as subdivide takes them
  const tagged = readObj(fixture('creases/holes.obj'));
  const withTags = subdiv.load(new Uint8Array(readFileSync(fixture('creases/holes.obj'))), 'holes.obj');
  // as undirected edges with their sharpness, in any order
  const edges = ({ edges, sharpness }) => Array.from(sharpness, (s, k) =>
    `${Math.min(edges[2 * k], edges[2 * k + 1])}-${Math.max(edges[2 * k], edges[2 * k + 1])}:${s}`).sort();
  assert.deepEqual(edges(withTags.creases), edges(tagged.creases));
  assert.deepEqual(Array.from(withTags.holes), Array.from(tagged.holes));
});

test('limit: the Loop limit of a regular torus lies between the cage and its subdivisions', () => {
  const m = readObj(`${fixture('')}../../models/torus.obj`);
  const lim = subdiv.limit(m.positions, m.indices);
  // the limit of vertex i is where subdividing converges: level 5's row i
  const fine = subdiv.subdivide(m.positions, m.indices, 5, 'loop').positions;
  const n = m.positions.length;
  assertClosePoints(lim.positions, fine.subarray(0, n), 'limit vs level 5', 1e-3);
  for (let i = 0; i < n; i += 3) {
    const len = Math.hypot(lim.normals[i], lim.normals[i + 1], lim.normals[i + 2]);
    assert.ok(Math.abs(len - 1) < 1e-5, `normal ${i / 3} is a unit vector`);
  }
});
