"""Arrays for plotting (numpy optional) and the package's version."""

import importlib.metadata
import math
import os
import struct
import sys
import zlib

import pytest

import lightcone

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
SCENES = os.path.join(ROOT, "assets", "scenes")


def test_version_is_the_installed_packages():
    assert lightcone.__version__ == importlib.metadata.version("lightcone")
    assert lightcone.__version__ == lightcone._lightcone.__version__
    assert all(part.isdigit() for part in lightcone.__version__.split("."))


def png(width, height, rows):
    """A PNG of RGBA 8-bit `rows` (lists of (r, g, b, a)), written by hand."""

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rows)
    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def test_frame_to_numpy_gives_the_pixels_row_by_row_from_the_top():
    np = pytest.importorskip("numpy")
    rows = [[(255, 0, 0, 255), (0, 255, 0, 128), (0, 0, 255, 0)], [(1, 2, 3, 4), (5, 6, 7, 8), (9, 10, 11, 12)]]
    frame = lightcone.Frame._from_png(png(3, 2, rows), 3, 2, 0.5)
    a = frame.to_numpy()
    assert a.shape == (2, 3, 4) and a.dtype == np.uint8
    assert a.tolist() == [[list(px) for px in row] for row in rows]
    a[0, 0, 0] = 7  # a copy the caller owns
    assert frame.to_numpy()[0, 0, 0] == 255


def test_a_rendered_frame_as_an_array_matches_its_png_and_shows_the_red_puck():
    np = pytest.importorskip("numpy")
    sim = lightcone.Simulation(lightcone.Scene.load(os.path.join(SCENES, "paper_carom.toml")))
    try:
        frame = sim.render(size=(320, 180))
    except lightcone.NoAdapterError:
        pytest.skip("no graphics adapter")
    a = frame.to_numpy()
    assert a.shape == (180, 320, 4)
    assert (a[:, :, 3] == 255).all()  # opaque
    red = (a[:, :, 0] > 90) & (a[:, :, 1] < 40) & (a[:, :, 2] < 40)
    assert red.sum() > 5, "the red puck"


def test_positions_and_velocities_are_arrays_of_the_closed_form_motion():
    np = pytest.importorskip("numpy")
    # Two pucks in uniform motion (frictionless), no hit before t = 1 s:
    # x(t) = x0 + (c u / γ) t.
    s = lightcone.Scene(size=(4.0, 2.0), c=2.0)
    s.add_puck("a", (1.0, 0.5), u=(0.75, 0.0))  # γ = 1.25, β = 0.6
    s.add_puck("b", (1.0, 1.5), u=(0.0, -0.2))
    sim = lightcone.Simulation(s)
    sim.run_until(1.0)
    x = sim.positions()
    assert x.shape == (2, 2) and x.dtype == np.float64
    gamma_b = math.sqrt(1 + 0.04)
    expected = [[1.0 + 2.0 * 0.6 * 1.0, 0.5], [1.0, 1.5 - 2.0 * 0.2 / gamma_b * 1.0]]
    assert np.allclose(x, expected, rtol=0, atol=1e-12)
    assert np.allclose(sim.positions(at=0.5)[0], [1.0 + 0.6, 0.5], rtol=0, atol=1e-12)
    assert sim.velocities().tolist() == [[0.75, 0.0], [0.0, -0.2]]
    # The same numbers as the records.
    assert x.tolist() == [p["position"][:2] for p in sim.state()["pucks"]]
    with pytest.raises(lightcone.NotComputedError):
        sim.positions(at=2.0)
    empty = lightcone.Simulation(lightcone.Scene())
    assert empty.positions().shape == (0, 2)


def test_without_numpy_the_arrays_say_so_and_the_rest_works(monkeypatch):
    monkeypatch.setitem(sys.modules, "numpy", None)  # `import numpy` fails
    sim = lightcone.Simulation(lightcone.Scene.load(os.path.join(SCENES, "paper_carom.toml")))
    with pytest.raises(ImportError, match=r"Simulation\.positions .*needs numpy: pip install numpy"):
        sim.positions()
    frame = lightcone.Frame._from_png(png(1, 1, [[(0, 0, 0, 255)]]), 1, 1, 0.0)
    with pytest.raises(ImportError, match=r"Frame\.to_numpy .*needs numpy"):
        frame.to_numpy()
    assert sim.velocity("white")[0] > 0
