"""A deliberately broken lesson: a thread it starts raises. The lesson
must fail with that thread's traceback, not pass as if nothing happened
(threading's default only prints it). The thread is joined in `setup`, so
its error is there when the hook returns."""

import threading

import lightcone


def count_down():
    return {"left": 3}["right"]


def setup(world):
    scene = lightcone.Scene(title="a thread that raises")
    scene.add_puck("a", (0.5, 0.71), beta=(0.8, 0.0))
    world.start(scene)
    helper = threading.Thread(target=count_down, name="counter")
    helper.start()
    helper.join()


def on_frame(world, t):
    if t > 1.0:
        world.finish("should not get here")
