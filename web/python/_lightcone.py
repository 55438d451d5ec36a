"""`lightcone._lightcone` in the browser: the web stand-in of the pyo3
extension module (py/src), for lessons run by Pyodide in a Web Worker
(web/static/lesson_worker.js).

The same classes, signatures and exceptions as the extension
(`_lightcone.pyi`), but no physics here: every operation of `Scene` and
`Simulation` is forwarded to the engine compiled for the worker
(`lightcone_engine_web`, whose one function `lightcone_call` takes and
returns JSON text), so it answers, and refuses, exactly as the extension
does. A `Scene` is its state (the engine's JSON of the scene, replaced
by each change); a `Simulation` is an id into the engine's simulations.

Requests: `{"class": "Scene", "op": OP, "state": STATE or null,
"args": [...], "kwargs": {...}}` and `{"class": "Simulation", "id": ID,
"op": OP, ...}` (`"new"` without an id); replies `{"ok": VALUE, "state":
NEW_STATE}` or `{"error": [KIND, MESSAGE]}`, KIND the name of the
exception to raise. Values travel as between a lesson and the game
(`lightcone_remote.encode` / `decode`: records, scenes, frames tagged).
Arguments are checked against each signature here (a wrong count or
keyword is Python's own `TypeError`) and sent all positional, in
signature order.
"""

import builtins
import json
import os

from lightcone_engine_web import lightcone_call as _lightcone_call  # lesson_worker.js

# The workspace's version: scripts/web.sh writes it here in web/dist.
__version__ = "0.1.0"

__all__ = [
    "Frame",
    "BrakingHorizonError",
    "NoAdapterError",
    "NotComputedError",
    "OutOfRangeError",
    "OverlapError",
    "Scene",
    "SceneError",
    "Simulation",
    "SpeedOfLightError",
    "World",
    "__version__",
]


# ---- Exceptions: the hierarchy of py/src/errors.rs. Their module is
# "_lightcone", as pyo3's `create_exception!(_lightcone, …)` names it, so
# a traceback ends "_lightcone.SceneError: …" as on the desktop.


class SceneError(ValueError):
    """A scene file, text or element is invalid; the message names the file, line and field (or the puck or observer)."""


class SpeedOfLightError(SceneError):
    """A speed at or above the speed of light c was given (β = v/c ≥ 1); no body reaches c."""


class OverlapError(SceneError):
    """Two pucks overlap at board time 0 (their rest-frame discs; touching is allowed)."""


class OutOfRangeError(SceneError):
    """A number lies outside what the engine holds (the guide, docs/guide/src/scenes.md, "What the engine holds"): a length, mass, c, friction, gravity, restitution or |u|."""


class BrakingHorizonError(SceneError):
    """A puck cannot brake rigidly on the cloth: its radius reaches the braking's Rindler horizon c²/(μg)."""


class NoAdapterError(RuntimeError):
    """Rendering needs a graphics adapter and none was found (install Mesa's lavapipe: mesa-vulkan-drivers)."""


class NotComputedError(ValueError):
    """A board time after the one the physics has reached was asked for: run the simulation to it first."""


_ERRORS = (
    SceneError,
    SpeedOfLightError,
    OverlapError,
    OutOfRangeError,
    BrakingHorizonError,
    NoAdapterError,
    NotComputedError,
)
for _cls in _ERRORS:
    _cls.__module__ = "_lightcone"


def _exception(kind):
    """The exception class the engine named (RuntimeError for a name that
    is none), as `lightcone_remote._exception` resolves one."""
    cls = globals().get(kind) if kind in __all__ else None
    cls = cls or getattr(builtins, kind, None)
    if isinstance(cls, type) and issubclass(cls, Exception):
        return cls
    return RuntimeError


# ---- The engine.


def _remote():
    # Imported when first needed: it imports `lightcone`, which imports
    # this module.
    import lightcone_remote

    return lightcone_remote


