"""A lesson that never reaches its end: it slows time to almost nothing,
so --until is never reached and it never calls finish()."""

import lightcone


def setup(world):
    scene = lightcone.Scene(title="never ends")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)
    world.time_scale = 1e-12
    world.check("it started", True)
