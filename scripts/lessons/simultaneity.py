"""Apparent simultaneity (the paper's §4.3).

Two pucks leave the middle of the table at the same speed in opposite
directions, so on the table they hit the two end cushions at the same
instant. You stand near the left cushion. Light from the left hit reaches
you first: what is simultaneous on the table is not seen to be.
"""

import math

import lightcone

BETA = 0.6
# Eye beyond the left cushion, above the cloth (outside the table, so the
# whole table is in view).
EYE = (-0.8, 0.71, 0.6)


def setup(world):
    scene = lightcone.Scene(title="Apparent simultaneity")
    scene.add_puck("left", (1.02, 0.71), beta=(-BETA, 0.0), color="yellow")
    scene.add_puck("right", (1.82, 0.71), beta=(BETA, 0.0), color="red")
    scene.add_observer("near the left cushion", EYE)
    world.start(scene)
    world.observer = "near the left cushion"
    world.hits = {}
    world.checked = False
    world.say(
        "Two pucks start from the middle of the table at the same speed "
        f"(β = {BETA}) in opposite directions. On the table they reach the "
        "end cushions at the same instant."
    )
    world.ask(
        "You stand near the left cushion. Which hit do you SEE first?",
        ["the left one", "the right one", "both at once"],
        answer=0,
    )


def on_collision(world, event):
    if event["kind"] == "cushion" and event["cushion"] in ("x0", "x1"):
        puck = event["pucks"][0]
        world.hits.setdefault(puck["name"], (event["t"], puck["position"]))


def on_frame(world, t):
    if world.checked or len(world.hits) < 2:
        return
    c = world.c
    (t_left, p_left), (t_right, p_right) = world.hits["left"], world.hits["right"]
    height = 0.01  # the centre of a puck, where its clock and colour are seen from

    def seen_at(t_hit, p):
        d = math.dist((p[0], p[1], height), EYE)
        return t_hit + d / c

    seen_left, seen_right = seen_at(t_left, p_left), seen_at(t_right, p_right)
    if t < seen_right + 0.1:
        return  # wait until the far hit has been seen too
    world.checked = True
    world.check(
        "on the table both hits happen at the same instant",
        abs(t_left - t_right) < 1e-9,
        f"t(left) = {t_left:.9f} s, t(right) = {t_right:.9f} s",
    )
    # What the eye sees at the moment light from the left hit arrives: the
    # left puck's light left it at the hit, the right puck's earlier.
    view = world.observe(t=seen_left)
    emitted = {p["name"]: p["emission"]["t"] for p in view["pucks"]}
    world.check(
        "when the left hit is seen, the light from the right puck left it before its hit",
        abs(emitted["left"] - t_left) < 1e-6 and emitted["right"] < t_right - 0.05,
        f"emission times then: left {emitted['left']:.6f} s (hit {t_left:.6f}), "
        f"right {emitted['right']:.6f} s (hit {t_right:.6f})",
    )
    # When is the right hit seen? Search the optics for the observer time at
    # which the light reaching the eye from the right puck left it at its hit.
    lo, hi = seen_left, t
    for _ in range(60):
        mid = (lo + hi) / 2
        right_now = [p for p in world.observe(t=mid)["pucks"] if p["name"] == "right"][0]
        if right_now["emission"]["t"] < t_right:
            lo = mid
        else:
            hi = mid
    world.check(
        "the right hit is seen later by the extra light-travel time, Δd / c",
        abs(hi - seen_right) < 1e-6 and hi - seen_left > 0.5,
        f"seen by the optics at {hi:.6f} s, t + d / c = {seen_right:.6f} s; "
        f"{hi - seen_left:.3f} s after the left hit",
    )
    world.say(
        f"On the table: both hits at t = {t_left:.3f} s. Seen from where you "
        f"stand: left at {seen_left:.3f} s, right at {seen_right:.3f} s. "
        "Simultaneity depends on where the light has to come from."
    )
    world.finish("Simultaneous on the table is not simultaneous to the eye.")
