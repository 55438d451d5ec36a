"""The shapes of the records `lightcone` returns, for type checkers.

The records are plain dictionaries (the JSON objects `lightcone simulate`
and `lightcone observe` print, see the README); these TypedDicts name their
keys, types and units. Units: metres, seconds of board time (or of proper
time where named), kilograms; velocities as β = v/c or as proper velocity
u = γβ (dimensionless).
"""

import sys
from typing import List, Optional

if sys.version_info >= (3, 11):
    from typing import NotRequired, TypedDict
else:  # pragma: no cover
    from typing import TypedDict

    NotRequired = Optional  # only for type checkers on old Pythons

__all__ = [
    "CollisionPuck",
    "Collision",
    "PuckState",
    "State",
    "Emission",
    "ObserverState",
    "SeenPoint",
    "SeenPuck",
    "Observation",
]


class CollisionPuck(TypedDict):
    """One puck's part in a collision: its own velocity-change event."""

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
    mass_before: NotRequired[float]
    """Rest mass before, kg: only when an inelastic collision changed it."""
    mass_after: NotRequired[float]
    """Rest mass after, kg: only when an inelastic collision changed it."""
    orientation: float
    """Rest-frame orientation after the change, rad counter-clockwise from +x (accumulated Thomas–Wigner rotation)."""
    pending: NotRequired[bool]
    """Present and True when this puck's velocity change was still ahead (the second kick of a contact)."""


class Collision(TypedDict):
    """A collision: `kind` is "puck_puck" or "cushion"."""

    kind: str
    cushion: NotRequired[str]
    """Cushion hits only: "x0", "x1", "y0" or "y1"."""
    t: float
    """Board time of the contact, s."""
    contact: List[float]
    """Contact point, (x, y) m."""
    pucks: List[CollisionPuck]


class PuckState(TypedDict):
    """A puck at one board time."""

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


class State(TypedDict):
    """Every puck at board time `t` (s); `kind` is "state"."""

    kind: str
    t: float
    pucks: List[PuckState]


class Emission(TypedDict):
    """The event whose light is seen: board time t (s), position (x, y, z) m."""

    t: float
    position: List[float]


class ObserverState(TypedDict):
    """The observer at the observation."""

    name: str
    position: List[float]
    """Eye, (x, y, z) m."""
    beta: List[float]
    """β = v/c, (x, y, z)."""
    proper_time: float
    """The observer's clock, s."""


class SeenPoint(TypedDict):
    """A point as seen: where its light left, from which direction it arrives."""

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

    name: str
    seen_proper_time: float
    """The proper time its clock shows in the picture, s."""
    orientation: float
    """Its rest-frame orientation in the picture, rad counter-clockwise from +x (Thomas–Wigner rotation)."""
    vertices: NotRequired[List[SeenPoint]]
    """Every mesh vertex, with `vertices=True`."""


class Observation(TypedDict):
    """What an observer sees at board time `t` (s)."""

    t: float
    observer: ObserverState
    pucks: List[SeenPuck]
