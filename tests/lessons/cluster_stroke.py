"""The CAVE cluster test's lesson: a cue stroke at board time 0.3 s that
sends the white puck into the red one (tests/cluster.rs).

Light at 5 m/s, not the default 1.42: the pucks are about 2.3 m from the
CAVE's eye, so the stroke is seen 0.5 s after it, not 1.6 s, and the test's
90 frames see the pucks meet however fast the frames come (at 1.42 m/s a
window drawing a frame in 20 ms saw nothing move by its last frame)."""

import lightcone


def setup(world):
    scene = lightcone.Scene(title="Cluster stroke", c=5.0)
    scene.add_puck("white", (0.6, 0.71), color="white")
    scene.add_puck("red", (2.0, 0.74), color="red")
    world.start(scene)
    world.struck = False


def on_frame(world, t):
    if not world.struck and t > 0.3:
        world.struck = True
        world.impulse("white", (2.0, 0.0))
