"""A deliberately misbehaving lesson: a hook that writes 1.5 GB with no
newline straight into its process's channel to the game (the pipe the
host reports on: a FIFO open for writing that is neither its standard
input's pipe nor its standard error)."""

import fcntl
import os
import stat
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def channel():
    skip = {os.fstat(0).st_ino, os.fstat(2).st_ino}
    for fd in range(3, 256):
        try:
            st = os.fstat(fd)
            flags = fcntl.fcntl(fd, fcntl.F_GETFL)
        except OSError:
            continue
        if stat.S_ISFIFO(st.st_mode) and flags & os.O_ACCMODE == os.O_WRONLY:
            if st.st_ino not in skip:
                return fd
    raise RuntimeError("no channel found")


def on_frame(world, t):
    fd = channel()
    chunk = b"z" * (1 << 20)
    for _ in range(1536):  # 1.5 GB
        os.write(fd, chunk)
