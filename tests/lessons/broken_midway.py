"""A deliberately broken lesson: the game starts, then a hook raises at the
first collision. The game must keep its state (the collision happened) and
show the traceback."""

import lightcone


def setup(world):
    scene = lightcone.Scene(title="breaks at the first collision")
    scene.add_puck("a", (0.5, 0.71), beta=(0.8, 0.0))
    scene.add_puck("b", (0.6, 0.71))
    world.start(scene)
    world.check("setup ran", True)


def on_collision(world, event):
    world.say("about to fail")
    return event["no such key"]
