#!/usr/bin/env bash
# Every test: the Rust workspace (engine, game, image and window tests),
# then the Python module built as a wheel with maturin and tested with
# pytest. Needs what .ci/run installs (Mesa's lavapipe, Xvfb) and pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace --release
python3 -m pip install --quiet --disable-pip-version-check .
python3 -m pytest -q tests/python
