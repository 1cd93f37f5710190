"""Scene files with pedestrians (docs/scene-format.md, "Pedestrians"): a [[pedestrians]] entry
is cs.Pedestrian placed by Scene.add with its soft contacts, bit for bit the API's scene; bad
entries refused naming the file, the table and the key."""

from __future__ import annotations

import math
from pathlib import Path

import crashsim as cs
import pytest
from crashsim.io.scenefile import SceneFileError, load_scene, loads_scene

HEAD = """format_version = 1
[run]
duration = "0.05 s"
dt = "0.2 ms"
[ground]
friction = 0.8
[contact]
normal = "volume"
friction = 0.3
[[vehicles]]
name = "car"
generate = "sedan"
mass = "1450 kg"
position = [0, 0]
speed = "40 km/h"
"""
PERSON = """
[[pedestrians]]
name = "ped"
height = "1.70 m"
mass = "70 kg"
sex = "female"
pose = "walking"
position = ["2.645 m", "0.1 m"]
heading = "90 deg"
speed = "1.2 m/s"
[[pedestrians.soft_contact]]
with = "car"
stiffness = "100 kN/m"
damping_ratio = 0.4
"""


def _api_scene(pose: str, passive_moments: float = 1.0) -> cs.Scene:
    """HEAD + PERSON (with ``pose``) made through the API."""
    api = cs.Scene(ground=cs.Ground(friction=0.8), normal="volume", friction=0.3)
    car = cs.Vehicle.generate("sedan", mass=1450.0, name="car")
    api.add(car, (0, 0), heading=0.0, velocity=(cs.kmh(40), 0.0, 0.0))
    person = cs.Pedestrian(height=1.70, mass=70.0, sex="female", pose=pose, name="ped",
                           passive_moments=passive_moments)
    api.add(person, (2.645, 0.1), heading=math.pi / 2,
            velocity=(1.2 * math.cos(math.pi / 2), 1.2, 0.0))  # fmt: skip
    api.soft_contact(car, person, stiffness=1e5, damping_ratio=0.4)
    return api


def test_a_files_pedestrian_is_the_apis_bit_for_bit() -> None:
    case = loads_scene(HEAD + PERSON)
    assert case.scene.to_spec(0.05).to_json() == _api_scene("walking").to_spec(0.05).to_json()
    assert len(case.scene.vehicles) == 17 and len(case.scene.joints) == 15
    result = case.scene.run(case.run.duration, dt=case.run.dt)
    assert result.impacts == [] and result.contacts[0].vehicles[0] == "car"


def test_a_files_running_pedestrian_is_the_apis_bit_for_bit() -> None:
    case = loads_scene(HEAD + PERSON.replace('pose = "walking"', 'pose = "running"'))
    assert case.scene.to_spec(0.05).to_json() == _api_scene("running").to_spec(0.05).to_json()
    walking = loads_scene(HEAD + PERSON).scene.to_spec(0.05).to_json()
    assert case.scene.to_spec(0.05).to_json() != walking


def test_a_files_passive_moments_factor_is_the_apis() -> None:
    text = HEAD + PERSON.replace('pose = "walking"', 'pose = "walking"\npassive_moments = 0.5')
    case = loads_scene(text)
    assert case.scene.pedestrians["ped"].passive_moments == 0.5
    api = _api_scene("walking", passive_moments=0.5)
    assert case.scene.to_spec(0.05).to_json() == api.to_spec(0.05).to_json()
    assert case.scene.to_spec(0.05).to_json() != _api_scene("walking").to_spec(0.05).to_json()


def test_the_example_file_runs() -> None:
    path = Path(__file__).resolve().parents[1] / "examples" / "pedestrian-sedan-40kmh.toml"
    case = load_scene(path)
    assert {s.name.split("/")[0] for s in case.scene.vehicles[1:]} == {"pedestrian"}
    assert len(case.scene.to_spec(0.1).soft_contacts) == 16


ERRORS = [
    ("an unknown key", PERSON.replace('pose = "walking"', 'pose = "walking"\narms = 2'),
     "pedestrians[0].arms", "unknown key"),
    ("a soft contact with no such vehicle", PERSON.replace('with = "car"', 'with = "bus"'),
     "pedestrians[0].soft_contact[0].with", 'no vehicle named "bus"'),
    ("a sex not known", PERSON.replace('"female"', '"other"'), "pedestrians[0].sex",
     '"other" is not one of "male" or "female"'),
    ("a stiffness out of range (the engine's)", PERSON.replace('"100 kN/m"', '"1e9 N/m"'),
     "pedestrians[0].soft_contact[0].stiffness", "soft contact stiffness = 1000000000 N/m"),
    ("a name taken", PERSON.replace('name = "ped"', 'name = "car"'), "pedestrians[0].name",
     'a vehicle or obstacle named "car" is already in the scene'),
    ("a height out of range (the model's)", PERSON.replace('"1.70 m"', '"3 m"'),
     "pedestrians[0]", "height_m"),
    ("a passive moments factor out of range (the model's)",
     PERSON.replace('pose = "walking"', 'pose = "walking"\npassive_moments = 12'),
     "pedestrians[0]", "passive_moments = 12.0: give a factor from 0"),
    ("a passive moments factor with a unit",
     PERSON.replace('pose = "walking"', 'pose = "walking"\npassive_moments = "1 N m"'),
     "pedestrians[0].passive_moments", "expected a plain number"),
    ("a pose not known (a cyclist's is [[cyclists]]')",
     PERSON.replace('"walking"', '"cycling"'), "pedestrians[0].pose",
     '"cycling" is not one of'),
]  # fmt: skip


@pytest.mark.parametrize("what, person, key, words", ERRORS, ids=[e[0] for e in ERRORS])
def test_bad_pedestrians_are_refused_naming_the_key(
    what: str, person: str, key: str, words: str
) -> None:
    with pytest.raises(SceneFileError) as info:
        loads_scene(HEAD + person, source="case.toml")
    message = str(info.value)
    assert message.startswith(f"case.toml: {key}: "), message
    assert words in message, message


def test_a_pedestrian_needs_a_ground() -> None:
    text = (HEAD + PERSON).replace("[ground]\nfriction = 0.8\n", "")
    with pytest.raises(SceneFileError, match="pedestrians.0..name: a pedestrian needs a ground"):
        loads_scene(text, source="case.toml")
