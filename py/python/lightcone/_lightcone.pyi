"""Type stubs of the native module (checked against it with mypy.stubtest).

Units: metres, seconds of board time, kilograms; velocities as β = v/c, as
v in m/s, or as proper velocity u = γβ (dimensionless). Wherever a vector
goes, any sequence of numbers is accepted: a tuple, a list, a numpy array.
"""

from os import PathLike
from typing import Any, Iterator, Optional, Protocol, Sequence, SupportsFloat, Union, final

from lightcone.records import Collision, Observation, Simultaneity, State

__version__: str
"""The package's version (the workspace's, as `pip show lightcone` gives it)."""

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
    "_standin_call",
]

class _Numbers(Protocol):
    """A sequence of numbers: tuple, list or numpy array."""

    def __len__(self) -> int: ...
    def __iter__(self) -> Iterator[SupportsFloat]: ...

_Vector = Union[Sequence[float], _Numbers]

class SceneError(ValueError):
    """A scene is invalid; the message names the file, line and field (or the puck or observer)."""

class SpeedOfLightError(SceneError):
    """A speed at or above c was given (β ≥ 1); no body reaches c."""

class OverlapError(SceneError):
    """Two pucks overlap at board time 0 (their rest-frame discs; touching is allowed)."""

class OutOfRangeError(SceneError):
    """A number lies outside what the engine holds (a length, mass, c, friction, gravity, restitution or |u|)."""

class BrakingHorizonError(SceneError):
    """A puck cannot brake rigidly on the cloth: its radius reaches the braking's Rindler horizon c²/(μg)."""

class NoAdapterError(RuntimeError):
    """Rendering needs a graphics adapter and none was found (install mesa-vulkan-drivers)."""

class NotComputedError(ValueError):
    """A board time after the one the physics has reached was asked for."""

@final
class Frame:
    """A rendered picture (shown inline in Jupyter)."""

    @property
    def width(self) -> int:
        """Width, pixels."""
    @property
    def height(self) -> int:
        """Height, pixels."""
    @property
    def t(self) -> float:
        """Board time of the picture, s."""
    @property
    def png(self) -> bytes:
        """The PNG file's bytes."""
    def save(self, path: Union[str, PathLike[str]]) -> None:
        """Saves the picture as a PNG file."""
    def to_numpy(self) -> Any:
        """The pixels as a numpy array of shape (height, width, 4), dtype uint8, RGBA, row 0 at the top.
        Needs numpy (ImportError otherwise)."""
    def _repr_png_(self) -> bytes: ...

@final
class Scene:
    """A validated scene."""

    def __new__(
        cls,
        size: _Vector = ...,
        c: Optional[float] = None,
        title: str = "scene",
        friction: float = 0.0,
        gravity: float = 9.80665,
        description: str = "",
    ) -> Scene:
        """An empty scene on a table of `size` = (x, y) m with speed of light `c` m/s, sliding `friction` μ under `gravity` m/s², and the `description` shown under its title."""
    @property
    def friction(self) -> float:
        """Sliding friction μ of the table (0: frictionless)."""
    @friction.setter
    def friction(self, value: float) -> None: ...
    @property
    def gravity(self) -> float:
        """Gravity under the table, m/s²."""
    @gravity.setter
    def gravity(self, value: float) -> None: ...
    def add_puck(
        self,
        name: str,
        position: _Vector,
        beta: Optional[_Vector] = None,
        u: Optional[_Vector] = None,
        radius: float = 0.0305,
        height: float = 0.02,
        mass: float = 0.21,
        color: Optional[str] = None,
        velocity: Optional[_Vector] = None,
    ) -> None:
        """Adds a puck at `position` (x, y) m; at most one of `beta` (v/c), `velocity` (m/s), `u` (γβ).
        `radius`, `height` in m, `mass` in kg. Raises SpeedOfLightError, OverlapError, OutOfRangeError,
        BrakingHorizonError or SceneError (each a SceneError)."""
    def add_observer(
        self,
        name: str,
        position: _Vector,
        look_at: Optional[_Vector] = None,
        beta: Optional[_Vector] = None,
    ) -> None:
        """Adds an observer with its eye at `position` (x, y, z) m, moving at `beta` (v/c).
        Its views frame the whole table unless `look_at` (x, y, z) m is given: then they look there with a 60° field."""
    def set_effect(self, name: str, on: bool) -> None: ...
    @staticmethod
    def load(path: Union[str, PathLike[str]]) -> Scene: ...
    @staticmethod
    def from_toml(text: str, name: str = "<string>") -> Scene: ...
    @property
    def c(self) -> float:
        """Speed of light, m/s."""
    @c.setter
    def c(self, c: float) -> None: ...
    @property
    def title(self) -> str: ...
    @property
    def description(self) -> str: ...
    @property
    def pucks(self) -> list[str]: ...
    @property
    def observers(self) -> list[str]: ...
    @property
    def effects(self) -> dict[str, bool]: ...

