"""Sliding friction near c: what it takes to stop a fast puck.

On the cloth a sliding puck feels a constant force μ m g against its motion
(in the board frame, the cloth's rest frame). Its momentum m c u (u = γβ)
falls linearly in time, u(t) = u₀ − μ g t / c, so it stops after

    t_stop = (c / μg) u₀          (board time)
    τ_stop = (c / μg) asinh u₀    (its own proper time)
    s_stop = (c² / μg) (γ₀ − 1)   (distance)

The last is the work–energy theorem: friction does work μ m g s, and the
puck had kinetic energy m c² (γ₀ − 1). Near c the kinetic energy grows
without bound while the speed hardly does: a puck at γ = 3 moves barely
faster than one at γ = 2 but slides twice as far. Keeping a puck near c
against friction costs power μ m g v ≈ μ m g c, yet what you must have put in
to get it there is m c² (γ − 1): the paper's haptic idea of a puck that
"feels heavy" to push near c.
"""

import math

import lightcone

C = 1.0  # m/s
MU, G = 0.5, 2.0  # μg = 1 m/s²: distances in metres are γ₀ − 1
LANES = {"γ = 1.25": (1.25, 0.25), "γ = 2": (2.0, 0.6), "γ = 3": (3.0, 0.95)}
X0 = 0.2


def proper_speed(gamma):
    return math.sqrt((gamma - 1.0) * (gamma + 1.0))


def setup(world):
    lines = [
        f"c = {C}",
        'title = "Friction near c"',
        "[table]",
        "size = [3.0, 1.2]",
        f"friction = {MU}",
        f"gravity = {G}",
    ]
    for name, (gamma, y) in LANES.items():
        lines += [
            "[[puck]]",
            f'name = "{name}"',
            f"position = [{X0}, {y}]",
            f"u = [{proper_speed(gamma)!r}, 0.0]",
        ]
    scene = lightcone.Scene.from_toml("\n".join(lines) + "\n", "friction")
    world.start(scene)
    world.done = False
    world.say(
        "Three pucks on a cloth (μ = 0.5, g = 2 m/s², c = 1 m/s), struck at γ = 1.25, 2 "
        "and 3. Friction brakes each with the same force."
    )
    # The paper's haptic idea as a plot: what it takes to bring a puck to β,
    # m c²(γ − 1) (here, with μg = 1 m/s² and c = 1 m/s, also the distance
    # friction needs to take it back, in metres), against Newton's ½ m v².
    edges = [k / 20 for k in range(20)] + [0.99]
    mid = [0.5 * (lo + hi) for lo, hi in zip(edges, edges[1:])]
    world.bars(
        "energy to reach β (m c²; here also the slide, m): relativity (bars), Newton ½β² (line)",
        edges,
        [1.0 / math.sqrt(1.0 - b * b) - 1.0 for b in mid],
        [0.5 * b * b for b in mid],
    )
    world.ask(
        "The γ = 3 puck moves only 6% faster than the γ = 2 one. How much farther does it slide?",
        ["about 6% farther", "about twice as far", "about 9 times as far"],
        answer=1,
    )


def on_frame(world, t):
    if world.done or t < 4.0:
        return
    world.done = True
    a = MU * G
    state = {p["name"]: p for p in world.state()["pucks"]}
    lines, ok = [], True
    for name, (gamma, _) in LANES.items():
        p = state[name]
        u0 = proper_speed(gamma)
        s = p["position"][0] - X0
        expect = C * C / a * (gamma - 1.0)
        at_rest = math.hypot(*p["u"][:2]) == 0.0
        ok = ok and at_rest and abs(s - expect) < 1e-9
        lines.append(f"{name}: slid {s:.9f} m, (c²/μg)(γ₀ − 1) = {expect:.9f} m")
    world.check("each stops after (c²/μg)(γ₀ − 1): the work–energy theorem", ok, "; ".join(lines))

    lines, ok = [], True
    for name, (gamma, _) in LANES.items():
        u0 = proper_speed(gamma)
        t_stop = C / a * u0
        tau = C / a * math.asinh(u0) + (t - t_stop)
        got = state[name]["proper_time"]
        ok = ok and abs(got - tau) < 1e-9
        lines.append(f"{name}: τ = {got:.9f} s, (c/μg) asinh u₀ + rest = {tau:.9f} s")
    world.check("its clock loses (c/μg)(u₀ − asinh u₀) while it slides", ok, "; ".join(lines))

    ratio = (LANES["γ = 3"][0] - 1.0) / (LANES["γ = 2"][0] - 1.0)
    speeds = {n: math.sqrt(1.0 - 1.0 / (g * g)) for n, (g, _) in LANES.items()}
    world.say(
        f"β = {speeds['γ = 2']:.3f} slid {LANES['γ = 2'][0] - 1.0:.2f} m; β = "
        f"{speeds['γ = 3']:.3f} slid {LANES['γ = 3'][0] - 1.0:.2f} m, {ratio:.0f}× as far. "
        "The distance measures the kinetic energy m c²(γ − 1), which grows without bound "
        "as the speed creeps towards c."
    )
    world.finish("Near c, friction reads energy, not speed.")
