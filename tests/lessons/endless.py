"""A deliberately broken lesson: on_frame never returns."""

import lightcone


def setup(world):
    scene = lightcone.Scene(title="endless")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    while True:
        pass
