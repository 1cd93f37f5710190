"""Tractors and trailers in scene files (issue 21, item 5; docs/scene-format.md, "Tractors,
trailers and hitches"): a file's combinations are the Scene that Scene.add(..., trailers=...,
coupling=...) builds from the same builders (the engine's value and the run the same bits),
every bad input is refused naming the file, the table and the key, and
examples/tractor-semitrailer-jackknife.toml runs through `crashsim run`."""

from __future__ import annotations

import json
import math
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
from conftest import REPO
from crashsim.cli import main
from crashsim.errors import SceneError
from crashsim.io.scenefile import SceneFileError, load_scene, loads_scene

EXAMPLE = REPO / "examples" / "tractor-semitrailer-jackknife.toml"
DEG = math.pi / 180.0  # rad, the parser's factor of "deg"
LB = 0.45359237  # kg, the parser's factor of "lb"

# Two chains, listed out of order (a trailer before the vehicle towing it): a tractor (its
# preset with some numbers replaced) towing an empty box van (a preset, with a fifth wheel
# behind it) towing a short semitrailer of explicit numbers, braked; and a generated sedan
# with a tow ball towing the caravan preset.
COMBINATIONS = """format_version = 1
[ground]
friction = 0.8

[[vehicles]]
name = "caravan"
trailer = "caravan"
towed_by = "car"

[[vehicles]]
name = "tractor"
mass = "8 t"
position = [0, 0]
speed = "20 m/s"
[vehicles.generate]
preset = "tractor"
wheelbase = "3.9 m"
driven_axles = 1
radius = ["0.5 m", "0.52 m"]
natural_frequency = "1.5 Hz"
fifth_wheel_height = "1.15 m"
steering_reference = "centre"
abs = false
[vehicles.tyre]
cornering = 6.0

[[vehicles]]
name = "semi1"
trailer = { preset = "box_van", laden = false, coupler_height = "1.15 m", cg_from_front = "6.5 m" }
weight = "20000 lb"
hitch = { at = ["-7.2 m", 0, "1.15 m"], kind = "fifth_wheel" }
towed_by = "tractor"
[vehicles.coupling]
limits = { articulation = ["-70 deg", "70 deg"], pitch = "(-15, 15) deg" }
damping = "100 N m s/rad"

[[vehicles]]
name = "semi2"
mass = "6 t"
towed_by = "semi1"
[vehicles.coupling]
limits = { articulation = "(-70, 70) deg", pitch = ["-15 deg", "15 deg"] }
damping = 100
[vehicles.trailer]
kind = "semitrailer"
length = "7 m"
width = "2.5 m"
height = "2 m"
ground_clearance = "1.15 m"
coupler = "0.3 m"
coupler_height = "1.15 m"
axles = ["5.5 m", "6.5 m"]
track = "2 m"
radius = "0.5 m"
cg_height = "1.9 m"
yaw_inertia = "40000 kg m^2"
natural_frequency = "1.4 Hz"
damping_ratio = 0.35
abs = false
load_sharing = false
[[vehicles.inputs.brake]]
time = 0
fraction = 0.2

[[vehicles]]
name = "car"
generate = { preset = "sedan" }
mass = "1542 kg"
hitch = { at = ["-2.595385 m", 0, "0.42 m"] }
position = [0, "10 m"]
speed = "20 m/s"
[[vehicles.inputs.steer]]
time = 0
angle = "2 deg"
"""


