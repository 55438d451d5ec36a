"""A deliberately misbehaving lesson: an endless loop that catches Exception."""

import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    while True:
        try:
            sum(range(1000))
        except Exception:
            continue
