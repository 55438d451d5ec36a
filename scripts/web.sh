#!/usr/bin/env bash
# Builds the browser version of the game into web/dist/: index.html, the
# game compiled to wasm32-unknown-unknown (the `web` crate), wasm-bindgen's
# JS glue. The shipped scenes are built into the wasm (game/src/assets.rs)
# and also copied to dist/scenes/ for reference. Lessons run in a Web
# Worker (lesson_host.js starts lesson_worker.js) on Pyodide: its runtime
# in dist/pyodide/ (the npm package pinned in web/package.json, installed
# if missing), the `lightcone` package and the lesson protocol's Python in
# dist/python/. Serve it with any static file server:
# python3 -m http.server -d web/dist
#
# Needs the wasm32 target (rust-toolchain.toml names it), wasm-bindgen-cli
# of exactly the wasm-bindgen version in Cargo.lock (installed if missing)
# and npm.
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

# The game, and the engine a lesson's worker calls (web-engine/), in one
# build (they share the engine's crates).
cargo build --release --target wasm32-unknown-unknown -p lightcone-web -p lightcone-engine-web
rm -rf web/dist
mkdir -p web/dist/scenes
wasm-bindgen --target web --no-typescript --out-dir web/dist \
  "${CARGO_TARGET_DIR:-target}/wasm32-unknown-unknown/release/lightcone_web.wasm"
cp web/static/index.html web/dist/
cp assets/scenes/*.toml web/dist/scenes/

# Lessons: the page's host and the worker.
cp web/static/lesson_host.js web/static/lesson_worker.js web/static/coi.js web/static/coi_sw.js web/dist/
# Pyodide's runtime, only what `loadPyodide` fetches to start with its
# standard library (no package of its own: lessons need none), so nothing
# comes from another host at run time.
[ -f web/node_modules/pyodide/package.json ] &&
  [ "$(node -p 'require("./web/node_modules/pyodide/package.json").version')" = \
    "$(node -p 'require("./web/package.json").dependencies.pyodide')" ] ||
  (cd web && npm install --no-audit --no-fund --silent)
mkdir -p web/dist/pyodide
for f in pyodide.mjs pyodide.asm.mjs pyodide.asm.wasm python_stdlib.zip pyodide-lock.json; do
  cp "web/node_modules/pyodide/$f" web/dist/pyodide/
done
# The Python a lesson's worker writes into Pyodide's file system, at the
# paths it imports them by: the wheel's own package, its `_lightcone`
# being the web stand-in (web/python/_lightcone.py, given the workspace's
# version), the protocol's lesson side (game/src/lesson/remote.py), the
# bootstrap's stdout tee, and the worker's loop.
mkdir -p web/dist/python/lightcone
cp py/python/lightcone/__init__.py py/python/lightcone/records.py web/dist/python/lightcone/
workspace_version=$(awk -F'"' '/^\[workspace.package\]/ { p = 1 } p && /^version = / { print $2; exit }' Cargo.toml)
sed "s/^__version__ = .*/__version__ = \"$workspace_version\"/" web/python/_lightcone.py >web/dist/python/lightcone/_lightcone.py
cp game/src/lesson/remote.py web/dist/python/lightcone_remote.py
cp game/src/lesson/bootstrap.py web/dist/python/lightcone_bootstrap.py
cp web/python/lightcone_web_child.py web/dist/python/
# The engine the worker's Scene and Simulation call (web-engine/, built
# above): lightcone_engine_web.js and its _bg.wasm.
wasm-bindgen --target web --no-typescript --out-dir web/dist \
  "${CARGO_TARGET_DIR:-target}/wasm32-unknown-unknown/release/lightcone_engine_web.wasm"
ls -l web/dist