def _api() -> cs.Scene:
    """COMBINATIONS through the Python API."""
    tractor = cs.tractor(
        "tractor_6x4",
        name="tractor",
        mass=8000.0,
        wheelbase=3.9,
        driven_axles=1,
        radius=(0.5, 0.52),
        natural_frequency=1.5,
        fifth_wheel_height=1.15,
        steering_reference="centre",
        abs=False,
        tyre=cs.Tyre(cornering=6.0),
    )
    semi1 = cs.Trailer.generate(
        "box_van", laden=False, coupler_height=1.15, cg_from_front=6.5, mass=20000 * LB,
        name="semi1",
    ).with_hitch((-7.2, 0.0, 1.15), "fifth_wheel")  # fmt: skip
    semi2 = cs.Trailer.box(
        "semitrailer", length=7.0, width=2.5, height=2.0, mass=6000.0, ground_clearance=1.15,
        coupler=0.3, coupler_height=1.15, axles=[5.5, 6.5], track=2.0, radius=0.5,
        cg_height=1.9, yaw_inertia=40000.0, natural_frequency=1.4, damping_ratio=0.35,
        abs=False, load_sharing=False, name="semi2",
    )  # fmt: skip
    brake = cs.DriverInputs(brake={"all": cs.Brake("fraction", np.array([(0.0, 0.2)]))})
    coupling = {
        "limits": {"articulation": (-70 * DEG, 70 * DEG), "pitch": (-15 * DEG, 15 * DEG)},
        "damping": 100.0,
    }
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    scene.add(tractor, (0, 0), heading=0.0, velocity=(20.0, 0, 0),
              trailers=[semi1, (semi2, brake)], coupling=coupling)  # fmt: skip
    car = cs.Vehicle.generate("sedan", name="car", mass=1542.0)
    car = car.with_hitch((-2.595385, 0.0, 0.42), "ball")
    steer = cs.DriverInputs(steer=[(0.0, 2 * DEG)])
    scene.add(car, (0, 10.0), heading=0.0, velocity=(20.0, 0, 0), inputs=steer,
              trailers=[cs.Trailer.generate("caravan")])  # fmt: skip
    return scene


def _same_runs(a: cs.Result, b: cs.Result) -> None:
    assert np.array_equal(a.t, b.t)
    for name in a.vehicles:
        for field, x in a.trajectory(name)._asdict().items():
            assert np.array_equal(x, getattr(b.trajectory(name), field)), (name, field)
    assert a.joints.keys() == b.joints.keys()
    for name, record in a.joints.items():
        for field in ("angles", "force", "torque"):
            assert np.array_equal(getattr(record, field), getattr(b.joints[name], field))


def test_a_files_combinations_are_scene_adds_with_trailers_bit_for_bit() -> None:
    case = loads_scene(COMBINATIONS)
    api = _api()
    # each towed vehicle right behind the one towing it, whatever the file's order
    assert [v.name for v in case.scene.vehicles] == ["tractor", "semi1", "semi2", "car", "caravan"]
    assert [(j.name, j.kind) for j in case.scene.joints] == [
        ("tractor-semi1", "fifth_wheel"), ("semi1-semi2", "fifth_wheel"),
        ("car-caravan", "spherical"),
    ]  # fmt: skip
    # the engine's value: every body, wheel, tyre, input, joint and its options
    assert case.scene.to_spec(0.3).to_json() == api.to_spec(0.3).to_json()
    _same_runs(case.scene.run(0.3), api.run(0.3))
    tractor, semi1, semi2, car, caravan = case.scene.vehicles
    assert tractor.mass == 8000.0 and semi1.mass == 20000 * LB and semi2.mass == 6000.0
    assert semi1.hitch is not None and semi1.hitch.kind == "fifth_wheel"
    assert caravan.mass == cs.Trailer.generate("caravan").mass  # the class's, laden


