"""Lightcone: a relativistic carom billiard, from Python.

    >>> import lightcone
    >>> scene = lightcone.Scene.load("assets/scenes/paper_carom.toml")
    >>> sim = lightcone.Simulation(scene)
    >>> sim.run_until(20.0)
    >>> sim.collisions()[0].kind
    'puck_puck'

Collision, state and observation records are classes in
`lightcone.records` (`Collision`, `State`, `Observation`, ...) holding the
JSON objects that `lightcone simulate` and `lightcone observe` print
(docs/guide/src/python.md): fields as attributes (typed, with units) or keys
(`c["kind"]`), `repr`, and `to_dict()`. Lessons
(`lightcone play LESSON.py`) receive a `World` in their hooks.
"""

from . import records
from ._lightcone import (
    BrakingHorizonError,
    Frame,
    NoAdapterError,
    NotComputedError,
    OutOfRangeError,
    OverlapError,
    Scene,
    SceneError,
    Simulation,
    SpeedOfLightError,
    World,
    __version__,
)
from .records import Collision, Observation, Record, State

__all__ = [
    "BrakingHorizonError",
    "Collision",
    "Frame",
    "NoAdapterError",
    "NotComputedError",
    "Observation",
    "OutOfRangeError",
    "OverlapError",
    "Record",
    "Scene",
    "SceneError",
    "Simulation",
    "SpeedOfLightError",
    "State",
    "World",
    "__version__",
    "records",
]
