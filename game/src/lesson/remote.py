"""A lesson run in its own process, as the window runs it (see remote.rs),
or in a browser's Web Worker (web/python/lightcone_web_child.py).

`World` stands for the game: each method that reads what the last snapshot
does not hold, or that changes the game or the lesson's panel, is a request
to the game, which answers (in Rust: lesson/src/protocol.rs, the same
operations as `lightcone.World`) with the snapshot of the world's simple
attributes that the lesson then reads without asking.

Values travel as JSON: records as {"$record": class, "data": dict},
scenes as {"$scene": json}, frames as {"$frame": [png_base64, width,
height, t]}. Whatever the game receives is checked again there: a scene
is rebuilt through the checks of a scene built in code.
"""

import base64
import builtins
import json
import os

import lightcone
from lightcone import records

# Read from the snapshot sent with each call and each answer.
SNAPSHOT = ("t", "c", "paused", "time_scale", "view", "observer", "effects")
# Attributes a lesson may set (`world.paused = True`): requests.
SETTABLE = ("paused", "time_scale", "view", "observer")
# Methods served by the game (lesson/src/protocol.rs: a test keeps the two
# lists equal).
METHODS = (
    "start",
    "pause",
    "resume",
    "set_effect",
    "state",
    "collisions",
    "velocity",
    "impulse",
    "observe",
    "show_diagram",
    "simultaneity",
    "say",
    "ask",
    "check",
    "bars",
    "finish",
    "diagram",
)
# Read-only attributes served by the game's process.
GETTERS = ("claims", "scene", "finished")
# Every request the game serves (the game refuses any other).
SERVED = METHODS + GETTERS + tuple("=" + name for name in SETTABLE)


# Largest integer sent as one (the game reads JSON numbers as 64-bit
# integers or doubles): beyond it, as a float, or OverflowError.
_MAX_INT = 2**63


def encode(value):
    """`value` as JSON data, records and scenes tagged. An int too large
    for a float raises OverflowError, as lightcone.World does."""
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= _MAX_INT:
        return float(value)  # OverflowError past a double's range
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    if isinstance(value, records.Record):
        return {"$record": type(value).__name__, "data": value.to_dict()}
    if isinstance(value, lightcone.Scene):
        return {"$scene": value._to_json()}
    if isinstance(value, lightcone.Frame):
        png = base64.b64encode(value.png).decode("ascii")
        return {"$frame": [png, value.width, value.height, value.t]}
    if isinstance(value, (list, tuple)):
        return [encode(v) for v in value]
    if isinstance(value, dict):
        return {str(k): encode(v) for k, v in value.items()}
    if hasattr(value, "tolist"):  # a numpy array or number
        return encode(value.tolist())
    raise TypeError(f"a {type(value).__name__} cannot be passed to the game")


def decode(value, frames=False):
    """The value `encode` made (frames only if `frames`: the lesson's
    side; the game takes none)."""
    if isinstance(value, list):
        return [decode(v, frames) for v in value]
    if isinstance(value, dict):
        if frames and len(value) == 1 and "$frame" in value:
            png, width, height, t = value["$frame"]
            return lightcone.Frame._from_png(base64.b64decode(png), width, height, t)
        if len(value) == 1 and isinstance(value.get("$scene"), str):
            return lightcone.Scene._from_json(value["$scene"])
        name = value.get("$record")
        if len(value) == 2 and name in records.__all__ and isinstance(value.get("data"), dict):
            cls = getattr(records, name)
            if isinstance(cls, type) and issubclass(cls, records.Record):
                return cls(value["data"])
        return {k: decode(v, frames) for k, v in value.items()}
    return value


def _exception(kind):
    cls = getattr(lightcone, kind, None) or getattr(builtins, kind, None)
    if isinstance(cls, type) and issubclass(cls, Exception):
        return cls
    return RuntimeError


class World:
    """The running game, as a lesson run in its own process sees it: the
    same attributes and methods as `lightcone.World` (each a request to
    the game's process). A lesson may keep its own attributes on it."""

    def __init__(self, request, directory):
        object.__setattr__(self, "_request", request)
        object.__setattr__(self, "_snapshot", {"$none": "no game yet"})
        object.__setattr__(self, "_dir", directory)

    def _begin(self, snap):
        object.__setattr__(self, "_snapshot", snap)

    def _call(self, op, args, kwargs):
        try:
            line = json.dumps(
                {"request": {"op": op, "args": encode(list(args)), "kwargs": encode(kwargs)}},
                allow_nan=False,
            )
        except ValueError:
            raise ValueError(f"world.{op.lstrip('=')}: every number must be finite") from None
        reply = json.loads(self._request(line))
        object.__setattr__(self, "_snapshot", reply["snapshot"])
        if "error" in reply:
            kind, message = reply["error"]
            raise _exception(kind)(message)
        return decode(reply["ok"], frames=True)

    def __getattr__(self, name):
        if name in SNAPSHOT:
            snap = self._snapshot
            if name not in snap:
                raise RuntimeError(snap.get("$none", "no game"))
            value = snap[name]
            return dict(value) if isinstance(value, dict) else value
        if name in METHODS:

            def method(*args, **kwargs):
                result = self._call(name, args, kwargs)
                return tuple(result) if name == "velocity" else result

            method.__name__ = name
            return method
        if name in GETTERS:
            result = self._call(name, (), {})
            return [tuple(c) for c in result] if name == "claims" else result
        raise AttributeError(f"'World' object has no attribute {name!r}")

    def __setattr__(self, name, value):
        # As on lightcone.World: a lesson's own attribute may hide a
        # method (`world.collisions = 0`), not a read-only attribute.
        if name in SETTABLE:
            self._call("=" + name, (value,), {})
        elif name in SNAPSHOT or name in GETTERS:
            raise AttributeError(f"world.{name} cannot be set")
        else:
            object.__setattr__(self, name, value)

    @property
    def __class__(self):
        # isinstance(world, lightcone.World) holds, as in the game's
        # process (isinstance falls back on __class__).
        return lightcone.World

    def diagram(self, path=None, *args, **kwargs):
        """The space-time diagram (see lightcone.World.diagram). With `path`
        (relative to the lesson), saved here, on the lesson's side: the
        game writes no file a lesson names."""
        frame = self._call("diagram", (None,) + args, kwargs)
        if path is not None:
            frame.save(os.path.join(self._dir, os.fspath(path)))
        return frame

    def load(self, path):
        """Loads a scene file; a relative path is taken from the lesson's
        directory. Raises SceneError naming the file, line and field."""
        return lightcone.Scene.load(os.path.join(self._dir, os.fspath(path)))

    def __repr__(self):
        snap = self._snapshot
        if "t" in snap:
            return f"World(t = {snap['t']:.3f} s, in the lesson's own process)"
        return "World(no game)"


def begin(world, line):
    """Reads a call line in the lesson: sets the world's snapshot; returns
    the hook's name and its arguments (the world first)."""
    msg = json.loads(line)
    world._begin(msg["snapshot"])
    return msg["call"], tuple([world] + decode(msg["args"], frames=True))
