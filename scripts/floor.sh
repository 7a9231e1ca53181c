#!/usr/bin/env bash
# The floor of a subdivision on this machine: what its fresh pages alone cost, before a
# byte is computed (docs/performance.md, "The floor").
#   fresh MB   the peak resident memory of `subdivide --levels L` less that of
#              `--levels 0` (the same reading, nothing refined), both written to
#              /dev/null: every page the levels touched for the first time;
#   page cost  scripts/page-cost.c: the first touch of 256 MiB of fresh 4 KiB pages;
#   floor      fresh pages x page cost, CPU time; the wall time on T threads is about
#              a T-th of it, as the pages are faulted in over all threads.
# Minima over REPS runs each, interleaved.
# Usage: scripts/floor.sh MODEL LEVELS [REPS] [subdivide options...]
set -euo pipefail
cd "$(dirname "$0")/.."
model="$1"; levels="$2"; reps="${3:-5}"; shift $(( $# < 3 ? $# : 3 ))
bin="${CARGO_TARGET_DIR:-target}/release/subdiv"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
ln -s /dev/null "$tmp/null.ply"
gcc -O2 scripts/page-cost.c -o "$tmp/page-cost"
rss() { /usr/bin/time -f "%M" "$bin" -q subdivide "$model" "$tmp/null.ply" --levels "$1" "${@:2}" 2>&1 >/dev/null | tail -1; }
min() { tr ' ' '\n' | grep . | sort -g | head -1; }
r0=""; rl=""; touch_ms=""; sub=""
for _ in $(seq "$reps"); do
  r0+="$(rss 0 "$@") "; rl+="$(rss "$levels" "$@") "
  sub+="$("$bin" subdivide "$model" "$tmp/null.ply" --levels "$levels" --stats "$@" | grep -o 'subdivide_ms=[0-9.]*' | cut -d= -f2) "
  touch_ms+="$("$tmp/page-cost" 0 | sed 's/.*first touch \([0-9.]*\) ms.*/\1/') "
done
r0="$(echo "$r0" | min)"; rl="$(echo "$rl" | min)"; touch_ms="$(echo "$touch_ms" | min)"
fresh_kb=$(( rl - r0 ))
per_page_us="$(echo "$touch_ms * 1000 / 65536" | bc -l)"
floor_ms="$(echo "$fresh_kb / 4 * $per_page_us / 1000" | bc -l)"
printf "model %s, %s levels, load %s\n" "$(basename "$model")" "$levels" "$(cut -d' ' -f1-3 /proc/loadavg)"
printf "fresh memory  %.1f MB (peak resident %.1f MB at %s levels, %.1f MB at 0)\n" \
  "$(echo "$fresh_kb / 1024" | bc -l)" "$(echo "$rl / 1024" | bc -l)" "$levels" "$(echo "$r0 / 1024" | bc -l)"
printf "page cost     %.2f us a 4 KiB page (first touch of 256 MiB: %s ms, minimum of %s)\n" "$per_page_us" "$touch_ms" "$reps"
printf "floor         %.1f ms of CPU: %.1f ms of wall time on 2 threads\n" "$floor_ms" "$(echo "$floor_ms / 2" | bc -l)"
printf "subdivide_ms  min %.1f (2 threads) of [%s]\n" "$(echo "$sub" | min)" "$sub"
