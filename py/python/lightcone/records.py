"""The records `lightcone` returns: collisions, puck outcomes, states and
observations, as classes.

Each record holds the JSON object that `lightcone simulate` or `lightcone
observe` prints for it (see the guide, docs/guide/src/commands.md) and offers it three ways:

- as attributes, typed here: `sim.collisions()[0].pucks[1].u_after`;
- by key, as before, so code written for dictionaries keeps working:
  `rec["pucks"][1]["u_after"]`, `"cushion" in rec`, `rec.get("cushion")`,
  `dict(rec)`, `rec == {...}` (a record is a read-only `Mapping`);
- as plain data: `rec.to_dict()` (dicts and lists all the way down, for
  `json.dumps`).

An optional field that a record lacks (`cushion` of a puck-puck collision,
`mass_before` of an elastic one) reads as `None` by attribute and raises
`KeyError` by key. Records are read-only.

Units: metres, seconds of board time (or of proper time where named),
kilograms; velocities as β = v/c or as proper velocity u = γβ
(dimensionless).
"""

from collections.abc import Mapping
from typing import Any, ClassVar, Dict, Iterator, List, Optional, TypedDict

__all__ = [
    "Record",
    "CollisionPuck",
    "Collision",
    "PuckState",
    "State",
    "Emission",
    "ObserverState",
    "SeenPoint",
    "SeenPuck",
    "Observation",
    "BoardEvent",
    "Simultaneity",
]


def _plain(value: Any) -> Any:
    if isinstance(value, Record):
        return value.to_dict()
    if isinstance(value, list):
        return [_plain(v) for v in value]
    return value


