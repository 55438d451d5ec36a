"""Relativity of simultaneity: whose "now"? (Einstein's train, on the table.)

Two pucks leave the middle of the table at the same speed in opposite
directions, so on the table they hit the two end cushions at the same
board time. A third puck, the "rocket", crosses the table at 0.6 c. In the
rocket's own frame the two hits are NOT simultaneous: the Lorentz transform
t' = γ (t − v x / c²) puts the hit ahead of it (the right one) earlier, by
γ β Δx / c.

The space-time diagram shows why: the rocket's line of simultaneity (its
"now", the events its frame calls simultaneous with where it is) is tilted,
t = t₀ + (v / c²)(x − x₀). Through the rocket's event at the instant of the
hits it passes above the right hit (already past, for the rocket) and below
the left one (still to come).
"""

import math

import lightcone

BETA = 0.5  # the two pucks from the middle
ROCKET = 0.6  # the rocket's β
START = 0.2  # the rocket's x at t = 0, m
Y_PAIR, Y_ROCKET = 0.95, 0.35


def setup(world):
    scene = lightcone.Scene(title="Whose now? The relativity of simultaneity")
    scene.add_puck("left", (1.32, Y_PAIR), beta=(-BETA, 0.0), color="yellow")
    scene.add_puck("right", (1.52, Y_PAIR), beta=(BETA, 0.0), color="red")
    scene.add_puck("rocket", (START, Y_ROCKET), beta=(ROCKET, 0.0), color="cyan")
    world.start(scene)
    world.view = "truth"
    world.hits = {}
    world.checked = False
    world.say(
        "Two pucks leave the middle at the same speed (β = 0.5) in opposite "
        "directions: on the table they hit the end cushions at the same "
        "instant. The cyan rocket crosses the table to the right at β = 0.6."
    )
    world.ask(
        "For someone riding the rocket, which cushion hit happens first?",
        ["the left one", "the right one (ahead of the rocket)", "both at once"],
        answer=1,
    )


def on_answer(world, question, choice):
    # The space-time diagram (Y), with the rocket's lines of simultaneity.
    world.show_diagram(frame="rocket")
    world.say(
        "The diagram (board x across, time up): the grey dashed line is the "
        "table's \"now\", the bright cyan line the rocket's \"now\" through "
        "where the rocket is; the faint ones its earlier nows. Watch where it "
        "crosses the two cushions (green) when the pucks hit them."
    )


def on_collision(world, event):
    if event["kind"] == "cushion" and event["cushion"] in ("x0", "x1"):
        puck = event["pucks"][0]
        if puck["name"] in ("left", "right"):
            world.hits.setdefault(puck["name"], (event["t"], event["contact"]))


def on_frame(world, t):
    if world.checked or len(world.hits) < 2:
        return
    world.checked = True
    world.pause()  # the student looks at the diagram at the hits
    c = world.c
    (t_left, p_left), (t_right, p_right) = world.hits["left"], world.hits["right"]
    world.check(
        "on the table both hits happen at the same instant",
        abs(t_left - t_right) < 1e-9,
        f"t(left) = {t_left:.9f} s, t(right) = {t_right:.9f} s",
    )
    # The line the diagram draws: the rocket's now through its event at the hits.
    now = world.simultaneity("rocket", at=t_left)
    t0, (x0, _) = now["event"]["t"], now["event"]["position"]
    slope = now["slope"][0]
    world.check(
        "the rocket's now is tilted by v / c² = β / c, through where it is",
        abs(slope - ROCKET / c) < 1e-12
        and now["slope"][1] == 0.0
        and abs(x0 - (START + ROCKET * c * t_left)) < 1e-9,
        f"slope {slope:.12f} s/m, β / c = {ROCKET / c:.12f} s/m; rocket at x = {x0:.6f} m",
    )

    def on_line(x):
        return t0 + slope * (x - x0)

    at_left, at_right = on_line(p_left[0]), on_line(p_right[0])
    world.check(
        "on the rocket's now the right hit is already past, the left one still to come",
        at_right > t_right + 0.1 and at_left < t_left - 0.1,
        f"its now crosses the right cushion at t = {at_right:.4f} s (hit {t_right:.4f} s), "
        f"the left at t = {at_left:.4f} s (hit {t_left:.4f} s)",
    )
    # The Lorentz transform into the rocket's frame, in closed form.
    gamma = 1.0 / math.sqrt(1.0 - ROCKET**2)

    def t_rocket(t, x):
        return gamma * (t - ROCKET * x / c)

    gap = t_rocket(t_right, p_right[0]) - t_rocket(t_left, p_left[0])
    closed = -gamma * ROCKET * (p_right[0] - p_left[0]) / c
    # Events on one line of simultaneity share the rocket's time, so the gap
    # is γ times the board-time gap between the two lines through the hits.
    from_line = -gamma * (at_right - t_right - (at_left - t_left))
    world.check(
        "in the rocket's frame the right hit comes first, by γ β Δx / c",
        gap < 0 and abs(gap - closed) < 1e-9 and abs(from_line - closed) < 1e-9,
        f"t'(right) − t'(left) = {gap:.6f} s; −γβΔx/c = {closed:.6f} s; "
        f"from the diagram's line {from_line:.6f} s",
    )
    picture = world.diagram(at=t_left, frame="rocket")
    world.check(
        "the diagram of that instant is drawn (the same picture as `lightcone diagram --frame rocket`)",
        picture.width == 1000 and picture.height == 700 and abs(picture.t - t_left) < 1e-12,
        repr(picture),
    )
    world.say(
        f"On the table both hits are at t = {t_left:.3f} s. For the rocket the "
        f"right hit is {-gap:.3f} s earlier than the left one: at the instant "
        "of the hits its now (the bright line) has already passed the right "
        "hit and not yet reached the left one. Simultaneity depends on the "
        "frame."
    )
    world.finish("Simultaneous in one frame is not simultaneous in another.")
