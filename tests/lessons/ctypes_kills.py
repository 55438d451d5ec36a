"""A deliberately misbehaving lesson: a hook that sends SIGKILL to the game
(its parent) through libc, past the audit hook."""

import ctypes
import os
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    libc = ctypes.CDLL(None, use_errno=True)
    if libc.kill(os.getppid(), 9) != 0:
        errno = ctypes.get_errno()
        raise PermissionError(errno, f"kill(parent, SIGKILL) refused: {os.strerror(errno)}")
