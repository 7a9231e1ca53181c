#!/usr/bin/env bash
# The JavaScript package of subdiv (web/, WebAssembly by wasm-bindgen).
#
#   bash scripts/web.sh build   target/web/pkg/: subdiv.js, subdiv_bg.wasm,
#                               subdiv.d.ts, package.json, README.md
#   bash scripts/web.sh test    the node tests (web/tests/*.test.mjs) on that package,
#                               then its npm tarball installed and imported
#   bash scripts/web.sh pack    npm pack of target/web/pkg (into target/web/)
#
# Installs what it needs when missing: the wasm32-unknown-unknown target and
# wasm-bindgen-cli of the exact version web/Cargo.toml pins. Runs wasm-opt
# only where it is installed. Quick when everything is built already.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
pkg=target/web/pkg
wasm=target/web-build/wasm32-unknown-unknown/release/subdiv_web.wasm
version=$(sed -n 's/^wasm-bindgen = "=\([0-9.]*\)".*/\1/p' web/Cargo.toml)
[ -n "$version" ] || { echo "web/Cargo.toml pins no wasm-bindgen version (wasm-bindgen = \"=0.2.x\")" >&2; exit 1; }
crate_version=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -1)

install_tools() {
    if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
        rustup target add wasm32-unknown-unknown
    fi
    if [ "$(wasm-bindgen --version 2>/dev/null)" != "wasm-bindgen $version" ]; then
        # --locked first; its lock file can name a release the registry
        # has withdrawn, and then the newest compatible ones serve
        cargo install wasm-bindgen-cli --version "$version" --locked \
            || cargo install wasm-bindgen-cli --version "$version"
    fi
}

build() {
    install_tools
    cargo build --release --target wasm32-unknown-unknown --manifest-path web/Cargo.toml \
        --target-dir target/web-build --locked
    rm -rf "$pkg.tmp"
    wasm-bindgen --target web --out-dir "$pkg.tmp" --out-name subdiv "$wasm"
    if command -v wasm-opt >/dev/null; then
        wasm-opt -O3 --all-features "$pkg.tmp/subdiv_bg.wasm" -o "$pkg.tmp/subdiv_bg.opt.wasm"
        mv "$pkg.tmp/subdiv_bg.opt.wasm" "$pkg.tmp/subdiv_bg.wasm"
    fi
    cp web/README.md "$pkg.tmp/README.md"
    cp LICENSE-MIT LICENSE-APACHE "$pkg.tmp/"
    cat > "$pkg.tmp/package.json" <<JSON
{
  "name": "subdiv",
  "version": "$crate_version",
  "description": "Subdivision surfaces (Loop, Catmull-Clark, butterfly, ...) equal to OpenSubdiv, in WebAssembly",
  "license": "MIT OR Apache-2.0",
  "repository": "https://github.com/subdiv-rs/subdiv",
  "type": "module",
  "main": "subdiv.js",
  "module": "subdiv.js",
  "types": "subdiv.d.ts",
  "exports": { ".": { "types": "./subdiv.d.ts", "default": "./subdiv.js" }, "./subdiv_bg.wasm": "./subdiv_bg.wasm" },
  "files": ["subdiv.js", "subdiv.d.ts", "subdiv_bg.wasm", "subdiv_bg.wasm.d.ts", "README.md", "LICENSE-MIT", "LICENSE-APACHE"],
  "sideEffects": false,
  "keywords": ["subdivision", "mesh", "loop", "catmull-clark", "wasm", "three"]
}
JSON
    rm -rf "$pkg"
    mv "$pkg.tmp" "$pkg"
    echo "$pkg: $(wc -c < "$pkg/subdiv_bg.wasm") bytes of wasm ($(gzip -9c "$pkg/subdiv_bg.wasm" | wc -c) gzipped)"
}

pack() {
    [ -f "$pkg/subdiv.js" ] || { echo "no $pkg: run bash scripts/web.sh build first" >&2; exit 1; }
    rm -f target/web/subdiv-*.tgz
    (cd target/web && npm pack --silent ./pkg >/dev/null)
    ls target/web/subdiv-*.tgz
}

run_tests() {
    [ -f "$pkg/subdiv.js" ] || { echo "no $pkg: run bash scripts/web.sh build first" >&2; exit 1; }
    SUBDIV_PKG="$root/$pkg" node --test web/tests/
    # the tarball npm would publish installs (offline: no dependencies) and imports by name
    local tgz dir
    tgz=$(pack)
    dir=$(mktemp -d)
    trap 'rm -rf "$dir"' RETURN
    (cd "$dir" && npm init -y >/dev/null && npm install --offline --no-audit --no-fund --silent "$root/$tgz" \
        && cp "$root/web/tests/tarball-check.mjs" . && node tarball-check.mjs)
}

case "${1:-}" in
    build) build ;;
    test) run_tests ;;
    pack) pack ;;
    *) echo "usage: bash scripts/web.sh build|test|pack" >&2; exit 2 ;;
esac
