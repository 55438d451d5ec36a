"""A deliberately misbehaving lesson: a hook that waits for a socket and a thread."""

import socket
import threading
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    a, b = socket.socketpair()
    worker = threading.Thread(target=a.recv, args=(1,), daemon=True)
    worker.start()
    worker.join()
