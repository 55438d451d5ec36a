#!/usr/bin/env bash
# The window under a screen reader's bus (issue 32, item 5): a private
# D-Bus session with the AT-SPI bus, accessibility switched on, the game
# under Xvfb, and scripts/screen_reader.py reading and pressing its panel.
# Needs: xvfb, dbus, at-spi2-core, python3-pyatspi (.ci/run installs them)
# and a built `target/release/lightcone` (under `CARGO_TARGET_DIR` if set).
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${LIGHTCONE:-${CARGO_TARGET_DIR:-target}/release/lightcone}
if [ -z "${DBUS_SESSION_BUS_ADDRESS:-}" ] || [ -z "${LIGHTCONE_IN_SESSION:-}" ]; then
  LIGHTCONE_IN_SESSION=1 exec dbus-run-session -- "$0" "$@"
fi
/usr/libexec/at-spi-bus-launcher --launch-immediately 2>/dev/null &
bus=$!
# Screen readers switch this on; AccessKit offers the tree only then.
for _ in $(seq 50); do
  if /usr/bin/python3 - 2>/dev/null <<'PY'
from gi.repository import Gio, GLib
bus = Gio.bus_get_sync(Gio.BusType.SESSION, None)
bus.call_sync("org.a11y.Bus", "/org/a11y/bus", "org.freedesktop.DBus.Properties", "Set",
  GLib.Variant("(ssv)", ("org.a11y.Status", "IsEnabled", GLib.Variant("b", True))),
  None, Gio.DBusCallFlags.NONE, -1, None)
PY
  then break; fi
  sleep 0.1
done
# Paused on its title card until "play (P)" is pressed; quits after the
# screenshot (the frames run at the screen's rate, about 60 a second).
xvfb-run -a -s "-screen 0 1280x800x24" "$exe" play --screenshot "${TMPDIR:-/tmp}/screen_reader.png" --frames 3000 \
  >"${TMPDIR:-/tmp}/screen_reader_game.log" 2>&1 &
game=$!
status=0
/usr/bin/python3 scripts/screen_reader.py || status=$?
kill "$game" "$bus" 2>/dev/null || true
wait "$game" 2>/dev/null || true
exit $status
