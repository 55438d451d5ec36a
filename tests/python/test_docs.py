"""The tour notebook in docs/ runs top to bottom, in a Jupyter kernel
(nbclient, installed by .ci/run with ipykernel and matplotlib): it plots the
worldlines and γ(t), and shows a rendered frame inline."""

import os

import nbformat
from nbclient import NotebookClient

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")


def test_the_tour_notebook_runs_plots_and_shows_a_frame(tmp_path):
    nb = nbformat.read(os.path.join(ROOT, "docs", "tour.ipynb"), as_version=4)
    NotebookClient(
        nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    ).execute()
    outputs = [o for cell in nb.cells if cell.cell_type == "code" for o in cell.outputs]
    printed = "".join(o.get("text", "") for o in outputs if o.output_type == "stream")
    assert "puck_puck at t =" in printed
    pngs = [o for o in outputs if "image/png" in o.get("data", {})]
    # The matplotlib figure, then the frame through Frame._repr_png_.
    assert len(pngs) == 2, [o.output_type for o in outputs]
    frame = outputs[-1]
    assert frame.output_type == "execute_result" and "Frame" in frame["data"]["text/plain"]