def test_the_presets_by_name_take_the_classes_numbers() -> None:
    text = """format_version = 1
[ground]
[[vehicles]]
name = "tractor"
generate = "tractor"
position = [0, 0]
[[vehicles]]
name = "van"
trailer = { preset = "box_van" }
towed_by = "tractor"
[[vehicles]]
name = "car"
generate = "sedan"
mass = "1542 kg"
hitch = { at = ["-2.6 m", 0, "0.42 m"] }
position = [0, "20 m"]
[[vehicles]]
name = "caravan"
trailer = "caravan"
towed_by = "car"
"""
    case = loads_scene(text)
    api = cs.Scene(ground=cs.Ground())
    api.add(cs.Vehicle.generate("tractor"), (0, 0), heading=0.0,
            trailers=[cs.Trailer.generate("box_van", laden=True, name="van")])  # fmt: skip
    car = cs.Vehicle.generate("sedan", mass=1542.0, name="car").with_hitch((-2.6, 0, 0.42))
    api.add(car, (0, 20.0), heading=0.0, trailers=[cs.Trailer.generate("caravan")])
    assert case.scene.to_spec(1.0).to_json() == api.to_spec(1.0).to_json()
    # the empty van: its class's mass
    empty = loads_scene(text.replace('preset = "box_van"', 'preset = "box_van", laden = false'))
    assert empty.scene.vehicles[1].mass == cs.Trailer.generate("box_van", laden=False).mass


def test_the_truck_presets_by_name_are_the_apis() -> None:
    # a tractor drawing the tanker and the flatbed's empty deck; the rigid truck (its class's
    # 18 t) with a centre-axle trailer on its ball
    text = """format_version = 1
[ground]
[[vehicles]]
name = "tractor"
generate = "tractor"
position = [0, 0]
[[vehicles]]
name = "tanker"
trailer = "tanker"
towed_by = "tractor"
[[vehicles]]
name = "tractor2"
generate = "tractor"
position = [0, "30 m"]
[[vehicles]]
name = "flatbed"
trailer = { preset = "flatbed", laden = false }
towed_by = "tractor2"
[[vehicles]]
name = "truck"
generate = { preset = "rigid_truck", length = "9 m" }
position = [0, "60 m"]
"""
    case = loads_scene(text)
    api = cs.Scene(ground=cs.Ground())
    api.add(cs.Vehicle.generate("tractor"), (0, 0), heading=0.0,
            trailers=[cs.Trailer.generate("tanker")])  # fmt: skip
    api.add(cs.Vehicle.generate("tractor", name="tractor2"), (0, 30.0), heading=0.0,
            trailers=[cs.Trailer.generate("flatbed", laden=False)])  # fmt: skip
    api.add(cs.Vehicle.generate("rigid_truck", length=9.0, name="truck"), (0, 60.0), heading=0.0)
    assert case.scene.to_spec(1.0).to_json() == api.to_spec(1.0).to_json()


# -- refusals ----------------------------------------------------------------------------------

HEAD = "format_version = 1\n[ground]\n"
TRACTOR = """
[[vehicles]]
name = "tractor"
generate = "tractor"
position = [0, 0]
speed = "20 m/s"
"""
SEMI = """
[[vehicles]]
name = "semi"
trailer = "box_van"
towed_by = "tractor"
"""
PAIR = HEAD + TRACTOR + SEMI
FIFTH_WHEEL = 'hitch = { at = ["-7 m", 0, "1.1 m"], kind = "fifth_wheel" }\n'
SEMI2 = '\n[[vehicles]]\nname = "semi2"\ntrailer = "box_van"\ntowed_by = "semi"\n'
SEMIS_RING = (
    '\n[[vehicles]]\nname = "semi2"\ntrailer = "box_van"\ntowed_by = "semi3"\n' + FIFTH_WHEEL
    + '\n[[vehicles]]\nname = "semi3"\ntrailer = "box_van"\ntowed_by = "semi2"\n' + FIFTH_WHEEL
)  # fmt: skip
CAR = """
[[vehicles]]
name = "car"
generate = "sedan"
mass = "1500 kg"
position = [0, "20 m"]
"""
BALL = 'hitch = { at = ["-2.595 m", 0, "0.42 m"] }\n'
CARAVAN = """
[[vehicles]]
name = "caravan"
trailer = "caravan"
towed_by = "car"
"""
EXPLICIT = ('trailer = { kind = "semitrailer", length = "7 m", width = "2.5 m", height = "2 m", '
            'ground_clearance = "1.1 m", coupler = "0.3 m", coupler_height = "1.1 m", '
            'axles = ["6 m"], track = "2 m", radius = "0.5 m" }')  # fmt: skip
