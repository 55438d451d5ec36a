#!/usr/bin/env bash
# The browser test (docs/web.md): serves web/dist/ (built by scripts/web.sh)
# on a local port and runs web/tests/page.mjs in Debian's headless Chromium
# with software WebGL2 (SwiftShader). Installs chromium (apt) and
# playwright-core (npm, web/tests/package.json) if missing. Writes
# docs/web_default.png (and docs/web_default_ten_pucks.png).
set -euo pipefail
cd "$(dirname "$0")/.."

[ -f web/dist/index.html ] || { echo "web/dist/ not built: run scripts/web.sh" >&2; exit 1; }
if ! command -v chromium >/dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq chromium
fi
[ -d web/tests/node_modules/playwright-core ] ||
  (cd web/tests && npm install --no-audit --no-fund --silent)

port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 -m http.server -b 127.0.0.1 -d web/dist "$port" >/dev/null 2>&1 &
server=$!
trap 'kill $server; [ -z "${native:-}" ] || rm -f "$native" "${native%.png}.json"; [ -z "${observed:-}" ] || rm -f "$observed"' EXIT
for _ in $(seq 50); do
  python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/')" 2>/dev/null && break
  sleep 0.1
done

# The window's own screenshot of the default scene, for the parity test
# (when the native game is built and Xvfb is here: after scripts/test.sh).
lightcone="${CARGO_TARGET_DIR:-target}/release/lightcone"
native=""
if [ -x "$lightcone" ] && command -v xvfb-run >/dev/null; then
  native=$(mktemp --suffix=.png)
  if ! xvfb-run -a -s "-screen 0 1280x720x24" "$lightcone" play --screenshot "$native" --frames 30 >/dev/null 2>&1; then
    rm -f "$native" "${native%.png}.json"
    native=""
  fi
fi
# And what the native build sees of ten_pucks at 3 s, for the same-numbers
# test.
observed=""
if [ -x "$lightcone" ]; then
  observed=$(mktemp --suffix=.json)
  "$lightcone" observe assets/scenes/ten_pucks.toml --at 3 >"$observed" || observed=""
fi
NATIVE_OBSERVE="$observed" NATIVE_PNG="$native" node web/tests/page.mjs "http://127.0.0.1:$port/" docs/web_default.png
# The lesson's worker on its own (the game's part played by the test).
node web/tests/lesson_worker.mjs web/dist
# Every shipped lesson in the page against `lightcone lesson --json` on
# the desktop (when the native game is built: after scripts/test.sh).
if [ -x "$lightcone" ]; then
  outcomes=$(mktemp --suffix=.json)
  python3 - "$lightcone" "$outcomes" <<'PY'
import json, pathlib, subprocess, sys
exe, out = sys.argv[1], sys.argv[2]
outcomes = {}
for path in sorted(pathlib.Path("scripts/lessons").glob("*.py")):
    run = subprocess.run([exe, "lesson", str(path), "--json"], capture_output=True, text=True, timeout=600)
    outcomes[path.name] = json.loads(run.stdout)
pathlib.Path(out).write_text(json.dumps(outcomes))
PY
  NATIVE_LESSONS="$outcomes" node web/tests/lessons.mjs "http://127.0.0.1:$port/" docs/web_lesson.png
  rm -f "$outcomes"
fi
# The download: the wasm gzipped (as a server sends it), and the JS glue.
wasm=web/dist/lightcone_web_bg.wasm
echo "wasm $(stat -c %s $wasm) bytes, gzipped $(gzip -9 -c $wasm | wc -c) bytes; JS glue $(stat -c %s web/dist/lightcone_web.js) bytes"
