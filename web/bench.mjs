// Speed of the package in node against the native command line on one
// thread, minima of interleaved runs:
//   node web/bench.mjs MODEL.obj [runs] [THREE_DIR]
// MODEL is read by load(); each run times subdivide() at levels 1 and 2 in
// WebAssembly (performance.now around the call: the cage's tables built,
// the copies in and out included), the library's part alone (_subdivideMs:
// the span the command line's subdivide_ms times), then `subdiv --threads 1 subdivide MODEL out.ply -n L
// --stats` (its subdivide_ms, the library's own time), and, with
// THREE_DIR (a folder where `npm install three three-subdivide` ran),
// three-subdivide's LoopSubdivision.modify at level 1.
import { readFileSync, mkdtempSync, rmSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { subdiv, nativeCli } from './tests/helpers.mjs';

const [model, runsArg, threeDir] = process.argv.slice(2);
const runs = Number(runsArg ?? 5);
const m = subdiv.load(new Uint8Array(readFileSync(model)), model);
console.log(`${model}: ${m.positions.length / 3} vertices, ${m.triangles.length / 3} triangles`);
const bin = nativeCli();
const dir = mkdtempSync(join(tmpdir(), 'subdiv-bench-'));
let three = null;
if (threeDir) {
  const THREE = await import(join(threeDir, 'node_modules/three/build/three.module.js'));
  const { LoopSubdivision } = await import(join(threeDir, 'node_modules/three-subdivide/src/index.js'));
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(m.positions, 3));
  g.setIndex(new THREE.BufferAttribute(m.triangles, 1));
  // its smoothing pass reads triangle soup (what its split pass makes from an indexed geometry)
  three = { g, soup: g.toNonIndexed(), LoopSubdivision };
}
const best = {};
const keep = (k, ms) => { best[k] = Math.min(best[k] ?? Infinity, ms); };
for (let r = 0; r < runs; r++) {
  for (const n of [1, 2]) {
    const t0 = performance.now();
    const out = subdiv.subdivide(m.positions, m.triangles, n, 'loop');
    keep(`wasm subdivide() L${n}`, performance.now() - t0);
    keep(`wasm library alone L${n}`, subdiv._subdivideMs(m.positions, m.triangles, n, 'loop'));
    if (r === 0) console.log(`L${n}: ${out.indices.length / 3} triangles`);
    if (bin) {
      const p = spawnSync(bin, ['--threads', '1', 'subdivide', model, join(dir, 'x.ply'), '-n', String(n), '--stats'], { encoding: 'utf8' });
      const ms = Number(/subdivide_ms=([0-9.]+)/.exec(p.stdout + p.stderr)?.[1]);
      if (Number.isNaN(ms)) throw new Error(`no subdivide_ms from ${bin}: ${p.stderr}`);
      keep(`native 1 thread L${n}`, ms);
    }
  }
  if (three) {
    for (const split of [false, true]) {
      const t0 = performance.now();
      three.LoopSubdivision.modify(split ? three.g : three.soup, 1, { split });
      keep(`three-subdivide L1 split=${split}`, performance.now() - t0);
    }
  }
}
rmSync(dir, { recursive: true, force: true });
for (const [k, ms] of Object.entries(best)) console.log(`${k}: ${ms.toFixed(1)} ms (min of ${runs})`);
