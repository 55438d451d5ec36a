"""Aberration: an eye flying past the table at β = 0.85.

Light reaching a moving eye arrives, in the eye's own frame, from further
ahead than it would for an eye at rest at the same place: the direction to
a source at angle θ from the motion (board frame) is seen at θ' with

    cos θ' = (cos θ + β) / (1 + β cos θ)

(Einstein 1905, §7). Everything ahead crowds towards the direction of
flight, so while the eye comes towards the table the table is seen further
ahead, and smaller, than a resting eye there would see it.
"""

import math

import lightcone

BETA = 0.85
FLYBY = (-5.0, -1.3, 0.7)
PUCKS = {"left": (0.5, 0.71), "middle": (1.42, 0.71), "right": (2.34, 0.71)}


def setup(world):
    scene = lightcone.Scene(
        title="Aberration: an eye flies past",
        description="The eye you look through flies past the table at 85 % of c.",
    )
    for (name, xy), colour in zip(PUCKS.items(), ["white", "yellow", "red"]):
        scene.add_puck(name, xy, color=colour)
    scene.add_observer("flyby", FLYBY, beta=(BETA, 0.0, 0.0))
    scene.add_observer("at rest", (1.42, -1.3, 0.7))
    world.start(scene)
    world.observer = "flyby"
    world.done = False
    world.say(
        f"You look through an eye flying towards the table at β = {BETA}. "
        "Choose 'at rest' in the eye menu to compare."
    )
    world.ask(
        "Coming towards the table this fast, the table looks ...",
        ["smaller, and further ahead", "bigger, and nearer", "as it does to a resting eye"],
        answer=0,
    )


def board_direction(seen, eye):
    """Unit vector, board frame, from the eye's event to where the light left."""
    d = [seen["emission"]["position"][i] - eye[i] for i in range(3)]
    n = math.sqrt(sum(x * x for x in d))
    return [x / n for x in d]


def angle(a, b):
    return math.acos(max(-1.0, min(1.0, sum(x * y for x, y in zip(a, b)))))


def on_frame(world, t):
    if world.done or t < 1.0:
        return
    world.done = True
    view = world.observe("flyby")
    eye = view["observer"]["position"]
    seen = {p["name"]: p for p in view["pucks"]}
    worst = 0.0
    for name in PUCKS:
        n = board_direction(seen[name], eye)
        cos_t = n[0]  # the eye moves along +x
        predicted = (cos_t + BETA) / (1 + BETA * cos_t)
        worst = max(worst, abs(seen[name]["direction"][0] - predicted))
    world.check(
        "each puck is seen where cos θ' = (cos θ + β)/(1 + β cos θ) puts it",
        worst < 1e-9,
        f"largest error in cos θ' {worst:.1e}",
    )
    wide_board = angle(board_direction(seen["left"], eye), board_direction(seen["right"], eye))
    wide_seen = angle(seen["left"]["direction"], seen["right"]["direction"])
    world.check(
        "coming towards it, the table is seen smaller than a resting eye there sees it",
        wide_seen < wide_board,
        f"left to right: {math.degrees(wide_seen):.1f}° seen, {math.degrees(wide_board):.1f}° at rest",
    )
    world.say(
        f"Left to right the table spans {math.degrees(wide_seen):.1f}° for the flying eye, "
        f"{math.degrees(wide_board):.1f}° for an eye at rest at the same place. "
        "Watch it swing by as the eye passes.",
        append=True,
    )
    world.finish("Aberration: light arrives from further ahead for a moving eye.")