@final
class Simulation:
    """The event-anticipation physics of a scene. Safe to share between
    threads: a call made while `run_until` runs waits for a consistent state."""

    def __new__(cls, scene: Scene, history: Optional[float] = None) -> Simulation:
        """`history`: seconds of board time of worldlines and collisions to
        keep (None: the whole run); memory stays bounded with a horizon."""
    @property
    def history(self) -> Optional[float]:
        """The history horizon, s (None: everything is kept)."""
    @property
    def forgotten_before(self) -> Optional[float]:
        """Board time before which the past has been forgotten, s."""
    @property
    def scene(self) -> Scene: ...
    @property
    def time(self) -> float:
        """Board time reached, s."""
    def run_until(self, t: float) -> None:
        """Runs the physics to board time `t` s; Ctrl-C stops it promptly."""
    def step(self, dt: float) -> None:
        """Advances by `dt` s of board time."""
    def impulse(self, name: str, du: _Vector) -> None:
        """Adds `du` to the proper velocity γβ of puck `name` now."""
    def collisions(self) -> list[Collision]:
        """Every collision so far, oldest first (records: `c.t`, `c.pucks[0].u_after`, or `c["t"]`)."""
    def state(self) -> State:
        """Every puck now (a record: `s.pucks[0].position`, or `s["pucks"][0]["position"]`)."""
    def observe(
        self,
        observer: Optional[str] = None,
        vertices: bool = False,
        effects: Optional[Sequence[str]] = None,
        at: Optional[float] = None,
    ) -> Observation:
        """What `observer` sees at board time `at` s (default: now)."""
    def positions(self, at: Optional[float] = None) -> Any:
        """Every puck's board position (m) at board time `at` (default: now) as a numpy array of
        shape (N, 2), float64, in scene order. Needs numpy."""
    def velocities(self, at: Optional[float] = None) -> Any:
        """Every puck's proper velocity u = γβ at board time `at` (default: now) as a numpy array of
        shape (N, 2), float64, in scene order. Needs numpy."""
    def velocity(self, name: str) -> tuple[float, float]:
        """Proper velocity γβ of puck `name` now, (x, y)."""
    def render(
        self,
        path: Optional[Union[str, PathLike[str]]] = None,
        observer: Optional[str] = None,
        size: tuple[int, int] = ...,
        view: str = "seen",
        at: Optional[float] = None,
    ) -> Frame:
        """Renders what `observer` sees at board time `at` s (default: now); saves it to `path` if given.
        Framed as `lightcone render` frames it: the whole table with a margin, unless the observer has a `look_at`."""
    def diagram(
        self,
        path: Optional[Union[str, PathLike[str]]] = None,
        observer: Optional[str] = None,
        size: tuple[int, int] = ...,
        at: Optional[float] = None,
        axis: str = "x",
        frame: Optional[str] = None,
    ) -> Frame:
        """The space-time diagram at board time `at` s (default: now), board
        `axis` ("x" or "y") across, with puck `frame`'s lines of
        simultaneity; drawn on the CPU; saved to `path` if given."""
    def simultaneity(self, frame: str, at: Optional[float] = None) -> Simultaneity:
        """Puck `frame`'s line of simultaneity through its event at `at` s."""
    def warnings(self) -> list[str]: ...
    def _repr_png_(self) -> Optional[bytes]: ...

