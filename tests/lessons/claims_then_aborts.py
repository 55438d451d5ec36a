"""A deliberately misbehaving lesson: a hook that makes a claim, then
aborts its process through ctypes (SIGABRT, past the guard on os.abort)."""

import ctypes
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    world.check("claimed before the crash", False, "a false claim, kept too")
    ctypes.CDLL(None).abort()
