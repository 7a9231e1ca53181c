#!/usr/bin/env bash
# Catmull-Clark beside OpenSubdiv, interleaved cold runs (one process each), minima and
# medians of REPS rounds: docs/performance.md, "Catmull-Clark".
#   bash ../shared/bench/native/build.sh PEERS        (apt-get install g++ libosd-dev)
# Usage: scripts/perf-catmark.sh [PEERS_DIR] [REPS]; MODELS=dir overrides ../shared/models.
# The input is a quad mesh of 70,272 faces: spot (5,856 triangles) after two
# Catmull-Clark levels, written by our own `subdivide` (OpenSubdiv's refinement of the same
# triangles gives the same quads; tests/catmull_clark.rs checks the rules against it).
# ours / ours1: `subdivide --levels 3` on 2 threads / 1 thread, subdivide_ms (the levels,
# after reading); osd: osd_bench's refine + interpolate (its subdivide_ms less create_ms,
# the topology built from the file's faces), one thread; anim: per frame at level 2, ours
# positions and normals, OpenSubdiv's StencilTable positions only.
set -euo pipefail
cd "$(dirname "$0")/.."
peers="${1:-/tmp/peers}"; reps="${2:-7}"
models="${MODELS:-../shared/models}"
bin="${CARGO_TARGET_DIR:-target}/release/subdiv"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
ln -s /dev/null "$tmp/null.ply"
quads="$tmp/spot_q70k.obj"
"$bin" -q subdivide "$models/spot.obj" "$quads" -s catmull-clark --levels 2
field() { grep -o "$1=[0-9.]*" | head -1 | cut -d= -f2; }
stats() { sort -g | awk '{a[NR]=$1} END {printf "min %.1f  median %.1f  max %.1f", a[1], a[int((NR+1)/2)], a[NR]}'; }
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)  threads: $(nproc)"
declare -A t
for _ in $(seq "$reps"); do
  t[ours]+="$("$bin" subdivide "$quads" "$tmp/null.ply" -s cc --levels 3 --stats | field subdivide_ms) "
  t[ours1]+="$("$bin" --threads 1 subdivide "$quads" "$tmp/null.ply" -s cc --levels 3 --stats | field subdivide_ms) "
  o="$("$peers/osd_bench" "$quads" 3 catmark)"
  t[osd]+="$(echo "$(echo "$o" | field subdivide_ms) - $(echo "$o" | field create_ms)" | bc) "
  t[ours_anim]+="$("$bin" animate --model "$quads" -s cc --level 2 --refine 4 --stats | field frame_min_ms) "
  t[osd_anim]+="$("$peers/osd_bench" "$quads" 2 catmark --frames 64 | grep stencils= | field frame_min_ms) "
done
for k in ours ours1 osd ours_anim osd_anim; do
  printf "%-10s %s   [%s]\n" "$k" "$(echo "${t[$k]}" | tr ' ' '\n' | grep . | stats)" "${t[$k]}"
done
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
