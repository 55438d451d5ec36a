"""A deliberately broken lesson: setup raises before any game starts."""

import lightcone


def setup(world):
    scene = lightcone.Scene(title="broken")
    scene.add_puck("a", (0.5, 0.7), beta=(0.5, 0.0))
    raise RuntimeError("this lesson is broken on purpose (line 9)")