BOX_VAN = 'trailer = "box_van"'
TOWED_BY = 'towed_by = "tractor"'


def _explicit(old: str = "", new: str = "") -> str:
    """PAIR with the semitrailer of explicit numbers (EXPLICIT, old replaced by new)."""
    return PAIR.replace(BOX_VAN, EXPLICIT.replace(old, new)) + 'mass = "5 t"\n'


ERRORS = [
    # (what, text, key path, words of the message)
    ("a position on a towed vehicle", PAIR + 'position = ["-8 m", 0]\n', "vehicles[1].position",
     'a towed vehicle starts where "tractor" (towed_by) puts it, moving with it: drop this key'),
    ("a speed on a towed vehicle", PAIR + 'speed = "20 m/s"\n', "vehicles[1].speed",
     'a towed vehicle starts where "tractor" (towed_by) puts it'),
    ("a yaw rate on a towed vehicle", PAIR + 'yaw_rate = "2 deg/s"\n', "vehicles[1].yaw_rate",
     "a towed vehicle starts where"),
    ("an unknown tower", PAIR.replace(TOWED_BY, 'towed_by = "tracktor"'), "vehicles[1].towed_by",
     'no vehicle named "tracktor" (the vehicles: tractor, semi)'),
    ("an obstacle as tower", PAIR.replace(TOWED_BY, 'towed_by = "post"')
     + '\n[[obstacles]]\nname = "post"\npole = { diameter = "0.3 m", height = "3 m" }\n'
     'position = ["20 m", "5 m"]\n', "vehicles[1].towed_by",
     '"post" is a fixed obstacle, which tows nothing'),
    ("a vehicle towing itself", PAIR.replace(TOWED_BY, 'towed_by = "semi"'),
     "vehicles[1].towed_by", "a vehicle cannot tow itself"),
    ("a cycle", PAIR + SEMIS_RING, "vehicles[2].towed_by",
     'the vehicles tow each other in a ring ("semi2" towed by "semi3" towed by "semi2"): a '
     "chain of trailers starts at a vehicle that is not towed"),
    ("two trailers on one hitch", PAIR + SEMI2.replace('"semi"', '"tractor"'),
     "vehicles[2].towed_by",
     '"tractor" already tows "semi" (one trailer on a hitch): hang this one behind it, '
     'towed_by = "semi"'),
    ("towed_by not a string", PAIR.replace(TOWED_BY, "towed_by = 1"), "vehicles[1].towed_by",
     "expected a string"),
    ("a kingpin on a ball", HEAD + CAR + BALL + SEMI.replace(TOWED_BY, 'towed_by = "car"'),
     "vehicles[1].towed_by",
     "'car' towing 'semi': a kingpin does not go on a ball (a kingpin goes on a fifth wheel, a "
     "drawbar's coupler on a ball)"),
    ("a tower without a hitch", HEAD + CAR + CARAVAN, "vehicles[1].towed_by",
     "'car' towing 'caravan': 'car' has no hitch (vehicle.with_hitch)"),
    ("a towed vehicle that is no trailer", PAIR.replace(BOX_VAN, 'box = { length = "4 m", '
     'width = "2 m", height = "1.5 m" }\nmass = "1 t"'), "vehicles[1].towed_by",
     "'tractor' towing 'semi': 'semi' has no coupler (build it with Trailer)"),
    ("a trailer not towed", PAIR.replace(TOWED_BY, ""), "vehicles[1].towed_by",
     'a trailer rests on the vehicle towing it: give its name, towed_by = "<the tractor or car>"'),
    ("towing without a ground", PAIR.replace("[ground]\n", ""), "vehicles[1].towed_by",
     "towing needs a ground: add a [ground] table"),
    ("an unknown trailer preset", PAIR.replace('"box_van"', '"lowboy"'), "vehicles[1].trailer",
     '"lowboy" is not one of "box_van", "flatbed", "tanker" or "caravan"'),
    ("an unknown trailer preset in a table", PAIR.replace(BOX_VAN,
     'trailer = { preset = "drawbar_trailer" }'), "vehicles[1].trailer.preset",
     '"drawbar_trailer" is not one of "box_van", "flatbed", "tanker" or "caravan"'),
    ("a trailer that is a number", PAIR.replace(BOX_VAN, "trailer = 5"), "vehicles[1].trailer",
     'expected a preset\'s name such as "box_van" or a table { preset = "box_van", ... }, got 5'),
    ("an unknown tractor preset", PAIR.replace('generate = "tractor"',
     'generate = "tractor_4x2"'), "vehicles[0].generate", '"tractor_4x2" is not one of "sedan"'),
    ("a trailer neither preset nor kind", PAIR.replace(BOX_VAN, 'trailer = { length = "13 m" }'),
     "vehicles[1].trailer",
     'give preset (a class\'s trailer: "box_van", "flatbed", "tanker" or "caravan") or kind '
     '("semitrailer", "centre_axle" or "drawbar_body": every dimension given)'),
    ("a trailer both preset and kind", PAIR.replace(BOX_VAN,
     'trailer = { preset = "box_van", kind = "semitrailer" }'), "vehicles[1].trailer.kind",
     "give preset (a class's trailer) or kind (every dimension), not both"),
    ("an unknown trailer kind", _explicit('"semitrailer"', '"dolly"'), "vehicles[1].trailer.kind",
     '"dolly" is not one of "semitrailer", "centre_axle" or "drawbar_body"'),
    ("an explicit trailer without its mass", PAIR.replace(BOX_VAN, EXPLICIT), "vehicles[1].mass",
     "this key is required and missing"),
    ("an explicit trailer without its axles", _explicit('axles = ["6 m"], '),
     "vehicles[1].trailer.axles", "this key is required and missing"),
    ("no axle", _explicit('["6 m"]', "[]"), "vehicles[1].trailer.axles",
     "expected a list of each axle's distance behind the body's front"),
    ("an axle in mph", _explicit('"6 m"', '"6 mph"'), "vehicles[1].trailer.axles[0]",
     '"6 mph" is a speed, not a length'),
    ("a negative axle", _explicit('"6 m"', '"-6 m"'), "vehicles[1].trailer.axles[0]",
     "-6 m must be positive (behind the front)"),
    ("a length in kg", _explicit('length = "7 m"', 'length = "7 kg"'),
     "vehicles[1].trailer.length", '"7 kg" is a mass, not a length'),
    ("laden with a kind", _explicit("{ ", "{ laden = true, "), "vehicles[1].trailer.laden",
     "laden is for a preset: give this trailer's mass"),
    ("a misspelt trailer key", PAIR.replace(BOX_VAN,
     'trailer = { preset = "box_van", lenght = "12 m" }'), "vehicles[1].trailer.lenght",
     'did you mean "length"'),
    ("a kingpin beyond the body (Trailer.box's)", _explicit('coupler = "0.3 m"',
     'coupler = "8 m"'), "vehicles[1].trailer",
     "coupler = 8.0 m: a semitrailer's kingpin lies behind the body's front and ahead of its "
     "rear (0 to 7.0 m)"),
    ("a sedan's body key on a tractor", PAIR.replace('generate = "tractor"',
     'generate = { preset = "tractor", hood_height = "1 m" }'),
     "vehicles[0].generate.hood_height", "unknown key"),
    ("three driven axles", PAIR.replace('generate = "tractor"',
     'generate = { preset = "tractor", driven_axles = 3 }'), "vehicles[0].generate.driven_axles",
     "expected 1 (a 4x2) or 2 (a 6x4), got 3"),
    ("a tractor's radius of three", PAIR.replace('generate = "tractor"',
     'generate = { preset = "tractor", radius = [0.5, 0.5, 0.5] }'),
     "vehicles[0].generate.radius", "expected 2 components, got 3"),
    ("wheels on a tractor", PAIR.replace('speed = "20 m/s"\n',
     'speed = "20 m/s"\n[vehicles.wheels]\ntrack = "2 m"\n'), "vehicles[0].wheels",
     "a tractor's wheels come from its builder: give their track, radius and springs in its "
     "generate table"),
    ("stiffness on a trailer", PAIR + 'stiffness = "van"\n', "vehicles[1].stiffness",
     "a trailer has no crush stiffness in scene files yet"),
    ("cg_height on a trailer", PAIR + 'cg_height = "2 m"\n', "vehicles[1].cg_height",
     "a trailer's CG, inertia and axles come from its builder: give them in its trailer table"),
    ("a hitch of an unknown kind", HEAD + CAR + BALL.replace('"] }', '"], kind = "hook" }')
     + CARAVAN, "vehicles[0].hitch.kind",
     '"hook" is not one of "ball", "fifth_wheel" or "turntable"'),
    ("a trailer's kind of hitch", HEAD + CAR + BALL.replace('"] }', '"], kind = "kingpin" }')
     + CARAVAN, "vehicles[0].hitch.kind",
     '"kingpin" is not one of "ball", "fifth_wheel" or "turntable"'),
    ("a hitch far off the body", HEAD + CAR + 'hitch = { at = ["-5 m", 0, "0.42 m"] }\n'
     + CARAVAN, "vehicles[0].hitch.at",
     "vehicle 'car': its hitch lies 2.55 m outside the body's box (at most 1 m)"),
    ("a hitch in 2-D", HEAD + CAR + 'hitch = { at = ["-2.6 m", 0] }\n', "vehicles[0].hitch.at",
     "expected 3 components, got 2"),
    ("a coupling on a tower", PAIR.replace('speed = "20 m/s"\n', 'speed = "20 m/s"\ncoupling = '
     "{ collide = true }\n"), "vehicles[0].coupling",
     "this is a towed vehicle's joint (with towed_by): give it the trailer"),
    ("a limit on a ball (the engine's)", HEAD + CAR + BALL + CARAVAN
     + 'coupling = { limits = { articulation = ["-80 deg", "80 deg"] } }\n',
     "vehicles[1].coupling.limits.articulation",
     'a spherical joint has no angle "articulation" to limit'),
    ("a negative coupling stiffness (the engine's)", PAIR + "coupling = { stiffness = -5 }\n",
     "vehicles[1].coupling.stiffness",
     "the joint's stiffness = -5 N m/rad is invalid: it must lie in [0, 1e9] N m/rad"),
    ("a misspelt coupling key", PAIR + "coupling = { colide = true }\n",
     "vehicles[1].coupling.colide", 'did you mean "collide"'),
    ("a towed vehicle's input on a wheel it lacks", PAIR + "[[vehicles.inputs.wheel_states]]\n"
     'wheel = "FL"\nstate = "locked"\ntime = "1 s"\n', "vehicles[1]", "vehicle 'semi' inputs"),
    ("a trailer heavier than 10 towers (Scene.add's)", PAIR + 'mass = "120 t"\n', "vehicles[0]",
     "trailer 'semi' (120000 kg) is more than 10 times as heavy as 'tractor' (9875 kg)"),
]  # fmt: skip


