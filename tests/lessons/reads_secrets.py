"""A deliberately misbehaving lesson: a hook that reads /etc/shadow and the
file named by LIGHTCONE_TEST_SECRET (outside every folder a lesson reads):
each refused."""

import os
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    refused = []
    for path in ("/etc/shadow", os.environ["LIGHTCONE_TEST_SECRET"]):
        try:
            with open(path) as f:
                f.read()
        except PermissionError as e:
            refused.append(f"{path}: {e.strerror}")
    raise PermissionError("reads refused: " + "; ".join(refused))
