#!/usr/bin/env bash
# Exact Loop evaluation against OpenSubdiv's patch table on the same points, in
# the same run: RUNS interleaved cold runs of each, minima reported.
#   scripts/perf-eval.sh [MODEL] [POINTS] [RUNS]
# POINTS: one "f u v" per line (default: 1,000,000 random points on the
# bunny's faces whose three vertices are interior, made here with a fixed seed).
# OpenSubdiv: scripts/osd-loop-eval.cpp built as /tmp/peers/osd_loop_eval
# (its `time` mode: build_ms = refiner + adaptive refinement + patch table +
# patch map, eval_ms = position, both first derivatives and the normal).
# Ours: `subdiv eval --stats` (prepare_ms = the f64 level 1 and the blocks,
# eval_ms = position and normal of every point), one thread and all.
set -euo pipefail
cd "$(dirname "$0")/.."
model=${1:-../shared/models/stanford-bunny.obj}
points=${2:-/tmp/eval-points.txt}
runs=${3:-5}
osd=${OSD_LOOP_EVAL:-/tmp/peers/osd_loop_eval}
bin=target/release/subdiv
if [ ! -f "$points" ]; then
  python3 - "$model" "$points" <<'PY'
import random, sys
faces, verts, bnd = [], 0, set()
for line in open(sys.argv[1]):
    t = line.split()
    if t and t[0] == 'f':
        faces.append([int(x.split('/')[0]) - 1 for x in t[1:4]])
edges = {}
for f in faces:
    for i in range(3):
        a, b = f[i], f[(i + 1) % 3]
        edges[(min(a, b), max(a, b))] = edges.get((min(a, b), max(a, b)), 0) + 1
for (a, b), n in edges.items():
    if n == 1:
        bnd.update((a, b))
ok = [i for i, f in enumerate(faces) if not (set(f) & bnd)]
rng = random.Random(12345)
with open(sys.argv[2], 'w') as out:
    for _ in range(1000000):
        u, v = rng.random(), rng.random()
        if u + v > 1:
            u, v = 1 - u, 1 - v
        out.write(f"{rng.choice(ok)} {u!r} {v!r}\n")
PY
fi
for i in $(seq "$runs"); do
  echo "ours1 $($bin --threads 1 eval "$model" "$points" /tmp/eval-out.txt --stats 2>&1 >/dev/null)"
  echo "ours  $($bin eval "$model" "$points" /tmp/eval-out.txt --stats 2>&1 >/dev/null)"
  echo "osd   $($osd time "$model" "$points")"
done | tee /tmp/perf-eval.log
python3 - <<'PY'
import re
best = {}
for line in open('/tmp/perf-eval.log'):
    who = line.split()[0]
    for k, v in re.findall(r'(\w+_ms)=([\d.]+)', line):
        best[(who, k)] = min(best.get((who, k), 1e99), float(v))
for who in ('ours1', 'ours', 'osd'):
    print(who, {k: v for (w, k), v in best.items() if w == who})
PY
