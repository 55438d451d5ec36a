"""Apparent acceleration and deceleration (the paper's §4.3).

A puck crosses the table at constant speed towards you, bounces off the
cushion in front of you and goes away. Coming towards you it seems to move
several times faster than it does, and to slow down as it nears (your eye is
a little off its line); at the bounce it seems to brake hard, and going away
it seems slow. Each picture comes from light that left the puck earlier, and the
puck chases its own light on the way in.

The apparent speed along a straight path is v / (1 − β·n), with n the unit
vector from the puck (when the light left it) to the eye.
"""

import math

import lightcone

BETA = 0.8
Y = 0.71
EYE = (3.30, Y, 0.10)  # beyond the right cushion, looking back along the path
HEIGHT = 0.02
START = 0.30


def setup(world):
    scene = lightcone.Scene(title="Apparent acceleration")
    scene.add_puck("runner", (START, Y), beta=(BETA, 0.0), color="white")
    scene.add_observer("at the end", EYE, look_at=(1.0, Y, 0.0))
    world.start(scene)
    world.observer = "at the end"
    world.bounce = None
    world.done = False
    world.say(
        f"A puck runs at β = {BETA} straight at you, bounces off the cushion "
        "in front of you and runs away at the same speed."
    )
    world.ask(
        "Does it LOOK faster coming or going?",
        ["coming towards me", "going away", "the same"],
        answer=0,
    )


def on_collision(world, event):
    if world.bounce is None and event["kind"] == "cushion":
        world.bounce = event["t"]


def position(world, t):
    """Where the puck's centre is at board time t (straight path, one bounce)."""
    v = BETA * world.c
    if world.bounce is None or t <= world.bounce:
        x = START + v * t
    else:
        x = START + v * world.bounce - v * (t - world.bounce)
    return (x, Y, HEIGHT / 2)


def apparent_speed(world, t_emit):
    """Measured from the optics: how fast the seen centre moves, per second
    of the observer's time, around the light emitted at t_emit."""
    c = world.c
    t_obs = t_emit + math.dist(position(world, t_emit), EYE) / c
    h = 1e-3
    a = world.observe(t=t_obs - h)["pucks"][0]["emission"]
    b = world.observe(t=t_obs + h)["pucks"][0]["emission"]
    mid = [(a["position"][i] + b["position"][i]) / 2 for i in range(3)]
    return math.dist(a["position"], b["position"]) / (2 * h), mid


def predicted(world, p, incoming):
    n = [EYE[i] - p[i] for i in range(3)]
    d = math.sqrt(sum(x * x for x in n))
    beta_dot_n = (BETA if incoming else -BETA) * n[0] / d
    return BETA * world.c / (1 - beta_dot_n)


def on_frame(world, t):
    if world.done or world.bounce is None:
        return
    late = world.bounce + 1.2
    if t < late + math.dist(position(world, late), EYE) / world.c + 0.05:
        return
    world.done = True
    v = BETA * world.c
    lines = []
    ok = True
    measured = {}
    for label, t_emit, incoming in [
        ("far, coming", 0.3, True),
        ("near, coming", world.bounce - 0.4, True),
        ("going", late, False),
    ]:
        speed, p = apparent_speed(world, t_emit)
        expect = predicted(world, p, incoming)
        measured[label] = speed
        ok = ok and abs(speed / expect - 1) < 1e-4
        lines.append(f"{label}: seen {speed / v:.3f} v (v/(1-β·n) = {expect / v:.3f} v)")
    world.check("the seen speed is v / (1 − β·n) along the path", ok, "; ".join(lines))
    world.check(
        "coming towards the eye it looks faster than it is",
        min(measured["far, coming"], measured["near, coming"]) > v,
        f"{measured['far, coming'] / v:.3f} v, then {measured['near, coming'] / v:.3f} v",
    )
    world.check(
        "nearing the eye (off its line) it seems to slow down, though its speed is constant",
        measured["near, coming"] < measured["far, coming"],
        f"{measured['far, coming'] / v:.4f} v far, {measured['near, coming'] / v:.4f} v near",
    )
    world.check(
        "going away it looks slower than it is",
        measured["going"] < v,
        f"{measured['going'] / v:.3f} v",
    )
    world.say("\n".join(["Seen speeds (true speed v):"] + lines))
    world.finish("The puck chases its own light on the way in.")
