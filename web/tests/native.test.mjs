// subdivide() in WebAssembly against the native command line of the root
// build on the same files ($SUBDIV_BIN, default target/release/subdiv),
// produced at test time: the same library compiled for two targets gives
// the same vertices in the same order.
import test from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { subdiv, root, parseObj, nativeCli, assertClosePoints } from './helpers.mjs';

const bin = nativeCli();
const cases = [
  ['models/torus.obj', 'loop', 2, []],
  ['models/torus.obj', 'butterfly', 2, []],
  ['tests/fixtures/creases/grid_open.obj', 'loop', 2, ['--boundary', 'edge-and-corner']],
  ['models/critter.obj', 'catmull-clark', 2, []],
  ['tests/fixtures/catmark/ngons.obj', 'catmull-clark', 2, []],
];

test('subdivide equals the native command line row for row', { skip: bin ? false : 'no native CLI (build it: cargo build --release)' }, () => {
  const dir = mkdtempSync(join(tmpdir(), 'subdiv-web-'));
  try {
    for (const [file, scheme, n, flags] of cases) {
      const out = join(dir, 'out.obj');
      execFileSync(bin, ['subdivide', join(root, file), out, '-n', String(n), '-s', scheme, ...flags], { stdio: 'pipe' });
      const native = parseObj(readFileSync(out, 'utf8'));
      const m = subdiv.load(new Uint8Array(readFileSync(join(root, file))), file);
      const opts = { faceSizes: m.faceSizes, creases: m.creases, holes: m.holes };
      if (flags[0] === '--boundary') opts.boundary = flags[1];
      const ours = subdiv.subdivide(m.positions, m.indices, n, scheme, opts);
      const what = `${file} ${scheme} L${n}`;
      assertClosePoints(ours.positions, native.positions, what);
      assert.deepEqual(Array.from(ours.indices), Array.from(native.indices), `${what}: faces`);
    }
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
