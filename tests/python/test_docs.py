"""The Python tour in docs/ runs (and plots, when matplotlib is installed)."""

import os
import subprocess
import sys

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")


def test_the_tour_runs_and_draws(tmp_path):
    run = subprocess.run(
        [sys.executable, os.path.join(ROOT, "docs", "python_tour.py"), str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0, run.stderr
    assert "puck_puck" in run.stdout
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        assert "no plot" in run.stdout
    else:
        assert (tmp_path / "tour_worldlines.png").stat().st_size > 1000