class Record(Mapping):  # type: ignore[type-arg]
    """A record: attribute and key access to one JSON object of the command
    line, `to_dict()` and a `repr` that shows its fields."""

    __slots__ = ("_data",)
    _children: ClassVar[Dict[str, type]] = {}
    """Fields holding records (or lists of records) of these classes."""

    def __init__(self, data: Mapping) -> None:  # type: ignore[type-arg]
        d = dict(data)
        for key, cls in type(self)._children.items():
            if key in d:
                v = d[key]
                d[key] = [cls(x) for x in v] if isinstance(v, list) else cls(v)
        object.__setattr__(self, "_data", d)

    @classmethod
    def _fields(cls) -> List[str]:
        names: List[str] = []
        for klass in reversed(cls.__mro__):
            for name in getattr(klass, "__annotations__", {}):
                if not name.startswith("_") and name not in names:
                    names.append(name)
        return names

    def __getattr__(self, name: str) -> Any:
        data = object.__getattribute__(self, "_data")
        if name in data:
            return data[name]
        if name in type(self)._fields():
            return None  # an optional field this record lacks
        raise AttributeError(
            f"{type(self).__name__} has no field {name!r}; its fields: {', '.join(data)}"
        )

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} is read-only (use to_dict() for a copy)")

    def __getitem__(self, key: str) -> Any:
        return self._data[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def to_dict(self) -> Dict[str, Any]:
        """The record as plain dicts and lists (what the command line prints)."""
        return {k: _plain(v) for k, v in self._data.items()}

    def __repr__(self) -> str:
        fields = ", ".join(f"{k}={v!r}" for k, v in self._data.items())
        return f"{type(self).__name__}({fields})"

    def __reduce__(self) -> Any:
        return (type(self), (self.to_dict(),))


class CollisionPuck(Record):
    """One puck's part in a collision: its own velocity-change event."""

    __slots__ = ()

    name: str
    t: float
    """Board time of this puck's velocity change, s (simultaneous with the contact in the pair frame)."""
    position: List[float]
    """Its centre then, (x, y) m."""
    u_before: List[float]
    """Proper velocity γβ before, (x, y)."""
    u_after: List[float]
    """Proper velocity γβ after, (x, y)."""
    beta_before: List[float]
    """β = v/c before, (x, y)."""
    beta_after: List[float]
    """β = v/c after, (x, y)."""
    mass_before: Optional[float]
    """Rest mass before, kg: only when an inelastic collision changed it."""
    mass_after: Optional[float]
    """Rest mass after, kg: only when an inelastic collision changed it."""
    orientation: float
    """Rest-frame orientation after the change, rad counter-clockwise from +x (accumulated Thomas–Wigner rotation)."""
    pending: Optional[bool]
    """Present and True when this puck's velocity change was still ahead (the second kick of a contact)."""


class Collision(Record):
    """A collision: `kind` is "puck_puck" or "cushion"."""

    __slots__ = ()

    kind: str
    cushion: Optional[str]
    """Cushion hits only: "x0", "x1", "y0" or "y1"."""
    t: float
    """Board time of the contact, s."""
    contact: List[float]
    """Contact point, (x, y) m."""
    pucks: List[CollisionPuck]
    simultaneous: Optional[bool]
    """Present and True when several contacts fell at one board time and were resolved together: `pucks` holds every puck of the group."""
    pairs: Optional[List[List[int]]]
    """With `simultaneous`: each pair in contact, as two indices into `pucks`."""


class PuckState(Record):
    """A puck at one board time."""

    __slots__ = ()

    name: str
    position: List[float]
    """Centre, (x, y) m."""
    u: List[float]
    """Proper velocity γβ, (x, y)."""
    beta: List[float]
    """β = v/c, (x, y)."""
    proper_time: float
    """The puck's own clock, s."""
    orientation: float
    """Rest-frame orientation, rad counter-clockwise from +x (accumulated Thomas–Wigner rotation; 0 at t = 0)."""


class State(Record):
    """Every puck at board time `t` (s); `kind` is "state"."""

    __slots__ = ()

    kind: str
    t: float
    pucks: List[PuckState]


class Emission(Record):
    """The event whose light is seen: board time t (s), position (x, y, z) m."""

    __slots__ = ()

    t: float
    position: List[float]


class ObserverState(Record):
    """The observer at the observation."""

    __slots__ = ()

    name: str
    position: List[float]
    """Eye, (x, y, z) m."""
    beta: List[float]
    """β = v/c, (x, y, z)."""
    proper_time: float
    """The observer's clock, s."""


class SeenPoint(Record):
    """A point as seen: where its light left, from which direction it arrives."""

    __slots__ = ()

    emission: Emission
    direction: List[float]
    """Unit vector from the observer, in its rest frame."""
    distance: float
    """Apparent distance in the observer's rest frame, m."""
    doppler: float
    """Observed / emitted frequency (> 1 approaching); 1 when the effect is off."""
    intensity: float
    """Searchlight intensity factor D⁴; 1 when the effect is off."""


class SeenPuck(SeenPoint):
    """A puck as seen: its centre's light (the SeenPoint keys) and its clock."""

    __slots__ = ()

    name: str
    seen_proper_time: float
    """The proper time its clock shows in the picture, s."""
    orientation: float
    """Its rest-frame orientation in the picture, rad counter-clockwise from +x (Thomas–Wigner rotation)."""
    vertices: Optional[List[SeenPoint]]
    """Every mesh vertex, with `vertices=True`."""


class Observation(Record):
    """What an observer sees at board time `t` (s)."""

    __slots__ = ()

    t: float
    observer: ObserverState
    pucks: List[SeenPuck]


# Nested records, set once every class exists.
Collision._children = {"pucks": CollisionPuck}
State._children = {"pucks": PuckState}
SeenPoint._children = {"emission": Emission}
SeenPuck._children = {"emission": Emission, "vertices": SeenPoint}
Observation._children = {"observer": ObserverState, "pucks": SeenPuck}


class BoardEvent(TypedDict):
    """An event on the board: board time t (s), position (x, y) m."""

    t: float
    position: List[float]


class Simultaneity(TypedDict):
    """A puck frame's line of simultaneity (what the space-time diagram
    draws): the board events its rest frame calls simultaneous with `event`
    are those with t = event.t + slope · (position − event.position)."""

    puck: str
    event: BoardEvent
    """The puck's centre at the board time asked for."""
    slope: List[float]
    """(dt/dx, dt/dy), s/m: the puck's velocity / c²."""
