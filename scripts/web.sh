#!/usr/bin/env bash
# Builds the browser version of the game into web/dist/: index.html, the
# game compiled to wasm32-unknown-unknown (the `web` crate), wasm-bindgen's
# JS glue. The shipped scenes are built into the wasm (game/src/assets.rs)
# and also copied to dist/scenes/ for reference. Serve it with any static
# file server: python3 -m http.server -d web/dist
#
# Needs the wasm32 target (rust-toolchain.toml names it) and wasm-bindgen-cli
# of exactly the wasm-bindgen version in Cargo.lock (installed if missing).
set -euo pipefail
cd "$(dirname "$0")/.."

version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)
if [ "$(wasm-bindgen --version 2>/dev/null | awk '{print $2}')" != "$version" ]; then
  # Not --locked: the CLI's own lock names crates the registry may lack.
  # Not under a clippy wrapper CI may have exported for the game: the
  # tool's own code is not ours to lint.
  env -u RUSTC_WORKSPACE_WRAPPER -u CLIPPY_ARGS cargo install wasm-bindgen-cli --version "$version"
fi
rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown ||
  rustup target add wasm32-unknown-unknown

cargo build --release --target wasm32-unknown-unknown -p lightcone-web
rm -rf web/dist
mkdir -p web/dist/scenes
wasm-bindgen --target web --no-typescript --out-dir web/dist \
  "${CARGO_TARGET_DIR:-target}/wasm32-unknown-unknown/release/lightcone_web.wasm"
cp web/static/index.html web/dist/
cp assets/scenes/*.toml web/dist/scenes/
ls -l web/dist
