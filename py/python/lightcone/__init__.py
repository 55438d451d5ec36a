"""Lightcone: a relativistic carom billiard, from Python.

    >>> import lightcone
    >>> scene = lightcone.Scene.load("assets/scenes/paper_carom.toml")
    >>> sim = lightcone.Simulation(scene)
    >>> sim.run_until(20.0)
    >>> sim.collisions()[0]["kind"]
    'puck_puck'

Collision, state and observation records are the dictionaries that
`lightcone simulate` and `lightcone observe` print as JSON (README); their
keys, types and units are in `lightcone.records`. Lessons
(`lightcone play LESSON.py`) receive a `World` in their hooks.
"""

from . import records
from ._lightcone import (
    Frame,
    NoAdapterError,
    NotComputedError,
    Scene,
    SceneError,
    Simulation,
    SpeedOfLightError,
    World,
)
from .records import Collision, Observation, State

__all__ = [
    "Collision",
    "Frame",
    "NoAdapterError",
    "NotComputedError",
    "Observation",
    "Scene",
    "SceneError",
    "Simulation",
    "SpeedOfLightError",
    "State",
    "World",
    "records",
]
