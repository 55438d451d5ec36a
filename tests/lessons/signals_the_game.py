"""A deliberately misbehaving lesson: a hook that signals the game running
it (its parent process) and then its own process group."""

import os
import signal
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    try:
        os.killpg(os.getpgrp(), signal.SIGTERM)
    except PermissionError:
        pass
    os.kill(os.getppid(), signal.SIGTERM)