@final
class World:
    """The running game as a lesson's hooks see it (`lightcone play LESSON.py`)."""

    def start(self, scene: Scene) -> None: ...
    def load(self, path: Union[str, PathLike[str]]) -> Scene: ...
    @property
    def scene(self) -> Scene: ...
    @property
    def t(self) -> float:
        """Board time, s."""
    @property
    def c(self) -> float:
        """Speed of light, m/s."""
    @property
    def paused(self) -> bool: ...
    @paused.setter
    def paused(self, paused: bool) -> None: ...
    def pause(self) -> None: ...
    def resume(self) -> None: ...
    @property
    def time_scale(self) -> float:
        """Board seconds per real second."""
    @time_scale.setter
    def time_scale(self, scale: float) -> None: ...
    @property
    def view(self) -> str: ...
    @view.setter
    def view(self, view: str) -> None: ...
    @property
    def observer(self) -> Optional[str]: ...
    @observer.setter
    def observer(self, name: Optional[str]) -> None: ...
    @property
    def effects(self) -> dict[str, bool]: ...
    def set_effect(self, name: str, on: bool) -> None: ...
    def state(self) -> State: ...
    def collisions(self) -> list[Collision]: ...
    def velocity(self, name: str) -> tuple[float, float]: ...
    def impulse(self, name: str, du: _Vector) -> None: ...
    def observe(
        self,
        observer: Optional[str] = None,
        t: Optional[float] = None,
        vertices: bool = False,
        effects: Optional[Sequence[str]] = None,
        at: Optional[float] = None,
    ) -> Observation: ...
    def diagram(
        self,
        path: Optional[Union[str, PathLike[str]]] = None,
        observer: Optional[str] = None,
        size: tuple[int, int] = ...,
        at: Optional[float] = None,
        axis: str = "x",
        frame: Optional[str] = None,
    ) -> Frame:
        """The space-time diagram (see `Simulation.diagram`); `path` relative to the lesson."""
    def show_diagram(self, on: bool = True, frame: Optional[str] = None, axis: str = "x") -> None:
        """Opens or closes the live diagram in the window, with puck `frame`'s lines of simultaneity."""
    def simultaneity(self, frame: str, at: Optional[float] = None) -> Simultaneity: ...
    def say(self, text: str, append: bool = False) -> None: ...
    def ask(self, question: str, choices: Sequence[str], answer: Optional[int] = None) -> None: ...
    def check(self, claim: str, ok: bool, detail: str = "") -> bool: ...
    @property
    def claims(self) -> list[tuple[str, bool, str]]: ...
    def bars(
        self,
        title: str,
        edges: Sequence[float],
        counts: Sequence[float],
        expected: Optional[Sequence[float]] = None,
    ) -> None: ...
    def finish(self, message: str = "", after_light_from: Optional[_Vector] = None) -> None:
        """Ends the lesson: no hook runs again, and the message is shown at once, or, with
        `after_light_from = (t, x, y)` (a board event: s, m, m), once that event's light has
        reached the eye looked through (at rest at distance d: at board time t + d / c)."""
    @property
    def finished(self) -> bool:
        """Whether `finish` was called."""

def _standin_call(request: str) -> str:
    """The browser's Scene and Simulation stand-ins' one call (JSON in,
    JSON out: lightcone_lesson::standin), for testing them against this
    module's classes. Not part of the API."""
    ...
