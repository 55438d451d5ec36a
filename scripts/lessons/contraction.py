"""Length contraction (the paper's §4.3).

A moving puck is shorter along its motion by the factor 1/γ, measured on
the table at one instant. With only "contraction" switched on, the picture
shows exactly that board-frame shape; switch on light delay and aberration
to see how differently the eye receives it.
"""

import math

import lightcone

BETA = 0.9


def extent(points, axis):
    values = [p["emission"]["position"][axis] for p in points]
    return max(values) - min(values)


def setup(world):
    scene = lightcone.Scene(title="Length contraction")
    scene.add_puck("moving", (0.4, 0.45), beta=(BETA, 0.0), color="yellow")
    scene.add_puck("resting", (1.42, 1.0), color="red")
    world.start(scene)
    for effect in ("light_delay", "aberration", "doppler", "searchlight"):
        world.set_effect(effect, False)
    world.done = False
    world.say(
        f"The yellow puck moves at β = {BETA}; the red one rests. "
        "Only length contraction is switched on: the picture is the board-frame shape."
    )
    world.ask(
        "Along its motion, the moving puck measured on the table is ...",
        ["as long as at rest", "shorter: 2R/γ", "longer: 2Rγ"],
        answer=1,
    )


def on_frame(world, t):
    if world.done or t < 0.5:
        return
    world.done = True
    gamma = 1 / math.sqrt((1 - BETA) * (1 + BETA))
    view = world.observe(vertices=True, effects=["contraction"])
    shapes = {p["name"]: p["vertices"] for p in view["pucks"]}
    ratio = extent(shapes["moving"], 0) / extent(shapes["moving"], 1)
    rest = extent(shapes["resting"], 0) / extent(shapes["resting"], 1)
    world.check(
        "the moving puck is shorter along its motion by 1/γ",
        abs(ratio * gamma - 1) < 1e-9,
        f"length/width = {ratio:.9f}, 1/γ = {1 / gamma:.9f}",
    )
    world.check(
        "the puck at rest keeps its shape",
        abs(rest - 1) < 1e-12,
        f"length/width = {rest:.12f}",
    )
    seen = world.observe(vertices=True, effects=["contraction", "light_delay"])
    moving = [p for p in seen["pucks"] if p["name"] == "moving"][0]["vertices"]
    seen_ratio = extent(moving, 0) / extent(moving, 1)
    world.check(
        "with light delay the eye sees a different length",
        abs(seen_ratio - ratio) > 0.05,
        f"seen length/width = {seen_ratio:.4f} against {ratio:.4f} on the table",
    )
    world.say(
        f"On the table the moving puck is {ratio:.3f} times as long as it is wide "
        f"(1/γ = {1 / gamma:.3f}). Switch on light_delay (key 2) to see what the eye gets."
    )
    # Measured at t = 0.5 s: closed once the light of the moving puck then
    # has reached the eye, so the student has seen the puck the numbers are about.
    now = {p["name"]: p for p in world.state()["pucks"]}["moving"]["position"]
    world.finish(
        "Contraction is a board-frame fact; what you see adds light delay.",
        after_light_from=(t, now[0], now[1]),
    )
