"""A deliberately misbehaving lesson: a hook that ends its process with
status 3 through libc's _exit (past the guard on os._exit)."""

import ctypes
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    ctypes.CDLL(None)._exit(3)
