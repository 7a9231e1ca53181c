// The page around the viewer: starts it on the canvas with the address's
// options, and hands it the files the user picks, drops, or names by URL
// (`?model=https://...`). The viewer itself (panel, rendering, editing) is
// the desktop app's Rust code (viewer/subdiv_viewer.js and its .wasm).
import init, { startViewer, openFile, reportProblem } from './viewer/subdiv_viewer.js';

const canvas = document.getElementById('view');
const status = document.getElementById('status');
const say = (text, state) => { status.textContent = text; status.dataset.state = state; };

async function openUrl(url) {
  const name = decodeURIComponent(new URL(url, location.href).pathname.split('/').pop() || 'model.obj');
  try {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`HTTP ${response.status} ${response.statusText}`);
    openFile(name, new Uint8Array(await response.arrayBuffer()));
  } catch (e) {
    reportProblem(`cannot fetch ${url}: ${e.message ?? e}`);
  }
}

async function openPicked(file) {
  try {
    openFile(file.name, new Uint8Array(await file.arrayBuffer()));
  } catch (e) {
    reportProblem(`cannot read ${file.name}: ${e.message ?? e}`);
  }
}

try {
  await init();
  startViewer(canvas, location.search);
} catch (e) {
  say(`subdiv cannot start here: ${e.message ?? e}`, 'error');
  throw e;
}
canvas.focus();

// model= a bundled model's name is opened by the viewer; anything else is a URL
const model = new URLSearchParams(location.search).get('model');
if (model && (model.includes('/') || model.includes(':'))) openUrl(model);

document.getElementById('file').addEventListener('change', (e) => {
  const file = e.target.files?.[0];
  if (file) openPicked(file);
  e.target.value = '';
  canvas.focus();
});
addEventListener('dragover', (e) => { e.preventDefault(); document.body.classList.add('dropping'); });
addEventListener('dragleave', () => document.body.classList.remove('dropping'));
addEventListener('drop', (e) => {
  e.preventDefault();
  document.body.classList.remove('dropping');
  const file = e.dataTransfer?.files?.[0];
  if (file) openPicked(file);
});