def test_each_joint_of_a_chain_takes_its_own_coupling() -> None:
    # A B-double: the first semitrailer's kingpin damped 10 N m s/rad, the second's 20 with an
    # articulation limit; the file's chain is Scene.add with one coupling per trailer.
    text = (
        PAIR + FIFTH_WHEEL + "coupling = { damping = 10 }\n" + SEMI2
        + 'coupling = { damping = 20, limits = { articulation = ["-60 deg", "60 deg"] } }\n'
    )  # fmt: skip
    case = loads_scene(text)
    first, second = case.scene.joints
    assert first.core.resistance == (0.0, 10.0, 0.0) and first.core.limits == []
    assert second.core.resistance == (0.0, 20.0, 0.0)
    assert second.core.limits == [("articulation", -math.radians(60), math.radians(60))]
    tractor, semi, semi2 = case.scene.vehicles
    api = cs.Scene(ground=cs.Ground())
    couplings = [
        {"damping": 10.0},
        {"damping": 20.0, "limits": {"articulation": (-math.radians(60), math.radians(60))}},
    ]
    api.add(tractor, (0, 0), heading=0.0, velocity=(20.0, 0, 0), trailers=[semi, semi2],
            coupling=couplings)  # fmt: skip
    assert case.scene.to_spec(0.5).to_json() == api.to_spec(0.5).to_json()
    with pytest.raises(SceneError, match="coupling has 1 entries for 2 trailer"):
        cs.Scene(ground=cs.Ground()).add(
            tractor, (0, 0), trailers=[semi, semi2], coupling=[{"damping": 1.0}]
        )


