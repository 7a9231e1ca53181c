#!/usr/bin/env bash
# subdiv in the browser (web/, WebAssembly by wasm-bindgen).
#
#   bash scripts/web.sh build   target/web/: index.html and main.js (the page),
#                               viewer/ (the viewer: subdiv_viewer.js and its wasm),
#                               pkg/ (the JavaScript package: subdiv.js, subdiv_bg.wasm,
#                               subdiv.d.ts, package.json, README.md)
#   bash scripts/web.sh serve [PORT]   serves target/web on 127.0.0.1 (default 8080)
#   bash scripts/web.sh test    the node tests (web/tests/*.test.mjs) on that package,
#                               then its npm tarball installed and imported
#   bash scripts/web.sh browser the page in headless Chromium on WebGPU and WebGL2
#                               (web/tests/browser; installs playwright-core by npm)
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
viewer=target/web/viewer
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

# wasm-bindgen of the crate built with features $1 into $2 as $3(.js, _bg.wasm)
bindgen() {
    cargo build --release --target wasm32-unknown-unknown --manifest-path web/Cargo.toml \
        --target-dir target/web-build --locked ${1:+--features "$1"}
    rm -rf "$2.tmp"
    wasm-bindgen --target web --out-dir "$2.tmp" --out-name "$3" "$wasm"
    if command -v wasm-opt >/dev/null; then
        wasm-opt -O3 --all-features "$2.tmp/$3_bg.wasm" -o "$2.tmp/$3_bg.opt.wasm"
        mv "$2.tmp/$3_bg.opt.wasm" "$2.tmp/$3_bg.wasm"
    fi
}

build() {
    install_tools
    # the viewer first: the package's build is then the one the wasm path holds
    bindgen viewer "$viewer" subdiv_viewer
    rm -rf "$viewer" && mv "$viewer.tmp" "$viewer"
    cp web/page/index.html web/page/main.js target/web/
    echo "$viewer: $(wc -c < "$viewer/subdiv_viewer_bg.wasm") bytes of wasm ($(gzip -9c "$viewer/subdiv_viewer_bg.wasm" | wc -c) gzipped)"
    bindgen "" "$pkg" subdiv
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
    SUBDIV_PKG="$root/$pkg" node --test web/tests/*.test.mjs
    # the tarball npm would publish installs (offline: no dependencies) and imports by name
    local tgz dir
    tgz=$(pack)
    dir=$(mktemp -d)
    trap 'rm -rf "$dir"' RETURN
    (cd "$dir" && npm init -y >/dev/null && npm install --offline --no-audit --no-fund --silent "$root/$tgz" \
        && cp "$root/web/tests/tarball-check.mjs" . && node tarball-check.mjs)
}

browser() {
    [ -f target/web/index.html ] || { echo "no target/web/index.html: run bash scripts/web.sh build first" >&2; exit 1; }
    command -v chromium >/dev/null || { echo "no chromium: apt-get install chromium" >&2; exit 1; }
    (cd web/tests/browser && npm ci --no-audit --no-fund --silent)
    SUBDIV_WEB="$root/target/web" SUBDIV_MODELS="$root/models" SUBDIV_FIXTURES="$root/tests/fixtures" node --test web/tests/browser/
}

case "${1:-}" in
    build) build ;;
    serve) exec node web/tests/browser/serve.mjs target/web "${2:-8080}" ;;
    test) run_tests ;;
    browser) browser ;;
    pack) pack ;;
    *) echo "usage: bash scripts/web.sh build|serve [PORT]|test|browser|pack" >&2; exit 2 ;;
esac
