"""`Scene.c` means c: a scene under another speed of light keeps each puck's
proper velocity in m/s (γv, its momentum per unit mass), so a large c is
Newton's scene. Checked against closed forms and a classical event loop
written here, never against what the engine computed before."""

import math
import os

import pytest

import lightcone

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
PAPER = os.path.join(ROOT, "assets", "scenes", "paper_carom.toml")


def test_setting_c_keeps_the_momentum_not_gamma_beta():
    # Issue 30's reproducer: β = 0.7071 at c = 1.42 m/s is γv = 1.42 m/s
    # (u = γβ = 1.0000 to 4 digits); at c = 10⁶ m/s the same γv is
    # u = 1.42e-6, a speed of 1.42 m/s: Newton's.
    s = lightcone.Scene(size=(10, 2), c=1.42)
    s.add_puck("a", (1, 1), beta=(0.7071, 0))
    b = 0.7071
    gv = 1.42 * b / math.sqrt((1 - b) * (1 + b))
    s.c = 1e6
    assert s.c == 1e6
    sim = lightcone.Simulation(s)
    ux, uy = sim.velocity("a")
    assert ux * 1e6 == pytest.approx(gv, rel=1e-12)
    assert uy == 0.0
    # In 2 s it moves γv·2 s to within (v/c)² ~ 1e-12 (Newton), not 10⁵
    # table lengths.
    sim.run_until(2.0)
    x = sim.state()["pucks"][0]["position"][0]
    assert x == pytest.approx(1.0 + 2.0 * gv, abs=1e-9)
    # Back to c = 1.42: the same γv, so β = 0.7071 again.
    s.c = 1.42
    beta = lightcone.Simulation(s).state()["pucks"][0]["beta"][0]
    assert beta == pytest.approx(b, rel=1e-12)


def test_setting_c_refuses_what_a_scene_file_refuses_and_keeps_the_scene():
    s = lightcone.Scene(size=(10, 2), c=1.0)
    s.add_puck("a", (1, 1), u=(2e6, 0))
    with pytest.raises(lightcone.SceneError, match=r"Scene\.c: .* from 1e-6 to 1e9 m/s"):
        s.c = 5e-7
    # γv kept: u would become 2e6 · (1 / 1e-6) = 2e12, beyond the 10¹² a
    # scene file may give.
    with pytest.raises(lightcone.SceneError, match=r"Scene\.c: .*beyond what the engine holds"):
        s.c = 1e-6
    assert s.c == 1.0
    assert lightcone.Simulation(s).velocity("a") == (2e6, 0.0)
    s.c = 2e-6  # |u| = 10¹² exactly: held
    assert lightcone.Simulation(s).velocity("a")[0] == pytest.approx(1e12, rel=1e-15)


def newton(x, v, r, size, until):
    """Classical elastic discs of equal mass and radius `r` on the table
    [0, size[0]] × [0, size[1]], from t = 0 to `until`: the same event loop
    as engine/tests/c_limit.rs, written again here."""
    x = [list(p) for p in x]
    v = [list(w) for w in v]
    n = len(x)
    t = 0.0
    while True:
        best, event = until - t, None
        for i in range(n):
            for k in (0, 1):
                pos, vel, hi = x[i][k], v[i][k], size[k]
                if vel > 0:
                    dt = (hi - r - pos) / vel
                elif vel < 0:
                    dt = (r - pos) / vel
                else:
                    dt = math.inf
                if 0 <= dt < best:
                    best, event = dt, (i, None)
            for j in range(i + 1, n):
                d = [x[j][k] - x[i][k] for k in (0, 1)]
                w = [v[j][k] - v[i][k] for k in (0, 1)]
                a = w[0] ** 2 + w[1] ** 2
                b = d[0] * w[0] + d[1] * w[1]
                c = d[0] ** 2 + d[1] ** 2 - 4 * r * r
                disc = b * b - a * c
                if b < 0 and disc >= 0 and a > 0:
                    dt = c / (-b + math.sqrt(disc))
                    if 0 <= dt < best:
                        best, event = dt, (i, j)
        for i in range(n):
            for k in (0, 1):
                x[i][k] += v[i][k] * best
        t += best
        if event is None:
            return x
        i, j = event
        if j is None:
            for k in (0, 1):
                if x[i][k] <= r + 1e-12 or x[i][k] >= size[k] - r - 1e-12:
                    v[i][k] = -v[i][k]
        else:
            d = [x[j][k] - x[i][k] for k in (0, 1)]
            norm = math.hypot(*d)
            nrm = [d[0] / norm, d[1] / norm]
            a = v[i][0] * nrm[0] + v[i][1] * nrm[1]
            b = v[j][0] * nrm[0] + v[j][1] * nrm[1]
            for k in (0, 1):
                v[i][k] += nrm[k] * (b - a)
                v[j][k] += nrm[k] * (a - b)


def test_at_a_million_metres_per_second_the_papers_carom_is_newtons():
    # The engine's c-limit test (engine/tests/c_limit.rs) through Python:
    # the paper's carom without its cloth, c raised to 10⁶ m/s by the
    # setter, run to t = 6 s, against Newton's discs with the paper's γv.
    paper = lightcone.Scene.load(PAPER)
    paper.friction = 0.0
    c0 = paper.c
    before = lightcone.Simulation(paper)
    x0 = [p["position"][:2] for p in before.state()["pucks"]]
    v0 = [(c0 * ux, c0 * uy) for ux, uy in map(before.velocity, paper.pucks)]
    fast = paper
    fast.c = 1e6
    sim = lightcone.Simulation(fast)
    for name, v in zip(fast.pucks, v0):
        ux, uy = sim.velocity(name)
        assert math.hypot(ux * 1e6 - v[0], uy * 1e6 - v[1]) < 1e-12 * (1 + math.hypot(*v))
    until = 6.0
    sim.run_until(until)
    assert sum(c["kind"] == "puck_puck" for c in sim.collisions()) >= 1
    assert len(sim.collisions()) >= 4
    size = (2.84, 1.42)
    expected = newton(x0, v0, 0.0305, size, until)
    got = [p["position"][:2] for p in sim.state()["pucks"]]
    for name, e, g in zip(fast.pucks, expected, got):
        # The issue asks 1e-5 m; the engine's own test holds 1e-6 m (the
        # relativistic corrections at c = 10⁶ are ~1e-10 m).
        assert math.dist(e, g) < 1e-6, (name, e, g)