def _engine(request, what):
    """Sends `request` to the engine; its reply (a dict with "ok" and
    perhaps "state"), or raises the error it names. `what` names the
    call in the message for a number JSON cannot carry."""
    try:
        text = json.dumps(request, allow_nan=False)
    except ValueError:
        raise ValueError(f"{what}: every number must be finite") from None
    reply = json.loads(str(_lightcone_call(text)))
    if "error" in reply:
        kind, message = reply["error"]
        raise _exception(kind)(message)
    return reply


def _args(values):
    """Arguments as JSON data (a tuple, a numpy array: a list)."""
    return _remote().encode(list(values))


def _value(reply):
    """The reply's value, records, scenes and frames rebuilt."""
    return _remote().decode(reply.get("ok"), frames=True)


def _final(cls, **kwargs):
    raise TypeError(f"type 'lightcone._lightcone.{cls.__mro__[1].__name__}' is not an acceptable base type")


def _rust_float(x):
    """`x` as Rust's `{}` writes an f64 (no exponent, no ".0"), for the
    repr that the extension formats itself."""
    x = float(x)
    if x != x:
        return "NaN"
    if x in (float("inf"), float("-inf")):
        return "inf" if x > 0 else "-inf"
    text = repr(x)
    if "e" in text:
        mantissa, exponent = text.split("e")
        sign = "-" if mantissa.startswith("-") else ""
        digits = mantissa.lstrip("-")
        whole, _, frac = digits.partition(".")
        frac = frac.rstrip("0") if frac != "0" else ""
        point = len(whole) + int(exponent)
        all_digits = whole + frac
        if point <= 0:
            text = sign + "0." + "0" * -point + all_digits
        elif point >= len(all_digits):
            text = sign + all_digits + "0" * (point - len(all_digits))
        else:
            text = sign + all_digits[:point] + "." + all_digits[point:]
    return text[:-2] if text.endswith(".0") else text


# ---- Frame: a rendered picture, kept here (its bytes come from the engine
# or the game).


class Frame:
    """A rendered picture (shown inline in Jupyter)."""

    __slots__ = ("_png", "_width", "_height", "_t")
    __init_subclass__ = classmethod(_final)

    def __new__(cls, *args, **kwargs):
        raise TypeError("No constructor defined for Frame")

    @staticmethod
    def _from_png(png, width, height, t):
        """A frame from its PNG bytes: how a lesson receives
        `world.diagram(...)` from the game (which made the PNG)."""
        frame = object.__new__(Frame)
        object.__setattr__(frame, "_png", bytes(png))
        object.__setattr__(frame, "_width", int(width))
        object.__setattr__(frame, "_height", int(height))
        object.__setattr__(frame, "_t", float(t))
        return frame

    def __setattr__(self, name, value):
        raise AttributeError(f"'lightcone._lightcone.Frame' object attribute '{name}' is read-only")

    @property
    def width(self):
        """Width, pixels."""
        return self._width

    @property
    def height(self):
        """Height, pixels."""
        return self._height

    @property
    def t(self):
        """Board time of the picture, s."""
        return self._t

    @property
    def png(self):
        """The PNG file's bytes."""
        return self._png

    def save(self, path):
        """Saves the picture as a PNG file."""
        path = os.fspath(path)
        try:
            with open(path, "wb") as f:
                f.write(self._png)
        except OSError as e:
            raise OSError(f"{path}: {e.strerror} (os error {e.errno})") from None

    def to_numpy(self):
        """The pixels as a numpy array of shape (height, width, 4), dtype
        uint8, RGBA, row 0 at the top. Needs numpy (ImportError otherwise)."""
        numpy = _numpy("Frame.to_numpy")
        pixels = _png_rgba(self._png, self._width, self._height)
        return numpy.frombuffer(pixels, "uint8").reshape(self._height, self._width, 4).copy()

    def _repr_png_(self):
        return self._png

    def __repr__(self):
        return f"Frame({self._width}×{self._height} px, t = {_rust_float(self._t)} s)"


def _numpy(what):
    """numpy, or the ImportError the extension raises without it."""
    try:
        import numpy
    except ImportError as e:
        raise ImportError(f"{what} returns a numpy array and needs numpy: pip install numpy ({e})") from None
    return numpy


