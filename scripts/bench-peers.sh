#!/usr/bin/env bash
# Times our CLI beside the peer libraries (VTK, libigl, pymeshlab, trimesh,
# Open3D) with ../shared/bench/peers.py and prints one table per row:
#   bunny loop L3, bunny butterfly L3, bunny modified butterfly L3 (VTK's
#   mbutterfly), bunny midpoint L3, icosphere 1,310,720 faces loop L1.
# Our figure is the whole process (load, subdivide, write OBJ) plus the
# subdivision call alone (subdivide_ms); the peers' figures are the call alone.
#
# Usage: scripts/bench-peers.sh            (from anywhere)
#   REPEATS  timed repeats per peer (default 3)
#   VENV     the peers' virtual environment (default $HOME/.cache/peers-venv;
#            created once with ../shared/bench/setup_peers.sh, a few minutes)
#   CACHE    where the generated icosphere is kept (default $HOME/.cache/subdiv-bench)
#   ROWS     space-separated subset of: loop butterfly mbutterfly midpoint icosphere
#   PEERS    comma-separated peers to time (default: all; e.g. vtk,igl for a
#            quick run: trimesh and open3d take minutes per row)
#   BUILD_FLAGS  extra cargo build flags (e.g. --no-default-features: skips the
#            viewer, the binary's subdivide command is the same)
# The machine is shared: only ratios within one table are comparable.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
shared="$(cd "$here/.." && pwd)/shared"
if [ ! -d "$shared/bench" ] || [ ! -f "$shared/bench/peers.py" ]; then
    echo "bench-peers: $shared/bench (peers.py, setup_peers.sh) not found next to the repository;" >&2
    echo "  this script needs the shared checkout at ../shared" >&2
    exit 2
fi
REPEATS="${REPEATS:-3}"
VENV="${VENV:-$HOME/.cache/peers-venv}"
CACHE="${CACHE:-$HOME/.cache/subdiv-bench}"
ROWS="${ROWS:-loop butterfly mbutterfly midpoint icosphere}"
bunny="$shared/models/stanford-bunny-compact.obj"
ico0="$shared/models/procedural/icosphere0.obj"

echo "== building the release binary" >&2
(cd "$here" && cargo build --release ${BUILD_FLAGS:-})
bin="$here/target/release/subdiv"

if [ ! -x "$VENV/bin/python" ]; then
    echo "== setting up the peers venv in $VENV (once, a few minutes)" >&2
    bash "$shared/bench/setup_peers.sh" "$VENV"
fi
PY="$VENV/bin/python"
export PEERS_LIBDIR="${PEERS_LIBDIR:-$VENV/sysroot/usr/lib/x86_64-linux-gnu}"

# icosphere0 + 8 midpoint levels, every vertex projected to the unit sphere
ico="$CACHE/icosphere-1310720.obj"
if [ ! -s "$ico" ]; then
    echo "== generating $ico" >&2
    mkdir -p "$CACHE"
    "$bin" subdivide "$ico0" "$CACHE/ico-flat.obj" --scheme midpoint --levels 8 >/dev/null
    awk '$1 == "v" { l = sqrt($2*$2 + $3*$3 + $4*$4); printf "v %.9g %.9g %.9g\n", $2/l, $3/l, $4/l; next } { print }' \
        "$CACHE/ico-flat.obj" >"$ico.tmp"
    mv "$ico.tmp" "$ico"
    rm -f "$CACHE/ico-flat.obj"
fi

ours="$bin subdivide {in} {out} --scheme {scheme} --levels {levels} --stats"
run() { # title, mesh, then peers.py arguments
    local title="$1" mesh="$2"
    shift 2
    echo
    echo "### $title"
    "$PY" "$shared/bench/peers.py" "$mesh" --repeats "$REPEATS" ${PEERS:+--peers "$PEERS"} --ours "$ours" "$@"
}
for row in $ROWS; do
    case "$row" in
    loop) run "stanford-bunny-compact, loop, level 3" "$bunny" --scheme loop --levels 3 ;;
    butterfly) run "stanford-bunny-compact, butterfly, level 3" "$bunny" --scheme butterfly --levels 3 ;;
    mbutterfly)
        run "stanford-bunny-compact, modified butterfly, level 3" "$bunny" --scheme mbutterfly \
            --ours-scheme modified-butterfly --levels 3
        ;;
    midpoint) run "stanford-bunny-compact, midpoint, level 3" "$bunny" --scheme midpoint --levels 3 ;;
    icosphere) run "icosphere 1,310,720 faces, loop, level 1" "$ico" --scheme loop --levels 1 ;;
    *) echo "bench-peers: unknown row '$row'" >&2 && exit 2 ;;
    esac
done
