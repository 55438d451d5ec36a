#!/usr/bin/env python3
"""Lists the crates the Python wheel's build (`pip install .`, only
lightcone-py's dependencies) compiles with other features than the whole
workspace's build (`cargo test --workspace`): each such crate, and all
that depend on it, is compiled twice in `scripts/test.sh`. The aligning
dependencies are at the end of py/Cargo.toml. Expected: only pyo3
(`auto-initialize`, which the game turns on and the wheel must not).
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
    found = {}
    for line in out.splitlines():
        line = line.strip().replace(" (*)", "")
        if "|" in line:
            package, names = line.split("|", 1)
            found.setdefault(package, set()).update(n for n in names.split(",") if n)
    if not found:
        sys.exit(f"feature_drift: cargo tree {' '.join(args)} listed no crates")
    return found


wheel = features("-p", "lightcone-py", "-e", "normal,build")
workspace = features("--workspace", "-e", "normal,build,dev")
drift = {
    p: sorted(workspace[p] - f) + sorted("-" + x for x in f - workspace[p])
    for p, f in wheel.items()
    if p in workspace and f != workspace[p]
}
for package, diff in sorted(drift.items()):
    print(f"{package}: {' '.join(diff)}")
sys.exit(0 if all(p.startswith("pyo3 ") for p in drift) else 1)
