// Time from opening the page to its first idle frame with a device (the
// loading notice gone, data-busy false), a fresh browser context per page,
// minima of 5 interleaved rounds: node web/tests/browser/startup.mjs
import { chromium } from 'playwright-core';
import { serve } from './serve.mjs';
const server = await serve(process.env.SUBDIV_WEB ?? 'target/web');
const base = `http://127.0.0.1:${server.address().port}/`;
const browser = await chromium.launch({ executablePath: '/usr/bin/chromium', headless: true, args: ['--enable-unsafe-webgpu','--enable-features=Vulkan','--use-vulkan=swiftshader','--use-webgpu-adapter=swiftshader','--enable-unsafe-swiftshader','--use-angle=swiftshader'] });
const best = {};
for (let round = 0; round < 5; round++) {
  for (const [name, q] of [['webgpu torus L2', 'model=torus.obj&level=2&scheme=loop'], ['webgl2 torus L2', 'model=torus.obj&level=2&scheme=loop&backend=webgl2'], ['webgpu first launch', ''], ['webgpu critter CC L2', 'model=critter.obj&level=2&scheme=catmull-clark']]) {
    const ctx = await browser.newContext({ viewport: { width: 1280, height: 800 } });
    const page = await ctx.newPage();
    const t0 = Date.now();
    await page.goto(`${base}index.html?${q}`);
    await page.waitForFunction(() => { const d = document.getElementById('view').dataset; return d.busy === 'false' && document.getElementById('status').textContent === '' && Number(d.frames) > 0; }, null, { timeout: 60000, polling: 5 });
    const ms = Date.now() - t0;
    best[name] = Math.min(best[name] ?? Infinity, ms);
    await ctx.close();
  }
}
console.log(JSON.stringify(best));
await browser.close(); server.close();
