"""The CAVE cluster test's lesson: a cue stroke at board time 0.3 s that
sends the white puck into the red one (tests/cluster.rs)."""

import lightcone


def setup(world):
    scene = lightcone.Scene(title="Cluster stroke")
    scene.add_puck("white", (0.6, 0.71), color="white")
    scene.add_puck("red", (2.0, 0.74), color="red")
    world.start(scene)
    world.struck = False


def on_frame(world, t):
    if not world.struck and t > 0.3:
        world.struck = True
        world.impulse("white", (2.0, 0.0))
