"""A deliberately misbehaving lesson: a hook that checks claims without end
(each with a long detail), as a flood."""

import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    detail = "x" * 2000
    for i in range(10**7):
        world.check(f"claim {i}", True, detail)
