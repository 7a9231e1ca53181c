// The page (target/web, built by `bash scripts/web.sh build`) in Debian's
// headless Chromium, once on WebGPU (SwiftShader) and once on WebGL2: it
// draws the model, a level change changes the picture, a picked file and a
// fetched URL open, an edit moves the cage and its undo restores the
// picture, and unsaved edits survive a reload. The viewer writes its state
// on the canvas (`data-frames`, `data-busy`, `data-level`, ...): every wait
// here is for one of those, never for a time.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, writeFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { chromium } from 'playwright-core';
import { serve } from './serve.mjs';
import { decodePng, differing } from './png.mjs';

const root = resolve(process.env.SUBDIV_WEB ?? 'target/web');
const models = resolve(process.env.SUBDIV_MODELS ?? 'models');
const fixtures = resolve(process.env.SUBDIV_FIXTURES ?? 'tests/fixtures');
const shots = process.env.SUBDIV_SHOTS; // a folder to keep the screenshots in, when set
const chrome = process.env.CHROMIUM ?? '/usr/bin/chromium';
// --use-angle=swiftshader: without it the WebGPU canvas never reaches the
// compositor in headless Chromium 156, and screenshots show the page behind it
const WEBGPU = ['--enable-unsafe-webgpu', '--enable-features=Vulkan', '--use-vulkan=swiftshader', '--use-angle=swiftshader',
  '--use-webgpu-adapter=swiftshader', '--enable-unsafe-swiftshader'];

let server, browser, base, scratch;
before(async () => {
  server = await serve(root);
  base = `http://127.0.0.1:${server.address().port}/`;
  browser = await chromium.launch({ executablePath: chrome, headless: true, args: ['--headless=new', ...WEBGPU] });
  scratch = mkdtempSync(join(tmpdir(), 'subdiv-page-'));
});
after(async () => {
  await browser?.close();
  server?.close();
  if (scratch) rmSync(scratch, { recursive: true, force: true });
});

/** Waits until the canvas says the viewer is idle with `want` (attribute: value) and has drawn since. */
async function settled(page, want = {}) {
  await page.waitForFunction((want) => {
    const c = document.getElementById('view');
    const d = c.dataset;
    if (d.busy !== 'false' || Number(d.frames ?? 0) < 2) return false;
    if (d.error) return true; // an error is a state too: the caller checks it
    return Object.entries(want).every(([k, v]) => d[k] === String(v));
  }, want, { timeout: 120_000 });
  // the attributes are written after the frame that drew the state is presented
  return page.evaluate(() => ({ ...document.getElementById('view').dataset }));
}

/** Presses `key` (or types `text`) and waits for the frame that took it in:
 * several keys within one frame are not all seen (a person's keys come
 * frames apart; a script's would not). */
async function key(page, k, text = false) {
  const frames = Number(await page.getAttribute('#view', 'data-frames'));
  if (text) await page.keyboard.type(k); else await page.keyboard.press(k);
  await page.waitForFunction((n) => Number(document.getElementById('view').dataset.frames) > n, frames);
}

async function shot(page, name) {
  const png = await page.screenshot();
  if (shots) writeFileSync(join(shots, `${name}.png`), png);
  return decodePng(png);
}

/** Pixels unlike the background colour (the top left corner's) in the middle of the 3D area. */
function modelPixels(img) {
  const bg = img.pixels.subarray(0, 3);
  let n = 0;
  for (let y = Math.floor(img.height * 0.3); y < img.height * 0.7; y++) {
    for (let x = Math.floor(img.width * 0.45); x < img.width * 0.85; x++) {
      const i = (y * img.width + x) * 4;
      if (Math.abs(img.pixels[i] - bg[0]) + Math.abs(img.pixels[i + 1] - bg[1]) + Math.abs(img.pixels[i + 2] - bg[2]) > 30) n++;
    }
  }
  return n;
}

async function open(backend, query) {
  const page = await browser.newPage({ viewport: { width: 1000, height: 640 } });
  const logs = [];
  page.on('console', (m) => logs.push(`${m.type()}: ${m.text()}`));
  page.on('pageerror', (e) => logs.push(`pageerror: ${e.message}`));
  const q = backend === 'webgl2' ? `${query}&backend=webgl2` : query;
  await page.goto(`${base}index.html?${q}`);
  return { page, logs };
}

