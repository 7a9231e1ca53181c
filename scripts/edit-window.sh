#!/usr/bin/env bash
# Edits the cage in the real window under Xvfb as a user would (xdotool):
# E, A, G Z 0.5 Return moves every control vertex; the title shows the
# unsaved mark and the recovery file appears; kill -9; a relaunch offers
# the edits, Return recovers them, Ctrl+S writes them to the model, which
# then has every vertex 0.5 higher and the same faces. Run by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."
bin="$(pwd)/${CARGO_TARGET_DIR:-target}/release/subdiv"
work="$(mktemp -d)"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"; chmod 700 "$XDG_RUNTIME_DIR"
export XDG_STATE_HOME="$work/state"
cp models/cube.obj "$work/cube.obj"
# a display no other X server holds
n=90; while [ -e "/tmp/.X$n-lock" ] || [ -e "/tmp/.X11-unix/X$n" ]; do n=$((n + 1)); done
Xvfb ":$n" -screen 0 1280x800x24 >/dev/null 2>&1 &
xvfb=$!
export DISPLAY=":$n"
viewer=""
cleanup() {
  if [ -n "$viewer" ]; then kill -9 "$viewer" 2>/dev/null || true; fi
  kill "$xvfb" 2>/dev/null || true
  wait "$xvfb" 2>/dev/null || true
}
trap cleanup EXIT
# waits (up to 60 s) until the command succeeds: the window's answer, not a fixed time
until_ok() {
  for _ in $(seq 600); do if eval "$1"; then return 0; fi; sleep 0.1; done
  echo "timed out: $1"; cat "$work/log.txt" 2>/dev/null; exit 1
}
until_ok 'xdotool getdisplaygeometry >/dev/null 2>&1'
launch() {
  (cd "$work" && exec "$bin" view cube.obj -s catmull-clark -n 2) > "$work/log.txt" 2>&1 &
  viewer=$!
  until_ok 'win=$(xdotool search --name "cube.obj" | head -1) && [ -n "$win" ]'
  xdotool windowfocus --sync "$win"
  xdotool mousemove --window "$win" 700 400
}
launch
xdotool key e a g z; xdotool type "0.5"; xdotool key Return
until_ok '[[ "$(xdotool getwindowname "$win")" == \** ]]'
until_ok 'ls "$XDG_STATE_HOME"/subdiv/recovery/*.obj >/dev/null 2>&1'
kill -9 "$viewer"; wait "$viewer" 2>/dev/null || true
cmp -s models/cube.obj "$work/cube.obj" || { echo "the model was written before a save"; exit 1; }
launch
# the recovery question is up: Return recovers (the title gets its mark), Ctrl+S saves
xdotool key Return
until_ok '[[ "$(xdotool getwindowname "$win")" == \** ]]'
xdotool key ctrl+s
until_ok '[[ "$(xdotool getwindowname "$win")" != \** ]]'
ls "$XDG_STATE_HOME"/subdiv/recovery/*.obj >/dev/null 2>&1 && { echo "the save left the recovery file"; exit 1; }
python3 - "$work/cube.obj" models/cube.obj <<'PY'
import sys
def read(p):
    v, f = [], []
    for line in open(p):
        t = line.split()
        if t and t[0] == "v": v.append(tuple(map(float, t[1:4])))
        if t and t[0] == "f": f.append(tuple(int(x.split("/")[0]) for x in t[1:]))
    return v, f
(v1, f1), (v0, f0) = read(sys.argv[1]), read(sys.argv[2])
assert len(v1) == len(v0) and f1 == f0, "same vertices and faces"
for a, b in zip(v1, v0):
    assert abs(a[0] - b[0]) < 1e-6 and abs(a[1] - b[1]) < 1e-6 and abs(a[2] - b[2] - 0.5) < 1e-6, (a, b)
print(f"edited in the window, killed, recovered and saved: {len(v1)} vertices 0.5 higher, faces kept")
PY
