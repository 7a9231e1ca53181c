#!/usr/bin/env bash
# Opens the real viewer window under Xvfb, renders N frames, saves the last
# one through wgpu and checks the PNG is not blank. Run by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin="${CARGO_TARGET_DIR:-target}/release/subdiv"
out="$(mktemp -d)"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"; chmod 700 "$XDG_RUNTIME_DIR"
run() { xvfb-run -a -s "-screen 0 1280x800x24" timeout 300 "$bin" "$@"; }
# 1. The default start: the bundled tetrahedron, subdivided and animating.
run view --level 5 --play --frames 30 --screenshot "$out/tetra.png"
python3 scripts/png_stats.py "$out/tetra.png"
# 2. Another model, wireframe over Phong, a worker-thread subdivision.
run view models/torus.obj --scheme modified-butterfly --level 3 --wireframe --frames 10 --screenshot "$out/torus.png"
python3 scripts/png_stats.py "$out/torus.png"
# 3. A bad file is refused with a message and a non-zero exit, before any window.
printf 'v 0 0 0\nf 1 2 3\n' > "$out/bad.obj"
if run view "$out/bad.obj" --frames 3 --screenshot "$out/bad.png" 2> "$out/err.txt"; then
  echo "a bad model was accepted"; exit 1
fi
grep -q "bad.obj" "$out/err.txt" || { echo "the error does not name the file:"; cat "$out/err.txt"; exit 1; }
echo "smoke test passed ($out)"
