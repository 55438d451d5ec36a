#!/usr/bin/env python3
"""Lists the crates the Python wheel's build (`pip install .`, only
lightcone-py's dependencies) compiles with other features than the whole
workspace's build (`cargo test --workspace`): each such crate, and all
that depend on it, is compiled twice in `scripts/test.sh`. The aligning
dependencies are at the end of py/Cargo.toml. Expected: only pyo3
(`auto-initialize`, which the game turns on and the wheel must not).
The same for `cargo install --path game` (tests/install.rs), whose
aligning dependencies are in game/Cargo.toml: expected none.
Exit status 1 if any other crate differs."""

import subprocess
import sys


def features(*args):
    run = subprocess.run(
        ["cargo", "tree", *args, "--prefix", "none", "-f", "{p}|{f}"],
        capture_output=True,
        text=True,
    )
    if run.returncode != 0:
        sys.exit(f"feature_drift: cargo tree {' '.join(args)} failed:\n{run.stderr}")
    out = run.stdout
    # A crate built both for the host (build scripts, proc-macros) and the
    # target has a feature set for each: compare the sets, not their union.
    found = {}
    for line in out.splitlines():
        line = line.strip().replace(" (*)", "")
        if "|" in line:
            package, names = line.split("|", 1)
            found.setdefault(package, set()).add(
                frozenset(n for n in names.split(",") if n)
            )
    if not found:
        sys.exit(f"feature_drift: cargo tree {' '.join(args)} listed no crates")
    return found


def drift(alone, workspace):
    def show(variants):
        return " / ".join(sorted(",".join(sorted(v)) or "(none)" for v in variants))

    return {
        p: [f"workspace {show(workspace[p])}", f"alone {show(f)}"]
        for p, f in alone.items()
        if p in workspace and not f <= workspace[p]
    }


workspace = features("--workspace", "-e", "normal,build,dev")
wheel = drift(features("-p", "lightcone-py", "-e", "normal,build"), workspace)
game = drift(features("-p", "lightcone", "-e", "normal,build"), workspace)
for package, diff in sorted(wheel.items()):
    print(f"wheel: {package}: {' '.join(diff)}")
for package, diff in sorted(game.items()):
    print(f"cargo install --path game: {package}: {' '.join(diff)}")
ok = all(p.startswith("pyo3 ") for p in wheel) and not game
sys.exit(0 if ok else 1)
