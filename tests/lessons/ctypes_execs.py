"""A deliberately misbehaving lesson: a hook that replaces its process with
`sleep 60` through libc's execv, past the audit hook."""

import ctypes
import os
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    libc = ctypes.CDLL(None, use_errno=True)
    argv = (ctypes.c_char_p * 3)(b"sleep", b"60", None)
    libc.execv(b"/bin/sleep", argv)
    errno = ctypes.get_errno()
    raise PermissionError(errno, f"execv refused: {os.strerror(errno)}")
