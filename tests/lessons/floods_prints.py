"""A deliberately misbehaving lesson: a hook that prints without end, with
no newline."""

import sys
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    chunk = "y" * (1 << 20)
    for _ in range(1536):  # 1.5 GB
        sys.stdout.write(chunk)
