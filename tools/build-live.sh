#!/usr/bin/env bash
# Builds the live lab (wasm/) for the browser: the renderer compiled to wasm32 and its
# JavaScript glue from wasm-bindgen-cli, pinned to the wasm-bindgen version wasm/Cargo.toml
# names. Writes target/live/shadelab_wasm.js and shadelab_wasm_bg.wasm, where
# `shadelab site` finds them (or give the folder with --live DIR / SHADELAB_LIVE).
set -euo pipefail
cd "$(dirname "$0")/.."
version=$(sed -n 's/^wasm-bindgen = "=\(.*\)"/\1/p' wasm/Cargo.toml)
rustup target add wasm32-unknown-unknown >/dev/null 2>&1 || true
bindgen=${WASM_BINDGEN:-wasm-bindgen}
if ! "$bindgen" --version 2>/dev/null | grep -q " $version\$"; then
    # Its own folder, so another wasm-bindgen on the PATH is left alone.
    cargo install wasm-bindgen-cli --version "=$version" --root target/wasm-bindgen-cli
    bindgen=target/wasm-bindgen-cli/bin/wasm-bindgen
fi
# simd128: the portable lanes compile to WebAssembly SIMD (every current browser has it).
RUSTFLAGS="${RUSTFLAGS:-} -C target-feature=+simd128" \
    cargo build --release --locked -p shadelab-wasm --target wasm32-unknown-unknown
"$bindgen" --target no-modules --no-typescript --out-dir target/live \
    target/wasm32-unknown-unknown/release/shadelab_wasm.wasm
echo "live lab: target/live/shadelab_wasm.js and shadelab_wasm_bg.wasm ($(du -h target/live/shadelab_wasm_bg.wasm | cut -f1))"
