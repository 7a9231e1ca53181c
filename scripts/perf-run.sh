#!/usr/bin/env bash
# One run of the figures in docs/performance.md: ours and OpenSubdiv's in the
# same run, medians (and min/max) over REPS repetitions, interleaved so that
# both see the same load. Needs the peers built by
#   bash ../shared/bench/native/build.sh PEERS   (apt-get install g++ libosd-dev)
# Usage: scripts/perf-run.sh [PEERS_DIR] [REPS]; MODELS=dir overrides ../shared/models.
# cmd_obj, cmd_ply: `subdivide` bunny L3 over an existing file of the same size;
# new_obj, new_ply: into a new file (no old file to free).
set -euo pipefail
cd "$(dirname "$0")/.."
peers="${1:-/tmp/peers}"; reps="${2:-5}"
models="${MODELS:-../shared/models}"
bin="${CARGO_TARGET_DIR:-target}/release/subdiv"
bunny="$models/stanford-bunny-compact.obj"; nef="$models/nefertiti.obj"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
ln -s /dev/null "$tmp/null.ply"
field() { grep -o "$1=[0-9.]*" | head -1 | cut -d= -f2; }
stats() { sort -g | awk '{a[NR]=$1} END {printf "median %.1f  min %.1f  max %.1f  max/min %.2f", a[int((NR+1)/2)], a[1], a[NR], a[NR]/a[1]}'; }
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)  threads: $(nproc)"
declare -A t
for _ in $(seq "$reps"); do
  t[ours_L3]+="$("$bin" subdivide "$bunny" "$tmp/null.ply" --levels 3 --stats | field subdivide_ms) "
  t[osd_L3]+="$("$peers/osd_bench" "$bunny" 3 loop | field subdivide_ms) "
  t[ours_nef4]+="$("$bin" subdivide "$nef" "$tmp/null.ply" --levels 4 --stats | field subdivide_ms) "
  t[ours_anim]+="$("$bin" animate --model "$bunny" --level 2 --refine 4 --stats | field frame_ms) "
  t[osd_anim]+="$("$peers/osd_bench" "$bunny" 2 loop --frames 64 | grep stencils= | field frame_ms) "
  # the whole command over the file of the round before (the replaced
  # file, its blocks and cached pages, is freed inside the command's rename),
  # then into a new file
  for ext in obj ply; do
    s=$(date +%s.%N); "$bin" subdivide "$bunny" "$tmp/out.$ext" --levels 3 >/dev/null
    t[cmd_$ext]+="$(echo "($(date +%s.%N) - $s) * 1000" | bc) "
    rm -f "$tmp/out.$ext"; sync
    s=$(date +%s.%N); "$bin" subdivide "$bunny" "$tmp/out.$ext" --levels 3 >/dev/null
    t[new_$ext]+="$(echo "($(date +%s.%N) - $s) * 1000" | bc) "
  done
done
for k in ours_L3 osd_L3 ours_nef4 ours_anim osd_anim cmd_obj new_obj cmd_ply new_ply; do
  printf "%-10s %s   [%s]\n" "$k" "$(echo "${t[$k]}" | tr ' ' '\n' | grep . | stats)" "${t[$k]}"
done
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
