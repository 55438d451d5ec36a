"""Records are classes: typed attributes, the old keys, repr and to_dict."""

import json
import math
import pickle

import pytest

import lightcone
from lightcone import records


def head_on():
    """A puck at 0.8 c strikes an equal one at rest (c = 2 m/s)."""
    s = lightcone.Scene(size=(4.0, 2.0), c=2.0, title="head-on")
    s.add_puck("a", (1.0, 1.0), beta=(0.8, 0.0))
    s.add_puck("b", (3.0, 1.0))
    s.add_observer("side", (2.0, -1.5, 1.0))
    sim = lightcone.Simulation(s)
    sim.run_until(2.0)  # the hit (≈ 1.22 s) and b's cushion (≈ 1.84 s)
    return sim


def test_a_collision_is_a_record_with_attributes_and_keys():
    sim = head_on()
    hit, cushion = sim.collisions()[:2]
    assert isinstance(hit, records.Collision) and isinstance(hit, lightcone.Record)
    assert isinstance(hit.pucks[1], records.CollisionPuck)
    assert hit.kind == hit["kind"] == "puck_puck"
    # Equal masses, elastic, head-on: b leaves with a's proper velocity.
    b = hit.pucks[1]
    assert b.name == "b"
    assert b.u_after[0] == pytest.approx(0.8 / math.sqrt(1 - 0.64), rel=1e-12)
    assert hit["pucks"][1]["u_after"] == b.u_after
    # An optional field: absent by key, None by attribute.
    assert hit.cushion is None and "cushion" not in hit
    with pytest.raises(KeyError):
        hit["cushion"]
    assert cushion.cushion == cushion["cushion"] == "x1"
    assert hit.get("cushion") is None and b.mass_before is None
    with pytest.raises(AttributeError, match="no field 'speed'.*kind"):
        hit.speed


def test_to_dict_is_plain_json_and_equal_to_the_record():
    sim = head_on()
    hit = sim.collisions()[0]
    d = hit.to_dict()
    assert type(d) is dict and type(d["pucks"][0]) is dict
    assert json.loads(json.dumps(d)) == d
    assert hit == d and dict(hit)["kind"] == "puck_puck"
    assert pickle.loads(pickle.dumps(hit)) == hit


def test_repr_names_the_class_and_fields():
    sim = head_on()
    text = repr(sim.collisions()[0])
    assert text.startswith("Collision(kind='puck_puck', t=")
    assert "CollisionPuck(name='a'" in text
    assert repr(sim.state()).startswith("State(kind='state', t=2.0")


def test_state_and_observation_records_nest():
    sim = head_on()
    state = sim.state()
    assert isinstance(state, records.State)
    assert [p.name for p in state.pucks] == ["a", "b"]
    assert isinstance(state.pucks[0], records.PuckState)
    assert state.pucks[0].proper_time < state.t  # a moved: its clock ran slow
    seen = sim.observe("side", at=1.5, vertices=True)
    assert isinstance(seen, records.Observation)
    assert isinstance(seen.observer, records.ObserverState)
    puck = seen.pucks[0]
    assert isinstance(puck, records.SeenPuck) and isinstance(puck.emission, records.Emission)
    # Light left the puck before the observation.
    assert puck.emission.t < seen.t
    assert isinstance(puck.vertices[0], records.SeenPoint)
    assert seen["pucks"][0]["emission"]["t"] == puck.emission.t


def test_records_are_read_only():
    rec = head_on().state()
    with pytest.raises(AttributeError, match="read-only"):
        rec.t = 0.0
    with pytest.raises(TypeError):
        rec["t"] = 0.0  # type: ignore[index]
