// Run by scripts/web.sh test in a folder where the tarball of `npm pack`
// was installed: the package imports by its name and subdivides.
import { readFileSync } from 'node:fs';
import init, { subdivide, version } from 'subdiv';
await init({ module_or_path: readFileSync(new URL('subdiv_bg.wasm', import.meta.resolve('subdiv'))) });
const r = subdivide([1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1], [0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2], 1, 'loop');
if (r.indices.length !== 48) throw new Error('wrong face count');
console.log(`subdiv ${version()} from the tarball: ${r.positions.length / 3} vertices`);
