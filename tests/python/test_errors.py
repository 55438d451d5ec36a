"""Each scene error raises the class of the rule it breaks, chosen by the
engine's typed error (`scene::BuildError`), never by the message's text."""

import pytest

import lightcone


def test_each_broken_rule_raises_its_class():
    s = lightcone.Scene(size=(2.0, 1.0), c=1.0)
    s.add_puck("a", (0.5, 0.5), radius=0.05)
    with pytest.raises(lightcone.OverlapError, match=r'puck "b" overlaps puck "a": centres 0\.050* ?\d* m apart'):
        s.add_puck("b", (0.55, 0.5), radius=0.05)
    with pytest.raises(lightcone.OutOfRangeError, match=r'puck "c" radius: 0 must be a positive finite number'):
        s.add_puck("c", (1.5, 0.5), radius=0.0)
    with pytest.raises(lightcone.OutOfRangeError, match=r"friction: -1 must be"):
        s.friction = -1.0
    with pytest.raises(lightcone.SpeedOfLightError, match=r'puck "d": speed \|β\| = 1 is not below'):
        s.add_puck("d", (1.5, 0.5), beta=(1.0, 0.0))
    with pytest.raises(lightcone.BrakingHorizonError, match=r"cannot brake rigidly"):
        lightcone.Scene(c=0.1, friction=0.2).add_puck("e", (0.5, 0.5))
    with pytest.raises(lightcone.SceneError) as e:
        s.add_puck("a", (1.5, 0.5))
    assert type(e.value) is lightcone.SceneError  # a duplicate name: no subclass
    assert s.pucks == ["a"]
    for cls in (lightcone.OverlapError, lightcone.OutOfRangeError, lightcone.BrakingHorizonError):
        assert issubclass(cls, lightcone.SceneError) and issubclass(cls, ValueError)


def test_the_class_does_not_come_from_the_words():
    # A puck named with the words the old code searched for: overlapping,
    # it is an OverlapError, not a SpeedOfLightError.
    s = lightcone.Scene(size=(2.0, 1.0), c=1.0)
    s.add_puck("not below the speed of light", (0.5, 0.5))
    with pytest.raises(lightcone.OverlapError) as e:
        s.add_puck("x", (0.51, 0.5))
    assert not isinstance(e.value, lightcone.SpeedOfLightError)
    assert "not below the speed of light" in str(e.value)


def test_a_scene_files_errors_raise_the_class_of_their_first_rule():
    with pytest.raises(lightcone.OverlapError, match=r"bad\.toml:5:12: puck\[1\]\.position: .*\(line 1\)"):
        lightcone.Scene.from_toml(
            "[[puck]]\nposition = [0.5, 0.5]\n[[puck]]\nname = \"b\"\nposition = [0.51, 0.5]\n", "bad.toml"
        )
    with pytest.raises(lightcone.OutOfRangeError, match=r"bad\.toml:1:5: c: 0 must be"):
        lightcone.Scene.from_toml("c = 0\n", "bad.toml")
    with pytest.raises(lightcone.BrakingHorizonError, match=r"table\.friction: .*cannot brake rigidly"):
        lightcone.Scene.from_toml("c = 0.1\n[table]\nfriction = 0.2\n[[puck]]\nposition = [0.5, 0.5]\n", "bad.toml")
    # Syntax is no rule: SceneError itself.
    with pytest.raises(lightcone.SceneError) as e:
        lightcone.Scene.from_toml("c = \n", "bad.toml")
    assert type(e.value) is lightcone.SceneError


def test_a_scene_sent_as_json_is_checked_as_one_built_in_code():
    s = lightcone.Scene(size=(2.0, 1.0), c=1.0)
    s.add_puck("a", (0.5, 0.5))
    text = s._to_json().replace('"restitution":1.0', '"restitution":1.5', 1)
    assert '"restitution":1.5' in text
    with pytest.raises(lightcone.OutOfRangeError, match=r"a scene sent as JSON: restitution: 1\.5 must lie in \[0, 1\]"):
        lightcone.Scene._from_json(text)