def _png_rgba(png, width, height):
    """The RGBA pixels of an 8-bit RGBA, non-interlaced PNG (what the
    engine and the game encode), rows from the top."""
    import struct
    import zlib

    bad = RuntimeError
    if png[:8] != b"\x89PNG\r\n\x1a\n":
        raise bad("the frame's PNG: not a PNG file")
    pos, data, header = 8, [], None
    while pos + 8 <= len(png):
        (length,) = struct.unpack(">I", png[pos : pos + 4])
        kind, body = png[pos + 4 : pos + 8], png[pos + 8 : pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            data.append(body)
        elif kind == b"IEND":
            break
    if header is None or header[2:5] != (8, 6, 0) or header[6] != 0 or header[:2] != (width, height):
        raise bad(f"the frame's PNG is not {width}×{height} RGBA 8 bits")
    raw = zlib.decompress(b"".join(data))
    stride = width * 4
    out = bytearray(stride * height)
    prev = bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind, row = raw[start], bytearray(raw[start + 1 : start + 1 + stride])
        for i in range(stride):
            a = row[i - 4] if i >= 4 else 0
            b = prev[i]
            c = prev[i - 4] if i >= 4 else 0
            if kind == 1:
                row[i] = (row[i] + a) & 255
            elif kind == 2:
                row[i] = (row[i] + b) & 255
            elif kind == 3:
                row[i] = (row[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out[y * stride : (y + 1) * stride] = row
        prev = row
    return bytes(out)


# ---- Scene: a validated scene, its state the engine's JSON of it.


def _scene(op, state, args=(), what=None):
    return _engine(
        {"class": "Scene", "op": op, "state": state, "args": _args(args), "kwargs": {}},
        what or f"Scene.{op.lstrip('=')}",
    )


def _with_state(state):
    scene = object.__new__(Scene)
    object.__setattr__(scene, "_state", state)
    return scene


class Scene:
    """A validated scene."""

    __slots__ = ("_state",)
    __init_subclass__ = classmethod(_final)

    def __init__(self, size=(2.84, 1.42), c=None, title="scene", friction=0.0, gravity=9.80665, description=""):
        """An empty scene on a table of `size` = (x, y) m with speed of light `c` m/s, sliding `friction` μ under `gravity` m/s², and the `description` shown under its title."""
        reply = _scene("new", None, (size, c, title, friction, gravity, description), "Scene")
        object.__setattr__(self, "_state", reply["state"])

    def __setattr__(self, name, value):
        # Only the settable properties (a pyo3 object takes no other
        # attribute).
        if name in ("friction", "gravity", "c"):
            reply = _scene("=" + name, self._state, (value,))
            object.__setattr__(self, "_state", reply["state"])
        elif name in ("title", "description", "pucks", "observers", "effects"):
            raise AttributeError(f"attribute '{name}' of 'lightcone._lightcone.Scene' objects is not writable")
        else:
            raise AttributeError(f"'lightcone._lightcone.Scene' object has no attribute '{name}'")

    def _get(self, op):
        return _value(_scene(op, self._state))

    def _change(self, op, args):
        reply = _scene(op, self._state, args)
        object.__setattr__(self, "_state", reply["state"])

    @property
    def friction(self):
        """Sliding friction μ of the table (0: frictionless)."""
        return self._get("friction")

    @property
    def gravity(self):
        """Gravity under the table, m/s²."""
        return self._get("gravity")

    @property
    def c(self):
        """Speed of light, m/s."""
        return self._get("c")

    @property
    def title(self):
        """Scene title."""
        return self._get("title")

    @property
    def description(self):
        """The scene's description (shown under its title when it opens)."""
        return self._get("description")

    @property
    def pucks(self):
        """Puck names, in file order."""
        return self._get("pucks")

    @property
    def observers(self):
        """Observer names, in file order."""
        return self._get("observers")

    @property
    def effects(self):
        """The effects as a dict of flags."""
        return self._get("effects")

    def add_puck(self, name, position, beta=None, u=None, radius=0.0305, height=0.02, mass=0.21, color=None, velocity=None):
        """Adds a puck at `position` (x, y) m; at most one of `beta` (v/c), `velocity` (m/s), `u` (γβ).
        `radius`, `height` in m, `mass` in kg. Raises SpeedOfLightError, OverlapError, OutOfRangeError,
        BrakingHorizonError or SceneError (each a SceneError)."""
        self._change("add_puck", (name, position, beta, u, radius, height, mass, color, velocity))

    def add_observer(self, name, position, look_at=None, beta=None):
        """Adds an observer with its eye at `position` (x, y, z) m, moving at `beta` (v/c).
        Its views frame the whole table unless `look_at` (x, y, z) m is given: then they look there with a 60° field."""
        self._change("add_observer", (name, position, look_at, beta))

    def set_effect(self, name, on):
        """Turns an effect on or off (`contraction`, `light_delay`,
        `aberration`, `doppler`, `searchlight`, `time_dilation`)."""
        self._change("set_effect", (name, on))

    @staticmethod
    def load(path):
        """Reads and validates a scene file (from the worker's file
        system: the engine reads none). Raises SceneError naming the
        file, line and field of every problem."""
        return _with_state(_scene("from_toml", None, _read_scene(path), "Scene.load")["state"])

    @staticmethod
    def from_toml(text, name="<string>"):
        """Parses and validates scene TOML text; `name` is used in messages."""
        return _with_state(_scene("from_toml", None, (text, name))["state"])

    def _to_json(self):
        """The scene as JSON (the engine's serde form): how a lesson sends
        `world.start(scene)` to the game."""
        return self._state

    @staticmethod
    def _from_json(text):
        """The scene `_to_json` wrote, checked again as a scene built in
        code is (SceneError otherwise)."""
        return _with_state(_scene("_from_json", None, (text,))["state"])

    def __repr__(self):
        return self._get("repr")


# Largest scene file read, bytes (the engine's MAX_SCENE_BYTES).
_MAX_SCENE_BYTES = 256 << 20


def _read_scene(path):
    """(text, name) of the scene file at `path`, or the SceneError the
    engine's `scene::read_text` gives (a file as a whole: "FILE: …")."""
    name = os.fspath(path)
    if isinstance(name, bytes):
        name = os.fsdecode(name)
    try:
        with open(name, "rb") as f:
            data = f.read(_MAX_SCENE_BYTES + 1)
    except OSError as e:
        raise SceneError(f"{name}: cannot read: {e.strerror} (os error {e.errno})") from None
    if len(data) > _MAX_SCENE_BYTES:
        raise SceneError(f"{name}: more than {_MAX_SCENE_BYTES >> 20} MiB: not a scene file")
    try:
        return data.decode("utf-8"), name
    except UnicodeDecodeError as e:
        before = data[: e.start].decode("utf-8")
        line = before.count("\n") + 1
        column = len(before) - (before.rfind("\n") + 1) + 1
        message = f"byte 0x{data[e.start]:02x} is not UTF-8: save the scene as UTF-8 text"
        raise SceneError(f"{name}:{line}:{column}: {message}") from None


# ---- Simulation: the engine's physics of a scene, by id.


class Simulation:
    """The event-anticipation physics of a scene. Safe to share between
    threads: a call made while `run_until` runs waits for a consistent state."""

    __slots__ = ("_id", "__weakref__")
    __init_subclass__ = classmethod(_final)

    def __init__(self, scene, history=None):
        """`history`: seconds of board time of worldlines and collisions to
        keep (None: the whole run); memory stays bounded with a horizon."""
        if not isinstance(scene, Scene):
            raise TypeError(f"argument 'scene': '{type(scene).__name__}' object cannot be converted to 'Scene'")
        reply = _engine(
            {
                "class": "Simulation",
                "op": "new",
                "args": [scene._state],
                "kwargs": {"history": _remote().encode(history)},
            },
            "Simulation",
        )
        object.__setattr__(self, "_id", reply["ok"])

    def __setattr__(self, name, value):
        raise AttributeError(f"'lightcone._lightcone.Simulation' object attribute '{name}' is read-only")

    def _call(self, op, *args):
        reply = _engine(
            {"class": "Simulation", "id": self._id, "op": op, "args": _args(args), "kwargs": {}},
            f"Simulation.{op}",
        )
        return _value(reply)

    def __del__(self):
        # The engine forgets the simulation with the Python object.
        sim = getattr(self, "_id", None)
        if sim is not None:
            try:
                _lightcone_call(json.dumps({"class": "Simulation", "id": sim, "op": "drop", "args": [], "kwargs": {}}))
            except Exception:
                pass  # the worker is ending

    @property
    def history(self):
        """The history horizon, s (None: everything is kept)."""
        return self._call("history")

    @property
    def forgotten_before(self):
        """Board time before which the past has been forgotten, s."""
        return self._call("forgotten_before")

    @property
    def scene(self):
        """The scene simulated (a copy)."""
        scene = self._call("scene")
        # The engine's own JSON of it (or a tagged scene, already rebuilt).
        return _with_state(scene) if isinstance(scene, str) else scene

    @property
    def time(self):
        """Board time reached, s."""
        return self._call("time")

    def run_until(self, t):
        """Runs the physics to board time `t` s."""
        self._call("run_until", t)

    def step(self, dt):
        """Advances by `dt` s of board time."""
        self._call("step", dt)

    def impulse(self, name, du):
        """Adds `du` to the proper velocity γβ of puck `name` now."""
        self._call("impulse", name, du)

    def collisions(self):
        """Every collision so far, oldest first (records: `c.t`, `c.pucks[0].u_after`, or `c["t"]`)."""
        return self._call("collisions")

    def state(self):
        """Every puck now (a record: `s.pucks[0].position`, or `s["pucks"][0]["position"]`)."""
        return self._call("state")

    def observe(self, observer=None, vertices=False, effects=None, at=None):
        """What `observer` sees at board time `at` s (default: now)."""
        return self._call("observe", observer, vertices, effects, at)

    def positions(self, at=None):
        """Every puck's board position (m) at board time `at` (default: now) as a numpy array of
        shape (N, 2), float64, in scene order. Needs numpy."""
        return self._rows("positions", at)

    def velocities(self, at=None):
        """Every puck's proper velocity u = γβ at board time `at` (default: now) as a numpy array of
        shape (N, 2), float64, in scene order. Needs numpy."""
        return self._rows("velocities", at)

    def _rows(self, op, at):
        rows = self._call(op, at)
        numpy = _numpy(f"Simulation.{op}")
        return numpy.array(rows, "float64").reshape(len(rows), 2)

    def velocity(self, name):
        """Proper velocity γβ of puck `name` now, (x, y)."""
        return tuple(self._call("velocity", name))

    def render(self, path=None, observer=None, size=(1280, 720), view="seen", at=None):
        """Renders what `observer` sees at board time `at` s (default: now); saves it to `path` if given."""
        return _saved(self._call("render", None, observer, size, view, at), path)

    def diagram(self, path=None, observer=None, size=(1000, 700), at=None, axis="x", frame=None):
        """The space-time diagram at board time `at` s (default: now), board
        `axis` ("x" or "y") across, with puck `frame`'s lines of
        simultaneity; saved to `path` if given."""
        return _saved(self._call("diagram", None, observer, size, at, axis, frame), path)

    def simultaneity(self, frame, at=None):
        """Puck `frame`'s line of simultaneity through its event at `at` s."""
        return self._call("simultaneity", frame, at)

    def warnings(self):
        """Warnings (e.g. a Zeno sequence ended)."""
        return self._call("warnings")

    def _repr_png_(self):
        try:
            return self.render(size=(640, 360)).png
        except Exception:
            return None

    def __repr__(self):
        return self._call("repr")


def _saved(frame, path):
    """`frame`, written to `path` first if one is given (here: the
    engine writes no file)."""
    if path is not None and isinstance(frame, Frame):
        frame.save(path)
    return frame


# ---- World: only for isinstance (a lesson's world is
# `lightcone_remote.World`, which reports this class).


class World:
    """The running game as a lesson's hooks see it (`lightcone play LESSON.py`)."""

    __init_subclass__ = classmethod(_final)

    def __new__(cls, *args, **kwargs):
        raise TypeError("No constructor defined for World")
