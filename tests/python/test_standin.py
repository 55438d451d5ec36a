"""The browser's `lightcone._lightcone` (web/python/_lightcone.py, whose
Scene and Simulation forward every operation to the engine compiled for
the lesson's worker) answers as the pyo3 extension does: the same tests
run against both. Here the stand-in's engine is the extension's own copy of
it (`_standin_call`, the same Rust as web-engine/), so what differs is
only the Python: argument binding, encoding, errors, records.
"""

import importlib.util
import math
import pathlib
import sys
import types

import pytest

import lightcone
from lightcone import _lightcone as extension

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _load_standin():
    # What the worker provides: the engine's one call, and the protocol's
    # lesson side (which the stand-in uses to decode records and frames).
    engine = types.ModuleType("lightcone_engine_web")
    engine.lightcone_call = extension._standin_call
    sys.modules["lightcone_engine_web"] = engine
    if "lightcone_remote" not in sys.modules:
        spec = importlib.util.spec_from_file_location("lightcone_remote", ROOT / "game/src/lesson/remote.py")
        remote = importlib.util.module_from_spec(spec)
        sys.modules["lightcone_remote"] = remote
        spec.loader.exec_module(remote)
    spec = importlib.util.spec_from_file_location("lightcone_standin", ROOT / "web/python/_lightcone.py")
    standin = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(standin)
    return standin


STANDIN = _load_standin()


@pytest.fixture(params=["extension", "standin"])
def lc(request):
    """The module under test: the pyo3 extension, or the browser's stand-in."""
    return extension if request.param == "extension" else STANDIN


def shot(lc, c=None, u=2.0):
    scene = lc.Scene(c=c, title="The collision angle")
    scene.add_puck("striker", (0.5, 0.71), u=(u, 0.0), color="white")
    scene.add_puck("target", (1.4, 0.74), color="red")
    return scene


def full_scene(lc):
    """A scene built through every builder: observer, each way of giving
    a motion, an effect, friction."""
    s = shot(lc)
    s.add_observer("eye", (1.42, -1.5, 1.2), look_at=[1.42, 0.71, 0.0])
    s.add_puck("slow", (2.2, 0.4), beta=(0.0, 0.3), radius=0.04, mass=0.3)
    s.add_puck("fast", (2.5, 1.1), velocity=(-0.5, 0.0))
    s.set_effect("doppler", True)
    s.friction = 0.1
    return s


def test_a_scene_built_in_code_is_the_same_scene(lc):
    s = full_scene(lc)
    assert s.pucks == ["striker", "target", "slow", "fast"]
    assert s.observers == ["eye"]
    assert s.effects["doppler"] is True
    assert (s.title, s.description, s.friction, s.gravity) == ("The collision angle", "", 0.1, 9.80665)
    # Byte for byte the extension's scene.
    ours = full_scene(extension)
    assert s._to_json() == ours._to_json()
    assert repr(s) == repr(ours)


def test_c_keeps_the_momentum(lc):
    s = lc.Scene(size=(10, 2), c=1.42)
    s.add_puck("a", (1, 1), beta=(0.7071, 0))
    s.c = 1e6
    sim = lc.Simulation(s)
    sim.run_until(2.0)
    u = sim.velocity("a")
    # γv in m/s kept: u·c unchanged, so at c = 1e6 the puck moves at ~1 m/s.
    assert math.isclose(u[0] * 1e6, 0.7071 / math.sqrt(1 - 0.7071**2) * 1.42, rel_tol=1e-9)


@pytest.mark.parametrize(
    "build, error",
    [
        (lambda s: s.add_puck("b", (1.0, 0.7), beta=(1.0, 0.0)), "SpeedOfLightError"),
        (lambda s: s.add_puck("b", (0.52, 0.71)), "OverlapError"),
        (lambda s: s.add_puck("b", (1.0, 0.7), radius=-1.0), "OutOfRangeError"),
        (lambda s: s.add_puck("striker", (2.0, 0.7)), "SceneError"),
        (lambda s: s.add_puck("b", (2.0, 0.7), color="no such colour"), "SceneError"),
        (lambda s: s.add_puck("b", (2.0, 0.7), beta=(0.1, 0.0), u=(0.1, 0.0)), "SceneError"),
        (lambda s: s.add_puck("b", (2.0,)), "TypeError"),
        (lambda s: s.add_puck("b", "xy"), "TypeError"),
        (lambda s: s.add_puck("b"), "TypeError"),
        (lambda s: s.add_puck("b", (2.0, 0.7), spin=3), "TypeError"),
        (lambda s: s.set_effect("sparkles", True), "ValueError"),
        (lambda s: setattr(s, "friction", -1.0), "OutOfRangeError"),
        (lambda s: setattr(s, "c", 0.0), "OutOfRangeError"),
        (lambda s: s.add_observer("o", (1.0, 1.0)), "TypeError"),
    ],
)
def test_a_bad_scene_raises_the_same_error_with_the_same_words(lc, build, error):
    with pytest.raises(Exception) as theirs:
        build(shot(lc))
    with pytest.raises(Exception) as ours:
        build(shot(extension))
    assert type(ours.value).__name__ == error
    assert type(theirs.value).__name__ == error
    if error != "TypeError":  # pyo3's TypeErrors have pyo3's own words
        assert str(theirs.value) == str(ours.value)
    if isinstance(ours.value, extension.SceneError):
        assert isinstance(theirs.value, lc.SceneError) and isinstance(theirs.value, ValueError)


def test_a_simulation_gives_the_same_records(lc):
    sim = lc.Simulation(shot(lc), history=None)
    sim.run_until(5.0)
    hits = [c for c in sim.collisions() if c["kind"] == "puck_puck"]
    ours = extension.Simulation(shot(extension))
    ours.run_until(5.0)
    assert [c.to_dict() for c in sim.collisions()] == [c.to_dict() for c in ours.collisions()]
    assert sim.state().to_dict() == ours.state().to_dict()
    assert hits and isinstance(hits[0], lightcone.records.Collision)
    assert sim.time == 5.0
    seen = sim.observe(at=4.0)
    assert seen.to_dict() == ours.observe(at=4.0).to_dict()
    with pytest.raises(lightcone.NotComputedError if lc is extension else lc.NotComputedError):
        sim.observe(at=6.0)
    line = sim.simultaneity("striker", at=1.0)
    assert line == ours.simultaneity("striker", at=1.0)
    frame = sim.diagram(size=(320, 200))
    assert (frame.width, frame.height) == (320, 200)
    assert frame.png == ours.diagram(size=(320, 200)).png
    with pytest.raises(KeyError):
        sim.velocity("nobody")


def test_a_scene_read_from_text_is_the_same(lc):
    text = (ROOT / "assets/scenes/paper_carom.toml").read_text()
    assert lc.Scene.from_toml(text, "paper_carom.toml")._to_json() == extension.Scene.from_toml(text, "paper_carom.toml")._to_json()
    with pytest.raises(Exception) as theirs:
        lc.Scene.from_toml("[table]\nsize = 3\n", "bad.toml")
    with pytest.raises(Exception) as ours:
        extension.Scene.from_toml("[table]\nsize = 3\n", "bad.toml")
    assert (type(theirs.value).__name__, str(theirs.value)) == (type(ours.value).__name__, str(ours.value))
