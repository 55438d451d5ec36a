"""A deliberately misbehaving lesson: a hook that signals the game running
it (its parent process), through its process group, a process handle
(pidfd) and its pid."""

import os
import signal
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    for kill in (
        lambda: os.killpg(os.getpgrp(), signal.SIGTERM),
        lambda: signal.pidfd_send_signal(os.pidfd_open(os.getppid()), signal.SIGTERM),
    ):
        try:
            kill()
        except PermissionError:
            pass
    os.kill(os.getppid(), signal.SIGTERM)
