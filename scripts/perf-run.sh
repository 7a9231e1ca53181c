#!/usr/bin/env bash
# The figures of docs/performance.md, "Where it stands": ours beside OpenSubdiv in the
# same run. Each measure is a cold process (one command, as a user runs it), REPS rounds
# (default 7), every measure once per round in the same order, so that all of them see
# the same load; they are compared by their minima (the run least disturbed by the
# host's other tenants), medians and max/min beside them. The load average is printed
# before and after. Needs the peers built by
#   bash ../shared/bench/native/build.sh PEERS   (apt-get install g++ libosd-dev)
# Usage: scripts/perf-run.sh [PEERS_DIR] [REPS]; MODELS=dir overrides ../shared/models.
#
# Ours is `subdivide_ms` of `subdivide --stats` (the levels, after reading, before
# writing) on 2 threads and, with `--threads 1`, on one. OpenSubdiv's is osd_bench's
# refine_ms + interpolate_ms (full topology in the last level, then the positions), one
# thread (it has no threaded refinement), without create_ms (its topology from the
# file's faces, which our reading does before subdivide_ms starts).
#   bunny   Loop level 3 of the Stanford bunny (69,451 triangles; 4.4 M after)
#   bunnyC  the same with --boundary edge-and-corner (OpenSubdiv: --corners)
#   fan     Loop level 3 of fandisk with --crease-angle 40 (710 infinitely sharp
#           edges; OpenSubdiv reads the same tags from the file our level 0 writes)
#   cc      Catmull-Clark level 3 of a quad mesh of 70,272 faces (spot after two
#           Catmull-Clark levels; 4.5 M quads after)
#   anim    per frame at bunny level 2, ours positions and normals, OpenSubdiv's
#           StencilTable positions only (minimum within the process)
#   ply     the whole command, bunny level 3 into a new binary PLY (wall time)
set -euo pipefail
cd "$(dirname "$0")/.."
peers="${1:-/tmp/peers}"; reps="${2:-7}"
models="${MODELS:-../shared/models}"
bin="${CARGO_TARGET_DIR:-target}/release/subdiv"
bunny="$models/stanford-bunny-compact.obj"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
ln -s /dev/null "$tmp/null.ply"
fan="$tmp/fandisk40.obj"; quads="$tmp/spot_q70k.obj"
"$bin" -q subdivide "$models/fandisk.obj" "$fan" --levels 0 --crease-angle 40 >/dev/null
"$bin" -q subdivide "$models/spot.obj" "$quads" -s catmull-clark --levels 2 >/dev/null
field() { grep -o "$1=[0-9.]*" | head -1 | cut -d= -f2; }
stats() { sort -g | awk '{a[NR]=$1} END {printf "min %7.1f  median %7.1f  max/min %.2f", a[1], a[int((NR+1)/2)], a[NR]/a[1]}'; }
ours() { "$bin" -q "$@" --stats | field subdivide_ms; }
osd() { local o; o="$("$peers/osd_bench" "$@")"; echo "$(echo "$o" | field refine_ms) + $(echo "$o" | field interpolate_ms)" | bc; }
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)  cores: $(nproc)"
declare -A t
keys="bunny2 bunny1 bunnyOSD bunnyC2 bunnyC1 bunnyCOSD fan2 fan1 fanOSD cc2 cc1 ccOSD anim animOSD ply"
for _ in $(seq "$reps"); do
  t[bunny2]+="$(ours subdivide "$bunny" "$tmp/null.ply" --levels 3) "
  t[bunny1]+="$(ours --threads 1 subdivide "$bunny" "$tmp/null.ply" --levels 3) "
  t[bunnyOSD]+="$(osd "$bunny" 3 loop) "
  t[bunnyC2]+="$(ours subdivide "$bunny" "$tmp/null.ply" --levels 3 --boundary edge-and-corner) "
  t[bunnyC1]+="$(ours --threads 1 subdivide "$bunny" "$tmp/null.ply" --levels 3 --boundary edge-and-corner) "
  t[bunnyCOSD]+="$(osd "$bunny" 3 loop --corners) "
  t[fan2]+="$(ours subdivide "$fan" "$tmp/null.ply" --levels 3) "
  t[fan1]+="$(ours --threads 1 subdivide "$fan" "$tmp/null.ply" --levels 3) "
  t[fanOSD]+="$(osd "$fan" 3 loop) "
  t[cc2]+="$(ours subdivide "$quads" "$tmp/null.ply" -s cc --levels 3) "
  t[cc1]+="$(ours --threads 1 subdivide "$quads" "$tmp/null.ply" -s cc --levels 3) "
  t[ccOSD]+="$(osd "$quads" 3 catmark) "
  t[anim]+="$("$bin" animate --model "$bunny" --level 2 --refine 4 --stats | field frame_min_ms) "
  t[animOSD]+="$("$peers/osd_bench" "$bunny" 2 loop --frames 64 | grep stencils= | field frame_min_ms) "
  s=$(date +%s.%N); "$bin" subdivide "$bunny" "$tmp/out.ply" --levels 3 >/dev/null
  t[ply]+="$(echo "($(date +%s.%N) - $s) * 1000" | bc) "
  rm -f "$tmp/out.ply"
done
declare -A lo
for k in $keys; do
  line="$(echo "${t[$k]}" | tr ' ' '\n' | grep . | stats)"
  lo[$k]="$(echo "$line" | awk '{print $2}')"
  printf "%-10s %s   [%s]\n" "$k" "$line" "${t[$k]}"
done
echo "ratios of minima, OpenSubdiv / ours (2 threads, 1 thread):"
for m in bunny bunnyC fan cc; do
  printf "  %-7s %5.1fx  %5.1fx\n" "$m" "$(echo "${lo[${m}OSD]} / ${lo[${m}2]}" | bc -l)" "$(echo "${lo[${m}OSD]} / ${lo[${m}1]}" | bc -l)"
done
printf "  %-7s %5.2f (ours / OpenSubdiv per frame)\n" anim "$(echo "${lo[anim]} / ${lo[animOSD]}" | bc -l)"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