for (const backend of ['webgpu', 'webgl2']) {
  test(`${backend}: draws the model, a level changes the picture, a file and a URL open`, async () => {
    const { page, logs } = await open(backend, 'model=torus.obj&level=1&scheme=loop');
    const s = await settled(page, { level: 1, model: 'torus.obj' });
    assert.equal(s.error ?? '', '', `no error: ${logs.join('\n')}`);
    assert.match(s.adapter, backend === 'webgpu' ? /WebGpu/i : /Gl/i, `the ${backend} adapter: ${s.adapter}`);
    assert.equal(await page.textContent('#status'), '', 'the loading notice is gone');
    assert.equal(Number(s.triangles), 4 * 1024, 'level 1 of the 1024-triangle torus');
    const one = await shot(page, `${backend}-torus-1`);
    assert.ok(modelPixels(one) > 0.2 * 0.4 * 0.4 * one.width * one.height, 'the torus covers the middle of the view');
    // idle, it draws nothing more (a redraw asking for another drew ~6 a second,
    // 1.5 s each at level 6 on SwiftShader): a window of time is what this checks
    const idle = Number(await page.getAttribute('#view', 'data-frames'));
    await page.waitForTimeout(1500);
    const later = Number(await page.getAttribute('#view', 'data-frames'));
    assert.ok(later - idle <= 2, `${later - idle} frames drawn in 1.5 s of idling`);

    await page.focus('#view');
    await key(page, 'Equal');
    await settled(page, { level: 2 });
    await key(page, 'Equal');
    const three = await settled(page, { level: 3 });
    assert.equal(Number(three.triangles), 64 * 1024);
    const img3 = await shot(page, `${backend}-torus-3`);
    assert.ok(differing(one, img3) > 500, 'level 3 is drawn, not level 1');

    await page.setInputFiles('#file', join(models, 'cube.obj'));
    const cube = await settled(page, { model: 'cube.obj' });
    assert.equal(cube.error ?? '', '');
    assert.ok(differing(img3, await shot(page, `${backend}-cube`)) > 500, 'the cube replaced the torus');

    // a file dropped on the page: a USD stage, read from its bytes
    const usda = readFileSync(join(fixtures, 'usd', 'two.usda'), 'utf8');
    await page.evaluate((text) => {
      const dt = new DataTransfer();
      dt.items.add(new File([text], 'two.usda'));
      document.body.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
    }, usda);
    const stage = await settled(page, { model: 'two.usda' });
    assert.equal(stage.error ?? '', '');

    const url = await open(backend, `model=${encodeURIComponent(`${base}lprism-copy.obj`)}`);
    const missing = await settled(url.page);
    assert.match(missing.error, /lprism-copy\.obj.*404/, 'a failed fetch is said in the panel');
    await url.page.close();
    const unknown = await open(backend, 'model=nope.obj');
    assert.match((await settled(unknown.page)).error, /no bundled model nope\.obj/, 'an unknown name is said');
    await unknown.page.close();

    await page.close();
  });

  test(`${backend}: the address's shading and the animation loop`, async () => {
    const { page, logs } = await open(backend, 'model=torus.obj&level=1&scheme=loop');
    await settled(page, { level: 1 });
    const phong = await shot(page, `${backend}-phong`);
    const wire = await open(backend, 'model=torus.obj&level=1&scheme=loop&shading=wire');
    await settled(wire.page, { level: 1 });
    assert.ok(differing(phong, await shot(wire.page, `${backend}-wire`)) > 2000, 'shading=wire draws the wireframe');
    await wire.page.close();
    // the adaptive display: the limit within half a pixel, drawn as a fine level is
    const fine = await open(backend, 'model=torus.obj&level=4&scheme=loop');
    await settled(fine.page, { level: 4 });
    const level4 = await shot(fine.page, `${backend}-level4`);
    await fine.page.close();
    const ad = await open(backend, 'model=torus.obj&level=4&scheme=loop&adaptive=1'); // framed as level 4
    const limit = await settled(ad.page, { adaptive: true });
    assert.equal(limit.error ?? '', '', ad.logs.join('\n'));
    assert.ok(Number(limit.triangles) > 4 * 1024, `${limit.triangles} triangles: finer than level 1`);
    const adaptive = await shot(ad.page, `${backend}-adaptive`);
    // the 3D area below the overlay's line (which names what is drawn); level 1
    // against level 4 shows what the comparison sees (measured: 213 and 2,632
    // pixels on WebGPU, 224 and 1,650 on WebGL2)
    const [x0, y0] = [Math.round(0.35 * phong.width), 40];
    const near = differing(adaptive, level4, 8, x0, y0);
    const coarse = differing(phong, level4, 8, x0, y0);
    assert.ok(near < 0.002 * phong.width * phong.height && near * 4 < coarse, `unlike level 4 in ${near} pixels; level 1 in ${coarse}`);
    await ad.page.close();
    await page.close();

    const anim = await open(backend, 'model=tetrahedron.obj&level=2&scheme=loop&play=1');
    const s = await settled(anim.page, { playing: true });
    assert.equal(s.error ?? '', '', `${anim.logs.join('\n')} ${logs.join('\n')}`);
    const a = await shot(anim.page, `${backend}-anim-a`);
    const frames = Number(s.frames);
    await anim.page.waitForFunction((n) => Number(document.getElementById('view').dataset.frames) > n, frames + 60);
    const b = await shot(anim.page, `${backend}-anim-b`);
    assert.ok(differing(a, b, 8, Math.round(0.35 * a.width)) > 200, 'sixty frames later the cage has moved');
    await anim.page.close();
  });

  test(`${backend}: an edit moves the cage, undo restores the picture, a reload offers the edits`, async () => {
    const { page, logs } = await open(backend, 'model=cube.obj&level=2&scheme=catmull-clark');
    await settled(page, { level: 2, model: 'cube.obj' });
    await page.focus('#view');
    await key(page, 'e');
    await key(page, 'a');
    const before = await shot(page, `${backend}-edit-before`);
    await key(page, 'g');
    await key(page, 'z');
    for (const c of '0.5') await key(page, c, true);
    await key(page, 'Enter');
    const moved = await settled(page, { steps: 1, unsaved: true });
    assert.equal(moved.error ?? '', '', logs.join('\n'));
    const after = await shot(page, `${backend}-edit-moved`);
    assert.ok(differing(before, after) > 500, 'the moved cube is drawn');
    await key(page, 'Control+z');
    await settled(page, { steps: 0 });
    const undone = await shot(page, `${backend}-edit-undone`);
    // the 3D area (right of the panel, whose history list shows the undone step)
    const view = Math.round(0.35 * before.width);
    assert.ok(differing(before, undone, 8, view) < 0.001 * before.width * before.height, 'undo restores the 3D view');
    assert.ok(differing(before, after, 8, view) > 500, 'the move is in the 3D view');
    await key(page, 'Control+Shift+z');
    await settled(page, { steps: 1, unsaved: true });
    await page.reload();
    const again = await settled(page, { model: 'cube.obj' });
    assert.equal(again.offer, 'true', 'the unsaved edits are offered after a reload');
    await page.focus('#view');
    await key(page, 'Enter');
    await settled(page, { offer: false, unsaved: true });
    // Ctrl+S downloads the cage, the recovered move in it
    const download = page.waitForEvent('download');
    await key(page, 'Control+s');
    const file = await download;
    assert.equal(file.suggestedFilename(), 'cube.obj');
    const text = readFileSync(await file.path(), 'utf8');
    const zs = text.split('\n').filter((l) => l.startsWith('v ')).map((l) => Number(l.split(/\s+/)[3]));
    assert.equal(zs.length, 8);
    const cube = readFileSync(join(models, 'cube.obj'), 'utf8').split('\n').filter((l) => l.startsWith('v '))
      .map((l) => Number(l.split(/\s+/)[3]));
    zs.forEach((z, i) => assert.ok(Math.abs(z - (cube[i] + 0.5)) < 1e-6, `vertex ${i}: z ${z} is ${cube[i]} + 0.5`));
    await settled(page, { unsaved: false });
    await page.close();
  });
}
