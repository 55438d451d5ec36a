"""A deliberately misbehaving lesson: a hook that forks through libc, past
the audit hook (the child would sleep for a minute)."""

import ctypes
import os
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    libc = ctypes.CDLL(None, use_errno=True)
    pid = libc.fork()
    if pid == 0:
        libc.sleep(60)
        libc._exit(0)
    if pid < 0:
        errno = ctypes.get_errno()
        raise PermissionError(errno, f"fork() refused: {os.strerror(errno)}")
