"""The Python module against physics and against its contract."""

import math
import os

import pytest

import lightcone

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
SCENES = os.path.join(ROOT, "assets", "scenes")


def scene(name):
    return lightcone.Scene.load(os.path.join(SCENES, name))


def test_load_and_summary():
    s = scene("paper_carom.toml")
    assert s.c == pytest.approx(1.42)
    assert s.pucks == ["white", "yellow", "red"]
    assert s.observers == ["eye"]
    assert s.effects["contraction"] is True


def test_bad_scene_raises_scene_error_naming_line_and_field():
    with pytest.raises(lightcone.SceneError) as e:
        lightcone.Scene.from_toml("[[puck]]\nposition = [0.5, 0.5]\nbeta = [1.2, 0.0]\n", "bad.toml")
    assert "bad.toml:3:" in str(e.value)
    assert "puck[0].beta" in str(e.value)
    with pytest.raises(lightcone.SceneError):
        lightcone.Scene.load(os.path.join(SCENES, "no_such.toml"))
    assert issubclass(lightcone.SceneError, ValueError)


def test_collisions_conserve_four_momentum():
    sim = lightcone.Simulation(scene("ten_pucks.toml"))
    sim.run_until(10.0)
    pairs = [c for c in sim.collisions() if c["kind"] == "puck_puck"]
    assert pairs
    for c in pairs:
        if any(p.get("pending") for p in c["pucks"]):
            continue
        for k in (0, 1):
            before = sum(p["u_before"][k] for p in c["pucks"])
            after = sum(p["u_after"][k] for p in c["pucks"])
            assert after == pytest.approx(before, rel=1e-12, abs=1e-12)
        e_before = sum(math.sqrt(1 + p["u_before"][0] ** 2 + p["u_before"][1] ** 2) for p in c["pucks"])
        e_after = sum(math.sqrt(1 + p["u_after"][0] ** 2 + p["u_after"][1] ** 2) for p in c["pucks"])
        assert e_after == pytest.approx(e_before, rel=1e-12)


def test_impulse_never_reaches_c():
    sim = lightcone.Simulation(scene("paper_carom.toml"))
    sim.impulse("yellow", (0.0, -1e9))
    ux, uy = sim.velocity("yellow")
    assert uy == -1e9
    sim.step(0.01)
    beta = sim.state()["pucks"][1]["beta"]
    ux, uy = sim.velocity("yellow")
    # β = u / √(1 + u²), short of 1 by about 1/(2u²) = 5e-19 (below f64's
    # resolution near 1): a speed computed as u itself would read 10⁹.
    assert beta[0] == pytest.approx(ux / math.sqrt(1 + ux**2 + uy**2), abs=1e-15)
    assert beta[1] == pytest.approx(uy / math.sqrt(1 + ux**2 + uy**2), rel=1e-15)
    assert math.hypot(*beta) <= 1.0
    with pytest.raises(KeyError):
        sim.impulse("nobody", (1.0, 0.0))


def test_observe_puts_the_emission_on_the_light_cone():
    sim = lightcone.Simulation(scene("parallel_tracks.toml"))
    sim.run_until(1.0)
    view = sim.observe("side", vertices=True)
    eye = view["observer"]["position"]
    for p in view["pucks"]:
        e = p["emission"]
        d = math.dist(eye, e["position"])
        assert 1.42 * (1.0 - e["t"]) == pytest.approx(d, abs=1e-12)
        assert len(p["vertices"]) > 90
    truth = sim.observe("side", effects=["contraction"])
    assert all(p["emission"]["t"] == 1.0 for p in truth["pucks"])
    with pytest.raises(ValueError):
        sim.observe(effects=["redshift"])


