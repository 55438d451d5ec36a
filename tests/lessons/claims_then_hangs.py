"""A deliberately misbehaving lesson: a hook that makes claims, then runs
one C call for hours (past its time limit: its process is stopped)."""

import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.check("claimed in setup", True, "kept")
    world.start(scene)


def on_frame(world, t):
    world.check("claimed before the C call", True, f"t = {t:.3f} s")
    sum(range(10**13))
