"""Lightcone: a relativistic carom billiard, from Python.

    >>> import lightcone
    >>> scene = lightcone.Scene.load("assets/scenes/paper_carom.toml")
    >>> sim = lightcone.Simulation(scene)
    >>> sim.run_until(20.0)
    >>> sim.collisions()[0]["kind"]
    'puck_puck'

Collision and observation records are the dictionaries that
`lightcone simulate` and `lightcone observe` print as JSON (README).
Lessons (`lightcone play LESSON.py`) receive a `World` in their hooks.
"""

from ._lightcone import Scene, SceneError, Simulation, World

__all__ = ["Scene", "SceneError", "Simulation", "World"]