def test_build_a_scene_in_code_and_check_the_head_on_exchange():
    s = lightcone.Scene(size=(4.0, 2.0), c=2.0, title="head-on")
    s.add_puck("a", (1.0, 1.0), beta=(0.8, 0.0))
    s.add_puck("b", (3.0, 1.0))
    with pytest.raises(lightcone.SceneError):
        s.add_puck("c", (1.03, 1.0))  # overlaps a
    with pytest.raises(lightcone.SceneError):
        s.add_puck("d", (2.0, 1.5), beta=(1.0, 0.0))  # at c
    s.add_observer("side", (2.0, -1.0, 0.5))
    s.set_effect("doppler", True)
    assert s.effects["doppler"] is True
    with pytest.raises(ValueError):
        s.set_effect("redshift", True)
    sim = lightcone.Simulation(s)
    sim.run_until(1.5)  # after the hit (≈ 1.2 s), before b reaches the cushion
    # Equal masses head-on, elastic: the velocities are exchanged.
    ua = sim.velocity("a")
    ub = sim.velocity("b")
    assert ua[0] == pytest.approx(0.0, abs=1e-12)
    assert ub[0] == pytest.approx(0.8 / math.sqrt(1 - 0.64), rel=1e-12)
    with pytest.raises(lightcone.SceneError):
        s.c = -1.0


@pytest.mark.parametrize("c", [0.0, -1.0, 5e-7, 2e9, 1e308, math.inf, math.nan])
def test_setting_c_outside_the_scene_files_range_is_a_located_scene_error(c):
    s = lightcone.Scene(size=(4.0, 2.0), c=2.0)
    with pytest.raises(lightcone.SceneError, match=r"Scene\.c: .* from 1e-6 to 1e9 m/s"):
        s.c = c
    assert s.c == 2.0  # unchanged
    s.c = 1e9  # both ends of the range are accepted
    s.c = 1e-6
    assert s.c == 1e-6


def test_render_writes_a_png(tmp_path):
    sim = lightcone.Simulation(scene("paper_carom.toml"))
    sim.run_until(1.0)
    out = tmp_path / "frame.png"
    sim.render(str(out), size=(160, 90))
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(data) > 500
    with pytest.raises(ValueError):
        sim.render(str(out), view="sideways")


