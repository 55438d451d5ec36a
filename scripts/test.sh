#!/usr/bin/env bash
# Every test: the Rust workspace (engine, game, image and window tests),
# then the Python module built as a wheel with maturin, its type stubs
# checked against it (mypy.stubtest) and its tests run with pytest. The
# lessons in scripts/lessons run inside `cargo test` (tests/lessons.rs),
# through the game's embedded interpreter. Needs what .ci/run installs
# (Mesa's lavapipe, Xvfb, pytest, mypy; nbclient, ipykernel and matplotlib
# for the tour notebook).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace --release
python3 -m pip install --quiet --disable-pip-version-check .
python3 -m mypy.stubtest lightcone._lightcone
python3 -m pytest -q tests/python
