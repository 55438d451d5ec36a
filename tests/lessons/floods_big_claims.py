"""A deliberately misbehaving lesson: a hook that checks claims of 1 MiB
each without end (megabytes of claims a frame, as a flood)."""

import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    detail = "x" * (1 << 20)
    for i in range(10**6):
        try:
            world.check(f"claim {i}", True, detail)
        except ValueError:
            # Refused: the flood goes on regardless, and ends at the limit.
            if i > 100:
                raise