@pytest.mark.parametrize("runtime_dir", [None, "relative/dir"])
def test_render_prints_no_driver_warning_without_a_runtime_dir(runtime_dir):
    # Mesa's device-select layer reaches libwayland, which prints
    # "error: XDG_RUNTIME_DIR is invalid or not set in the environment."
    # when the variable is unset or relative; the wheel gives it a private
    # one (through os.environ) before its first device, as `lightcone` does.
    import subprocess
    import sys

    env = {k: v for k, v in os.environ.items() if k not in ("XDG_RUNTIME_DIR", "WAYLAND_DISPLAY")}
    if runtime_dir is not None:
        env["XDG_RUNTIME_DIR"] = runtime_dir
    code = (
        "import os, lightcone\n"
        f"sim = lightcone.Simulation(lightcone.Scene.load({os.path.join(SCENES, 'paper_carom.toml')!r}))\n"
        "sim.run_until(0.5)\n"
        "try:\n"
        "    print(sim.render(size=(64, 36)).width)\n"
        "except lightcone.NoAdapterError:\n"
        "    print('no adapter')\n"
        "print(os.path.isabs(os.environ['XDG_RUNTIME_DIR']))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    if out.stdout.startswith("no adapter"):
        pytest.skip("no graphics adapter")
    assert out.stdout.split() == ["64", "True"], out.stdout
    assert "XDG_RUNTIME_DIR" not in out.stderr, out.stderr


def test_world_is_only_made_by_the_game():
    """Lessons receive a World from `lightcone play`; Python cannot make one."""
    assert "World" in lightcone.__all__
    with pytest.raises(TypeError):
        lightcone.World()


def test_threads_wait_for_run_until_instead_of_raising():
    """A call from another thread while run_until runs waits for a
    consistent state; it never raises "Already borrowed"."""
    import threading

    sim = lightcone.Simulation(scene("ten_pucks.toml"))
    errors = []
    seen = []

    def run():
        try:
            sim.run_until(6.0)
        except Exception as e:  # pragma: no cover - the failure reported below
            errors.append(e)

    worker = threading.Thread(target=run)
    worker.start()
    while worker.is_alive():
        state = sim.state()
        seen.append(state["t"])
        assert len(state["pucks"]) == 10
        sim.collisions()
        sim.velocity(state["pucks"][0]["name"])
    worker.join()
    assert not errors, errors
    assert sim.time == pytest.approx(6.0)
    # Board time only moves forward, as the other thread saw it.
    assert seen == sorted(seen)


def test_ctrl_c_stops_a_long_run_promptly():
    import _thread
    import threading
    import time

    # Frictionless pucks that bounce for ever (on the paper's cloth every
    # puck is at rest by t = 2.5 s, and a run to 1e308 s is then immediate).
    sim = lightcone.Simulation(scene("ten_pucks.toml"))
    timer = threading.Timer(0.3, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sim.run_until(1e308)
    assert time.monotonic() - start < 2.0
    # The state is consistent and the simulation goes on.
    t = sim.time
    assert 0.0 < t < 1e308
    sim.run_until(t + 0.1)
    assert sim.time == pytest.approx(t + 0.1)


def test_any_sequence_where_a_vector_goes_and_errors_name_the_argument():
    s = lightcone.Scene(size=[4.0, 2.0], c=2.0)
    s.add_puck("tuple", (1.0, 0.5), beta=(0.5, 0.0))
    s.add_puck("list", [1.0, 1.0], beta=[0.0, 0.5])
    s.add_puck("fast", [3.0, 1.0], velocity=[-1.0, 0.0])  # m/s, as in scene files
    with pytest.raises(TypeError, match="position"):
        s.add_puck("bad", "xy")
    with pytest.raises(TypeError, match="got 3") as e:
        s.add_puck("bad", (2.0, 1.5), beta=(0.1, 0.0, 0.0))
    assert "beta" in str(e.value)
    with pytest.raises(lightcone.SceneError, match="at most one"):
        s.add_puck("bad", (2.0, 1.5), beta=(0.1, 0.0), velocity=(0.1, 0.0))
    sim = lightcone.Simulation(s)
    state = sim.state()
    fast = state["pucks"][2]
    assert fast["beta"][0] == pytest.approx(-0.5, rel=1e-12)  # v / c
    sim.impulse("list", [0.0, 0.1])
    with pytest.raises(TypeError, match="du"):
        sim.impulse("list", 0.1)


def test_numpy_arrays_are_vectors():
    np = pytest.importorskip("numpy")
    s = lightcone.Scene(size=np.array([4.0, 2.0]))
    s.add_puck("a", np.array([1.0, 1.0]), beta=np.array([0.3, 0.0]))
    s.add_observer("eye", np.array([2.0, -1.0, 1.0]))
    assert lightcone.Simulation(s).state()["pucks"][0]["beta"][0] == pytest.approx(0.3)


def test_names_are_refused_when_padded_or_empty():
    s = lightcone.Scene()
    s.add_puck("a", (0.5, 0.5))
    for bad in (" a ", "a ", "", "\t"):
        with pytest.raises(lightcone.SceneError, match="name"):
            s.add_puck(bad, (1.5, 0.5))
    assert s.pucks == ["a"]


def test_one_exception_class_per_kind():
    s = lightcone.Scene()
    with pytest.raises(lightcone.SpeedOfLightError):
        s.add_puck("c", (0.5, 0.5), beta=(1.0, 0.0))
    with pytest.raises(lightcone.SpeedOfLightError):
        s.add_puck("c", (0.5, 0.5), velocity=(2.0 * s.c, 0.0))
    with pytest.raises(lightcone.SpeedOfLightError):
        lightcone.Scene.from_toml("[[puck]]\nposition = [0.5, 0.5]\nbeta = [1.2, 0.0]\n")
    assert issubclass(lightcone.SpeedOfLightError, lightcone.SceneError)
    assert issubclass(lightcone.NoAdapterError, RuntimeError)
    sim = lightcone.Simulation(scene("paper_carom.toml"))
    with pytest.raises(lightcone.NotComputedError):
        sim.observe(at=1.0)


def test_observe_at_a_past_time_is_what_was_seen_then():
    early = lightcone.Simulation(scene("paper_carom.toml"))
    early.run_until(0.7)
    late = lightcone.Simulation(scene("paper_carom.toml"))
    late.run_until(2.0)
    then = late.observe(at=0.7)
    now = early.observe()
    assert then["t"] == 0.7
    for a, b in zip(then["pucks"], now["pucks"]):
        assert a["emission"]["position"] == pytest.approx(b["emission"]["position"], abs=1e-9)


def test_records_match_their_typed_dicts():
    from lightcone.records import Collision, CollisionPuck, Observation, PuckState, State

    sim = lightcone.Simulation(scene("paper_carom.toml"))
    sim.run_until(3.0)
    optional = {"cushion", "mass_before", "mass_after", "pending", "vertices", "simultaneous", "pairs"}
    for c in sim.collisions():
        assert set(Collision.__annotations__) - optional <= set(c) <= set(Collision.__annotations__)
        for p in c["pucks"]:
            assert set(p) <= set(CollisionPuck.__annotations__)
    st = sim.state()
    assert set(st) == set(State.__annotations__)
    assert set(st["pucks"][0]) == set(PuckState.__annotations__)
    ob = sim.observe()
    assert set(ob) == set(Observation.__annotations__)


def test_render_returns_a_frame_shown_inline(tmp_path):
    sim = lightcone.Simulation(scene("paper_carom.toml"))
    sim.run_until(1.0)
    try:
        frame = sim.render(size=(160, 90), at=0.5)
    except lightcone.NoAdapterError:
        pytest.skip("no graphics adapter")
    assert (frame.width, frame.height, frame.t) == (160, 90, 0.5)
    assert frame._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"
    frame.save(str(tmp_path / "f.png"))
    assert (tmp_path / "f.png").read_bytes() == frame.png
    assert sim._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "Simulation(" in repr(sim) and "Frame(" in repr(frame)


def test_history_horizon_bounds_what_is_kept_and_says_so():
    sim = lightcone.Simulation(scene("ten_pucks.toml"), history=2.0)
    assert sim.history == 2.0
    assert sim.forgotten_before is None
    sim.run_until(30.0)
    assert sim.forgotten_before is not None and 25.0 < sim.forgotten_before <= 28.0
    # The kept collisions reach back no further than the horizon (records
    # are dropped as each chunk of the run starts, so give or take a chunk).
    first = sim.collisions()[0]
    assert max(p["t"] for p in first["pucks"]) > 25.0
    everything = lightcone.Simulation(scene("ten_pucks.toml"))
    everything.run_until(30.0)
    assert len(sim.collisions()) < len(everything.collisions())
    with pytest.raises(ValueError):
        lightcone.Simulation(scene("ten_pucks.toml"), history=-1.0)


def test_diagram_returns_a_frame_and_its_line_is_the_pucks_now(tmp_path):
    """The diagram needs no graphics adapter. The white puck, struck at
    β₀ = (0.94, 0.141), brakes on the cloth: its proper velocity falls as
    u₀ − μg t / c along its line, and it has slid (c²/μg)(γ₀ − γ) by 0.8 s,
    before its hit: its now is tilted by β / c."""
    sim = lightcone.Simulation(scene("paper_carom.toml"))
    sim.run_until(1.0)
    frame = sim.diagram(size=(200, 140), at=0.8, frame="white", path=str(tmp_path / "d.png"))
    assert isinstance(frame, lightcone.Frame)
    assert (frame.width, frame.height, frame.t) == (200, 140, 0.8)
    assert (tmp_path / "d.png").read_bytes() == frame.png[:]
    assert sim.diagram(size=(50, 40), axis="y").png[:8] == b"\x89PNG\r\n\x1a\n"
    now = sim.simultaneity("white", at=0.8)
    c = sim.scene.c
    a = sim.scene.friction * sim.scene.gravity
    b0 = (0.94, 0.141)
    speed0 = math.hypot(*b0)
    n = (b0[0] / speed0, b0[1] / speed0)
    gamma0 = 1 / math.sqrt((1 - speed0) * (1 + speed0))
    u = gamma0 * speed0 - a * 0.8 / c
    gamma = math.sqrt(1 + u * u)
    bx, by = u * n[0] / gamma, u * n[1] / gamma
    slid = c * c / a * (gamma0 - gamma)
    assert now["puck"] == "white" and now["event"]["t"] == 0.8
    assert now["slope"] == pytest.approx([bx / c, by / c], abs=1e-12)
    assert now["event"]["position"] == pytest.approx([0.6 + slid * n[0], 0.55 + slid * n[1]], abs=1e-12)
    # Lorentz transform: points on the line share the white puck's time.
    x0, y0 = now["event"]["position"]
    for x, y in [(0.0, 0.0), (2.84, 1.42)]:
        t = 0.8 + now["slope"][0] * (x - x0) + now["slope"][1] * (y - y0)
        t_white = gamma * (t - (bx * x + by * y) / c)
        assert t_white == pytest.approx(gamma * (0.8 - (bx * x0 + by * y0) / c), abs=1e-12)
    from lightcone.records import Simultaneity

    assert set(now) == set(Simultaneity.__annotations__)
    with pytest.raises(KeyError):
        sim.diagram(frame="nobody")
    with pytest.raises(ValueError):
        sim.diagram(axis="z")


def test_friction_in_code_stops_a_puck_where_relativity_says():
    # μ = 0.2, g = 9.80665, c = 1.42 m/s; struck at u₀ = γβ = 2 along x.
    # Closed forms (docs/guide/src/friction.md): stopping time (c/μg) u₀,
    # distance (c²/μg)(γ₀ − 1).
    mu, g, c, u0 = 0.2, 9.80665, 1.42, 2.0
    s = lightcone.Scene(size=(6.0, 2.0), c=c, friction=mu)
    assert s.friction == mu and s.gravity == g
    s.add_puck("a", (0.5, 1.0), u=(u0, 0.0))
    sim = lightcone.Simulation(s)
    stop = c / (mu * g) * u0
    sim.run_until(stop * (1 - 1e-6))
    assert sim.velocity("a")[0] > 0.0
    sim.run_until(stop * 1.5)
    assert sim.velocity("a") == (0.0, 0.0)
    x = sim.state()["pucks"][0]["position"][0]
    distance = c * c / (mu * g) * (math.sqrt(1 + u0 * u0) - 1)
    assert x - 0.5 == pytest.approx(distance, rel=1e-12)
    with pytest.raises(lightcone.SceneError, match="friction"):
        s.friction = -0.1
    with pytest.raises(lightcone.SceneError, match="gravity"):
        lightcone.Scene(gravity=0.0)
    assert s.friction == mu  # unchanged by the refused value


def test_slow_light_on_a_cloth_is_refused_with_the_reason():
    s = scene("paper_carom.toml")
    with pytest.raises(lightcone.SceneError, match="Scene.c: .*cannot brake rigidly"):
        s.c = 0.01
    assert s.c == pytest.approx(1.42)
    s.friction = 0.0
    s.c = 0.01
    assert s.c == 0.01


def test_a_scene_built_in_code_carries_its_description():
    # As a scene file's `description`: kept, and carried by the JSON a
    # lesson's process sends the game (the path `world.load` takes).
    s = lightcone.Scene(title="Train", description="Two flashes, one train.")
    assert s.description == "Two flashes, one train."
    back = lightcone.Scene._from_json(s._to_json())
    assert back.description == "Two flashes, one train."
    assert lightcone.Scene().description == ""
    from_file = lightcone.Scene.from_toml('title = "t"\ndescription = "d"\n', "d.toml")
    assert from_file.description == "d"
