"""A deliberately misbehaving lesson: a hook that writes garbage to every
pipe it can find (in the window, one of them is its channel to the game)."""

import os
import stat
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    for fd in range(3, 64):
        try:
            if stat.S_ISFIFO(os.fstat(fd).st_mode):
                os.write(fd, b'{"shell": "rm -rf /"}\n')
        except OSError:
            pass
    world.say("still here")
