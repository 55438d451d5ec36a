"""A deliberately misbehaving lesson: an endless loop that catches BaseException, even in its handler."""

import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    while True:
        try:
            while True:
                pass
        except BaseException:
            try:
                world.say("caught it")
            except BaseException:
                pass
