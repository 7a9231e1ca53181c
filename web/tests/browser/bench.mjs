// Speed of the package in headless Chromium (the browser the page runs in),
// against three-subdivide in the same page and the native command line on
// one thread, minima of interleaved runs:
//   node web/tests/browser/bench.mjs MODEL.obj [runs] [THREE_DIR]
// THREE_DIR: a folder where `npm install three three-subdivide` ran. Times
// are taken in the page with performance.now around each call and returned
// through playwright's evaluate (no virtual time, no DOM dump).
import { mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { chromium } from 'playwright-core';
import { serve } from './serve.mjs';

const [model, runsArg, threeDir] = process.argv.slice(2);
const runs = Number(runsArg ?? 5);
const root = resolve(process.env.SUBDIV_WEB ?? 'target/web');
const bin = resolve(process.env.SUBDIV_BIN ?? 'target/release/subdiv');
const site = mkdtempSync(join(tmpdir(), 'subdiv-bench-site-'));
symlinkSync(join(root, 'pkg'), join(site, 'pkg'));
symlinkSync(resolve(model), join(site, 'model.obj'));
if (threeDir) symlinkSync(resolve(threeDir, 'node_modules'), join(site, 'node_modules'));
// three-subdivide imports 'three' by name: the page maps it
writeFileSync(join(site, 'bench.html'), '<!doctype html><script type="importmap">'
  + '{"imports":{"three":"/node_modules/three/build/three.module.js"}}</script><p>bench</p>');
const server = await serve(site);
const base = `http://127.0.0.1:${server.address().port}/`;
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium', headless: true });
const page = await browser.newPage();
await page.goto(`${base}bench.html`);
await page.evaluate(async ({ base, three }) => {
  const subdiv = await import(`${base}pkg/subdiv.js`);
  await subdiv.default();
  const bytes = new Uint8Array(await (await fetch(`${base}model.obj`)).arrayBuffer());
  const m = subdiv.load(bytes, 'model.obj');
  window.bench = { subdiv, m };
  if (three) {
    const THREE = await import(`${base}node_modules/three/build/three.module.js`);
    const { LoopSubdivision } = await import(`${base}node_modules/three-subdivide/src/index.js`);
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(m.positions, 3));
    g.setIndex(new THREE.BufferAttribute(m.triangles, 1));
    // its smoothing pass alone reads triangle soup (what its split pass makes of an indexed geometry)
    Object.assign(window.bench, { g, soup: g.toNonIndexed(), LoopSubdivision });
  }
}, { base, three: Boolean(threeDir) });
const dir = mkdtempSync(join(tmpdir(), 'subdiv-bench-'));
const best = {};
const keep = (k, ms) => { best[k] = Math.min(best[k] ?? Infinity, ms); };
for (let r = 0; r < runs; r++) {
  for (const n of [1, 2]) {
    const t = await page.evaluate((n) => {
      const { subdiv, m } = window.bench;
      const t0 = performance.now();
      subdiv.subdivide(m.positions, m.triangles, n, 'loop');
      const call = performance.now() - t0;
      return { call, alone: subdiv._subdivideMs(m.positions, m.triangles, n, 'loop') };
    }, n);
    keep(`Chromium wasm subdivide() L${n}`, t.call);
    keep(`Chromium wasm library alone L${n}`, t.alone);
    const p = spawnSync(bin, ['--threads', '1', 'subdivide', model, join(dir, 'out.ply'), '-n', String(n), '--scheme', 'loop', '--stats'], { encoding: 'utf8' });
    const ms = Number(/subdivide_ms=([0-9.]+)/.exec(p.stdout + p.stderr)?.[1]);
    if (Number.isNaN(ms)) throw new Error(`no subdivide_ms from ${bin}: ${p.stderr}`);
    keep(`native --threads 1 subdivide_ms L${n}`, ms);
  }
  if (threeDir) {
    keep('Chromium three-subdivide LoopSubdivision.modify(g, 1)', await page.evaluate(() => {
      const { g, LoopSubdivision } = window.bench;
      const t0 = performance.now();
      LoopSubdivision.modify(g, 1);
      return performance.now() - t0;
    }));
    // about 45 s on the bunny: the first round only
    if (r === 0) {
      keep('Chromium three-subdivide modify(soup, 1, { split: false })', await page.evaluate(() => {
        const { soup, LoopSubdivision } = window.bench;
        const t0 = performance.now();
        LoopSubdivision.modify(soup, 1, { split: false });
        return performance.now() - t0;
      }));
    }
  }
}
for (const [k, v] of Object.entries(best)) console.log(`${k}: ${v.toFixed(1)} ms`);
await browser.close();
server.close();
rmSync(dir, { recursive: true, force: true });
rmSync(site, { recursive: true, force: true });