@pytest.mark.parametrize("what, text, key, words", ERRORS, ids=[e[0] for e in ERRORS])
def test_bad_combinations_are_refused_naming_the_file_table_and_key(
    what: str, text: str, key: str, words: str, tmp_path: Path
) -> None:
    path = tmp_path / "case.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(SceneFileError) as info:
        load_scene(path)
    e = info.value
    message = str(e)
    assert "\n" not in message
    assert e.file == str(path) and e.key == key, message
    assert message.startswith(f"{path}: {key}: "), message
    assert words in message, message


# -- the example -------------------------------------------------------------------------------


def test_the_jackknife_example_is_the_presets_on_the_curve_and_runs(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    case = load_scene(EXAMPLE)
    # the same scene through the API: the presets, the curve's 49 points (every 0.025 rad of
    # a 250 m radius, as the file gives them to 1 mm), the tandem locked at 1 s
    tractor = cs.Vehicle.generate("tractor")
    arc = 0.025 * np.arange(49)
    path = np.round(np.c_[250.0 * np.sin(arc), 250.0 * (1.0 - np.cos(arc))], 3)
    locks = [(f"drive{k}_{side}", "locked", 1.0) for k in (1, 2) for side in ("left", "right")]
    api = cs.Scene(ground=cs.Ground(friction=0.35))
    api.add(tractor, (0, 0), heading=0.0, velocity=(80 / 3.6, 0, 0),
            inputs=cs.DriverInputs(path=path, wheel_states=locks),
            trailers=[cs.Trailer.generate("box_van", name="semitrailer")],
            coupling={"collide": True})  # fmt: skip
    assert case.scene.to_spec(8.0).to_json() == api.to_spec(8.0).to_json()
    assert (case.run.duration, case.run.dt, case.scene.ground.friction) == (8.0, 1e-3, 0.35)
    # 3 s of it through the command: the trailer's front strikes the cab (a jackknife)
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLE), "--out", str(out), "--duration", "3 s"]) == 0
    assert "  tractor-semitrailer: fifth_wheel, tractor - semitrailer; largest force " in (
        capsys.readouterr().out
    )
    assert {"report.json", "time-histories.csv", "trajectories.png", "motion.glb"} <= {
        p.name for p in out.iterdir()
    }
    d = json.loads((out / "report.json").read_text(encoding="utf-8"))
    assert d["impacts"] and all(i["vehicles"] == ["tractor", "semitrailer"] for i in d["impacts"])
    (joint,) = d["joints"]
    articulation = joint["angle_min"][joint["angle_names"].index("articulation")]
    assert articulation < -20 * DEG  # the tractor turned against the trailer
