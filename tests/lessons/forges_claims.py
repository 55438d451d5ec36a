"""A deliberately misbehaving lesson: a hook that writes claim events
straight into its channel to `lightcone lesson`, past `world.check`'s
bounds (20 000 claims)."""

import os
import json
import lightcone
from floods_its_pipe import channel


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    fd = channel()
    for i in range(20000):
        line = {"progress": {"claim": {"claim": f"forged {i}", "ok": True, "detail": ""}}}
        os.write(fd, (json.dumps(line) + "\n").encode())
