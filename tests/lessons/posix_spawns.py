"""A deliberately misbehaving lesson: a hook that starts `sleep 60` in a
new session through `_posixsubprocess.fork_exec` (pure Python, no audit
event: it once outlived the run, holding its stderr)."""

import os
import _posixsubprocess
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    errpipe_read, errpipe_write = os.pipe()
    _posixsubprocess.fork_exec(
        [b"sleep", b"60"], [b"/bin/sleep", b"/usr/bin/sleep"],
        True, (errpipe_write,), None, None,
        -1, -1, -1, -1, -1, -1,
        errpipe_read, errpipe_write,
        True, True, -1, None, None, None, -1,
        None, True,
    )
