// subdivide() in WebAssembly against OpenSubdiv 3.5's results on the
// fixtures the library's own tests use (tests/fixtures/*/README or the
// scripts named in each fixture's first line made them).
import test from 'node:test';
import assert from 'node:assert/strict';
import { subdiv, fixture, readObj, readOsd, assertSamePointSets } from './helpers.mjs';

function check(name, scheme, level, options, osd) {
  const m = readObj(fixture(name));
  const polygons = scheme === 'catmull-clark' || scheme === 'bilinear';
  const opts = { ...options };
  if (polygons) opts.faceSizes = m.faceSizes;
  if (m.creases.sharpness.length) opts.creases = m.creases;
  if (m.holes.length) opts.holes = m.holes;
  const out = subdiv.subdivide(m.positions, m.indices, level, scheme, opts);
  const theirs = readOsd(fixture(osd));
  const k = polygons ? 4 : 3;
  // OpenSubdiv's face count where the fixture states it
  if (!Number.isNaN(theirs.faces)) assert.equal(out.indices.length, k * theirs.faces, `${osd}: faces`);
  if (polygons) assert.ok(out.faceSizes.every((s) => s === 4), `${osd}: quads`);
  else assert.equal(out.faceSizes, undefined);
  assert.ok(out.indices.every((i) => i < out.positions.length / 3), `${osd}: indices in range`);
  assertSamePointSets(out.positions, theirs.positions, `${osd}`);
}

test('Loop with creases equals OpenSubdiv', () => {
  for (const l of [1, 2, 3]) check('creases/cube_sharp.obj', 'loop', l, {}, `creases/cube_sharp.uniform.L${l}.osd.txt`);
  for (const l of [1, 2]) check('creases/ico_crease.obj', 'loop', l, {}, `creases/ico_crease.uniform.L${l}.osd.txt`);
  check('creases/ico_crease.obj', 'loop', 2, { creasing: 'chaikin' }, 'creases/ico_crease.chaikin.L2.osd.txt');
  check('creases/torus_semi.obj', 'loop', 2, {}, 'creases/torus_semi.uniform.L2.osd.txt');
});

test('Loop boundary options equal OpenSubdiv', () => {
  for (const l of [1, 2]) {
    check('creases/grid_open.obj', 'loop', l, {}, `creases/grid_open.uniform.L${l}.osd.txt`);
    check('creases/grid_open.obj', 'loop', l, { boundary: 'edge-and-corner' }, `creases/grid_open.corners.L${l}.osd.txt`);
  }
});

test('Loop holes equal OpenSubdiv', () => {
  check('creases/holes.obj', 'loop', 1, {}, 'creases/holes.edge.L1.osd.txt');
});

test('Catmull-Clark on quads equals OpenSubdiv', () => {
  for (const l of [1, 2, 3]) check('catmark/cube.obj', 'catmull-clark', l, {}, `catmark/cube.uniform.L${l}.osd.txt`);
});

test('Catmull-Clark on polygons of 3 to 6 corners equals OpenSubdiv', () => {
  for (const l of [1, 2]) check('catmark/ngons.obj', 'catmull-clark', l, {}, `catmark/ngons.uniform.L${l}.osd.txt`);
});

test('Catmull-Clark boundary options, creases and holes equal OpenSubdiv', () => {
  check('catmark/grid.obj', 'catmull-clark', 2, {}, 'catmark/grid.uniform.L2.osd.txt');
  check('catmark/grid.obj', 'catmull-clark', 2, { boundary: 'edge-and-corner' }, 'catmark/grid.corners.L2.osd.txt');
  check('catmark/holes.obj', 'catmull-clark', 1, {}, 'catmark/holes.edge.L1.osd.txt');
});
