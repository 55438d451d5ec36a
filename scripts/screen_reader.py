#!/usr/bin/python3
"""The window as a screen reader sees it (issue 32, item 5): reads the
running game's accessibility tree over AT-SPI (Linux's screen-reader bus,
what Orca reads), checks that the panel's controls are there by name and
role, presses "play (P)" through AT-SPI's Action interface, and checks
that the game answered (the button now reads "pause (P)").

Run by scripts/screen_reader_test.sh inside a private D-Bus session (it
needs Debian's python3-pyatspi, at-spi2-core; the system Python, where
the `gi` bindings live). Exit status 0 when every check holds."""

import sys
import time

import gi

gi.require_version("Atspi", "2.0")
from gi.repository import Atspi  # noqa: E402

# (role, name) the panel must offer a screen reader.
EXPECTED = [
    ("push button", "play (P)"),
    ("push button", "restart"),
    ("slider", "c (m/s)"),
    ("spin button", "c (m/s)"),
    ("check box", "contraction"),
    ("check box", "light_delay"),
    ("toggle button", "split"),
    ("combo box", "eye"),
    ("push button", "start (Space)"),
]


def nodes(node, out):
    """Every accessible under `node`, as (role, name, node)."""
    try:
        out.append((node.get_role_name(), node.get_name(), node))
        for i in range(node.get_child_count()):
            child = node.get_child_at_index(i)
            if child is not None:
                nodes(child, out)
    except gi.repository.GLib.Error:
        pass  # a node gone while read (the next frame rebuilt it)
    return out


def game_tree():
    """The game's accessibles, or [] if it has not shown up yet."""
    desktop = Atspi.get_desktop(0)
    for i in range(desktop.get_child_count()):
        app = desktop.get_child_at_index(i)
        if app is not None and app.get_name() == "lightcone":
            return nodes(app, [])
    return []


def wait_for(what, check, seconds):
    deadline = time.time() + seconds
    while time.time() < deadline:
        found = check(game_tree())
        if found:
            return found
        time.sleep(0.25)
    tree = "\n".join(f"  {r}: {n!r}" for r, n, _ in game_tree())
    sys.exit(f"screen reader: {what} not seen within {seconds} s; the tree:\n{tree}")


def main():
    tree = wait_for(
        "the panel's controls",
        lambda t: t if all(any((r, n) == e for r, n, _ in t) for e in EXPECTED) else None,
        60,
    )
    print(f"screen reader: {len(tree)} accessibles, every expected control named")
    play = next(node for r, n, node in tree if (r, n) == ("push button", "play (P)"))
    # The accessible is its own Action interface (AT-SPI's "press").
    if play.get_n_actions() < 1:
        sys.exit("screen reader: 'play (P)' offers no action")
    play.do_action(0)
    wait_for(
        "'pause (P)' after pressing 'play (P)'",
        lambda t: any((r, n) == ("push button", "pause (P)") for r, n, _ in t),
        30,
    )
    print("screen reader: pressing 'play (P)' started the game ('pause (P)' shown)")


if __name__ == "__main__":
    main()
