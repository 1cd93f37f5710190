"""Joints in scene files (issue 21, item 5; docs/scene-format.md "[[joints]]"): the file's
joints are Scene.join's (the same engine values, the same run bits), every bad input is
refused naming the file, the joint's table and the key, the units of a joint's resistance,
the report's joints (JSON against the schema, the text) and examples/towed-car.toml run by
`crashsim run` and `crashsim check`."""

from __future__ import annotations

import json
import math
from pathlib import Path

import crashsim as cs
import jsonschema
import numpy as np
import pytest
from conftest import REPO
from crashsim.analysis.report import build_report, report_schema
from crashsim.cli import main
from crashsim.io.scenefile import SceneFileError, load_scene, loads_scene, parse_quantity

EXAMPLE = REPO / "examples" / "towed-car.toml"
DEG = math.pi / 180.0  # rad, the parser's factor of "deg"
LBF_FT = 0.45359237 * 9.80665 * 0.3048  # N m, the parser's factor of "lbf ft"

# Two generated sedans at 15 m/s, the front one braking, the second 0.6 m behind it (the
# generated sedan's rear bumper is 2.781 m behind its CG, its front 2.110 m ahead).
TOW = """format_version = 1
[ground]
friction = 0.8

[[vehicles]]
name = "car"
generate = { preset = "sedan" }
mass = "1542 kg"
position = [0, 0]
speed = "15 m/s"
[[vehicles.inputs.brake]]
time = 0
fraction = 0.3

[[vehicles]]
name = "towed"
generate = { preset = "sedan" }
mass = "1542 kg"
position = ["-5.491 m", 0]
speed = "15 m/s"
"""
JOINT = """
[[joints]]
vehicles = ["car", "towed"]
at = ["-3.081 m", 0, "0.5 m"]
"""


def _tow_api() -> cs.Scene:
    """TOW through the Python API."""
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    brake = cs.DriverInputs(brake={"all": cs.Brake("fraction", np.array([(0.0, 0.3)]))})
    for name, x, inputs in (("car", 0.0, brake), ("towed", -5.491, None)):
        car = cs.Vehicle.generate("sedan", name=name, mass=1542.0)
        scene.add(car, (x, 0.0), heading=0.0, velocity=(15.0, 0.0, 0.0), inputs=inputs)
    return scene


def _same_joints(a: cs.Scene, b: cs.Scene) -> None:
    assert [j.name for j in a.joints] == [j.name for j in b.joints]
    for x, y in zip(a.joints, b.joints, strict=True):
        assert x.vehicles == y.vehicles and x.core == y.core
        assert np.array_equal(x.at, y.at) and np.array_equal(x.axes, y.axes)


def _same_runs(a: cs.Result, b: cs.Result) -> None:
    assert np.array_equal(a.t, b.t)
    for name in a.vehicles:
        for field, x in a.trajectory(name)._asdict().items():
            assert np.array_equal(x, getattr(b.trajectory(name), field)), (name, field)
    assert a.joints.keys() == b.joints.keys()
    for name, record in a.joints.items():
        for field in ("angles", "force", "torque"):
            assert np.array_equal(getattr(record, field), getattr(b.joints[name], field))
    assert a.joint_events == b.joint_events


def test_a_files_fifth_wheel_is_scene_joins_and_runs_the_same_bits() -> None:
    text = TOW + JOINT + """kind = "fifth_wheel"
axes = [1, 0, 0, 0]
limits = { articulation = ["-80 deg", "80 deg"], pitch = "(-10, 10) deg" }
stiffness = "100 N m/deg"
damping = "50 N m s/rad"
friction = "20 lbf ft"
name = "hitch"
"""
    case = loads_scene(text)
    api = _tow_api().join(
        "car",
        "towed",
        at=(-3.081, 0.0, 0.5),
        kind="fifth_wheel",
        axes=(1.0, 0.0, 0.0, 0.0),
        limits={"articulation": (-80.0 * DEG, 80.0 * DEG), "pitch": (-10.0 * DEG, 10.0 * DEG)},
        stiffness=100.0 / DEG,
        damping=50.0,
        friction=20.0 * LBF_FT,
        name="hitch",
    )
    _same_joints(case.scene, api)
    joint = case.scene.joints[0]
    assert joint.core.resistance == (100.0 / DEG, 50.0, 20.0 * LBF_FT)
    assert not joint.core.collide and joint.vehicles == ("car", "towed")
    _same_runs(case.scene.run(0.5), api.run(0.5))


def test_the_defaults_are_scene_joins() -> None:
    case = loads_scene(TOW + JOINT)
    api = _tow_api().join("car", "towed", at=(-3.081, 0.0, 0.5))
    _same_joints(case.scene, api)
    joint = case.scene.joints[0]
    assert joint.name == "car-towed" and joint.kind == "spherical"
    assert joint.core.resistance == (0.0, 0.0, 0.0) and joint.core.limits == []
    # the axes: the first vehicle's orientation at t = 0 (heading 0)
    assert np.array_equal(joint.axes, [1.0, 0.0, 0.0, 0.0])


HIGH = 30.0  # m, the pivot's height: the ground far below
ANGLE = 30.0 * DEG  # the rod's start, from the vertical
TILT = (math.cos((math.pi / 2 - ANGLE) / 2), 0.0, math.sin((math.pi / 2 - ANGLE) / 2), 0.0)
ROD = f"""format_version = 1
[ground]

[[vehicles]]
name = "rod"
box = {{ length = "1 m", width = "5 cm", height = "5 cm" }}
mass = "5 kg"
position = [{0.5 * math.sin(ANGLE)!r}, 0, {HIGH - 0.5 * math.cos(ANGLE)!r}]
orientation = [{TILT[0]!r}, 0, {TILT[2]!r}, 0]   # the rod's body x down the rod

[[joints]]
vehicles = ["rod"]
kind = "revolute"
at = [0, 0, {HIGH!r}]
axes = [[1, 0, 0], [0, 0, 1], [0, -1, 0]]   # the hinge's z axis along world y
limits = {{ angle = "(-10, 10) deg" }}
"""


def _rod_api() -> tuple[cs.Scene, np.ndarray]:
    """ROD's scene through the API, without its joint, and the joint's axes as a matrix."""
    api = cs.Scene(ground=cs.Ground())
    api.add(
        cs.Vehicle.box(1.0, 0.05, 0.05, mass=5.0, name="rod"),
        (0.5 * math.sin(ANGLE), 0.0, HIGH - 0.5 * math.cos(ANGLE)),
        orientation=TILT,
    )
    return api, np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])


def test_a_pendulum_on_the_world_with_axes_as_a_matrix_and_its_limit_in_the_report() -> None:
    case = loads_scene(ROD)
    api, matrix = _rod_api()
    api.join("rod", at=(0.0, 0.0, HIGH), kind="revolute", axes=matrix,
             limits={"angle": (-10.0 * DEG, 10.0 * DEG)})  # fmt: skip
    _same_joints(case.scene, api)
    joint = case.scene.joints[0]
    assert joint.name == "rod-world" and joint.vehicles == ("rod", None)
    # the matrix's columns are the joint's axes: a quarter turn about world x (z to world y)
    half = -math.pi / 4
    assert np.allclose(joint.axes, [math.cos(half), math.sin(half), 0, 0], rtol=0, atol=1e-15)
    result = case.scene.run(0.6)
    _same_runs(result, api.run(0.6))
    assert result.joint_events and result.joint_events[0].angle == "angle"
    # the report: the joint as made, over the run, its limit hit (JSON and text)
    report = build_report(result)
    d = report.to_dict()
    jsonschema.Draft202012Validator(report_schema()).validate(d)
    (made,) = d["scene"]["joints"]
    assert made == {**joint.to_dict(), "stiffness": 0.0, "damping": 0.0, "friction": 0.0,
                    "collide": False}  # fmt: skip
    assert made["vehicles"] == ["rod", None] and made["limits"] == {"angle": [-10 * DEG, 10 * DEG]}
    record = result.joints["rod-world"]
    (run,) = d["joints"]
    force = np.linalg.norm(record.force, axis=1)
    assert run["max_force"] == force.max() and run["max_force_time"] == record.t[force.argmax()]
    assert run["angle_names"] == ["angle"]
    assert run["angle_min"] == record.angles.min(axis=0).tolist()
    assert run["angle_max"] == record.angles.max(axis=0).tolist()
    assert d["joint_events"] == [e.to_dict() for e in result.joint_events]
    text = report.summary_table()
    first = result.joint_events[0]
    assert "  rod-world: revolute, rod - the world; largest force " in text
    assert f"    limit of angle hit at {first.time:.3f} s (" in text


def test_a_files_passive_moment_is_scene_joins_and_runs_the_same_bits() -> None:
    # [joints.passive.<angle>]: terms of [torque, per angle, angle], constant, offset
    text = ROD.replace('limits = {{ angle = "(-10, 10) deg" }}'.replace("{{", "{").replace(
        "}}", "}"), "") + """
[joints.passive.angle]
terms = [["5 N m", "-3 1/rad", "0.2 rad"], [-0.5, 2, "5.729577951308232 deg"]]
constant = "-1 N m"
offset = "0.2 rad"
"""
    case = loads_scene(text)
    api, matrix = _rod_api()
    law = cs.PassiveMoment(terms=((5.0, -3.0, 0.2), (-0.5, 2.0, 0.1)), constant=-1.0, offset=0.2)
    api.join("rod", at=(0.0, 0.0, HIGH), kind="revolute", axes=matrix, passive={"angle": law})
    (joint,) = case.scene.joints
    assert joint.passive["angle"].terms[0] == (5.0, -3.0, 0.2)
    assert joint.passive["angle"].terms[1] == pytest.approx((-0.5, 2.0, 0.1), rel=1e-15)
    api._joints = []  # the file's centre in degrees: the API's built from the file's numbers
    api.join("rod", at=(0.0, 0.0, HIGH), kind="revolute", axes=matrix,
             passive={"angle": joint.passive["angle"]})  # fmt: skip
    _same_joints(case.scene, api)
    _same_runs(case.scene.run(0.3), api.run(0.3))


def test_a_files_coupled_angle_is_the_apis() -> None:
    # a term's fourth item: [[joint, angle, rate, offset]], with units
    text = ROD + """
[joints.passive.angle]
terms = [["5 N m", "-3 1/rad", "0.2 rad", [["rod-world", "angle", "0.01 1/deg", "10 deg"]]]]
"""
    (joint,) = loads_scene(text).scene.joints
    ((_, _, _, (c,)),) = joint.passive["angle"].terms
    assert (c.joint, c.angle) == ("rod-world", "angle")
    assert c.rate == pytest.approx(0.01 / DEG, rel=1e-15)
    assert c.offset == pytest.approx(10 * DEG, rel=1e-15)
    assert joint.core.coupled == [("angle", 0, "rod-world", "angle", c.offset, c.rate)]


PASSIVE_ERRORS = [
    ("an unknown key", 'rate = 3\n', "joints[0].passive.angle.rate", "unknown key"),
    ("terms not a list", 'terms = 5\n', "joints[0].passive.angle.terms", "expected a list"),
    ("a term of two", 'terms = [[1, 2]]\n', "joints[0].passive.angle.terms[0]",
     "expected [scale, rate, centre]"),
    ("a scale in metres", 'terms = [["1 m", 2, 0]]\n', "joints[0].passive.angle.terms[0].scale",
     '"1 m" is a length, not a torque'),
    ("a rate too steep (the engine's)", 'terms = [[1, "1000 1/rad", 0]]\n',
     "joints[0].passive.angle", "rate = 1000 1/rad is invalid"),
    ("a coupled angle not a list", 'terms = [[1, 2, 0, 5]]\n',
     "joints[0].passive.angle.terms[0][3]", "expected a list of [joint, angle, rate, offset]"),
    ("a coupled angle without names", 'terms = [[1, 2, 0, [[1, 2, 3]]]]\n',
     "joints[0].passive.angle.terms[0][3][0]", "expected [joint name, angle name"),
    ("a coupled rate in metres", 'terms = [[1, 2, 0, [["a", "b", "1 m"]]]]\n',
     "joints[0].passive.angle.terms[0][3][0].rate", '"1 m" is a length'),
]  # fmt: skip


@pytest.mark.parametrize("what, line, key, words", PASSIVE_ERRORS,
                         ids=[e[0] for e in PASSIVE_ERRORS])  # fmt: skip
def test_bad_passive_moments_are_refused_naming_the_key(
    what: str, line: str, key: str, words: str, tmp_path: Path
) -> None:
    path = tmp_path / "case.toml"
    path.write_text(ROD + "\n[joints.passive.angle]\n" + line, encoding="utf-8")
    with pytest.raises(SceneFileError) as info:
        load_scene(path)
    assert info.value.key == key and words in str(info.value), str(info.value)
    path.write_text(ROD + "\n[joints.passive.pitch]\nconstant = 1\n", encoding="utf-8")
    with pytest.raises(SceneFileError, match='no angle "pitch" for a passive moment'):
        load_scene(path)


def test_joint_units_and_their_spellings() -> None:
    cases = {
        ("600 N m/deg", "rotational stiffness"): 600.0 / DEG,
        ("2 kN m/rad", "rotational stiffness"): 2000.0,
        ("50 Nms/rad", "rotational damping"): 50.0,
        ("50 N*m*s/rad", "rotational damping"): 50.0,
        ("5 N m s/deg", "rotational damping"): 5.0 / DEG,
        ("3 kN m s/rad", "rotational damping"): 3000.0,
        ("20 Nm", "torque"): 20.0,
        ("20 N·m", "torque"): 20.0,
        ("2 kNm", "torque"): 2000.0,
        ("10 ft lbf", "torque"): 10.0 * LBF_FT,
        ("10 lbf ft", "torque"): 10.0 * LBF_FT,
    }
    for (text, dim), want in cases.items():
        assert parse_quantity(text, dim) == pytest.approx(want, rel=2.3e-16, abs=0.0), text
    with pytest.raises(cs.ParameterError, match='"20 N m" is a torque, not a rotational stiffness'):
        parse_quantity("20 N m", "rotational stiffness")


# -- refusals ----------------------------------------------------------------------------------

GOOD = TOW + JOINT
POST = '\n[[obstacles]]\nname = "post"\npole = { diameter = "0.3 m", height = "3 m" }\n' \
       'position = ["20 m", "5 m"]\n'  # fmt: skip
VEHICLES = 'vehicles = ["car", "towed"]'
AT = 'at = ["-3.081 m", 0, "0.5 m"]'

ERRORS = [
    # (what, text, key path, words of the message)
    ("an unknown key", GOOD + 'kindd = "revolute"\n', "joints[0].kindd", 'did you mean "kind"'),
    ("joints not tables", "format_version = 1\njoints = 5\n" + TOW[len("format_version = 1\n"):],
     "joints", "expected an array of tables"),
    ("vehicles missing", GOOD.replace(VEHICLES, ""), "joints[0].vehicles", "required"),
    ("vehicles a string", GOOD.replace(VEHICLES, 'vehicles = "car"'), "joints[0].vehicles",
     "expected one or two vehicle names"),
    ("three vehicles", GOOD.replace(VEHICLES, 'vehicles = ["car", "towed", "car"]'),
     "joints[0].vehicles", "expected one or two vehicle names"),
    ("an unknown vehicle", GOOD.replace(VEHICLES, 'vehicles = ["car", "trailer"]'),
     "joints[0].vehicles[1]", 'no vehicle named "trailer" (the vehicles: car, towed)'),
    ("an obstacle", GOOD.replace(VEHICLES, 'vehicles = ["car", "post"]') + POST,
     "joints[0].vehicles[1]", '"post" is a fixed obstacle, which cannot be joined'),
    ("a vehicle twice", GOOD.replace(VEHICLES, 'vehicles = ["car", "car"]'), "joints[0].vehicles",
     "a joint needs two different vehicles"),
    ("at missing", GOOD.replace(AT, ""), "joints[0].at", "required"),
    ("at in mph", GOOD.replace('"0.5 m"]', '"0.5 mph"]'), "joints[0].at[2]",
     '"0.5 mph" is a speed, not a length'),
    ("at in 2-D", GOOD.replace(', "0.5 m"]', "]"), "joints[0].at", "expected 3 components, got 2"),
    ("a kind not a string", GOOD + "kind = 3\n", "joints[0].kind", "expected a string"),
    ("an unknown kind (the engine's)", GOOD + 'kind = "weld"\n', "joints[0].kind",
     'joint kind "weld" is unknown: give spherical (ball), revolute (hinge), fixed or fifth_wheel'),
    ("collide not a boolean", GOOD + 'collide = "yes"\n', "joints[0].collide",
     "expected true or false"),
    ("a torque as a stiffness", GOOD + 'stiffness = "5 N m"\n', "joints[0].stiffness",
     '"5 N m" is a torque, not a rotational stiffness'),
    ("a stiffness as a damping", GOOD + 'damping = "5 N m/rad"\n', "joints[0].damping",
     '"5 N m/rad" is a rotational stiffness, not a rotational damping'),
    ("a force as a friction", GOOD + 'friction = "20 N"\n', "joints[0].friction",
     '"20 N" is a force, not a torque'),
    ("an unknown unit", GOOD + 'friction = "20 N ft"\n', "joints[0].friction",
     'unknown unit "N ft"'),
    ("a negative stiffness (the engine's)", GOOD + "stiffness = -5\n", "joints[0].stiffness",
     "the joint's stiffness = -5 N m/rad is invalid: it must lie in [0, 1e9] N m/rad"),
    ("a negative damping (the engine's)", GOOD + 'damping = "-1 N m s/rad"\n',
     "joints[0].damping", "it must lie in [0, 1e8] N m s/rad"),
    ("a negative friction (the engine's)", GOOD + 'friction = "-1 N m"\n', "joints[0].friction",
     "it must lie in [0, 1e6] N m"),
    ("limits not a table", GOOD + "limits = 5\n", "joints[0].limits", "expected a table"),
    ("a limit in metres", GOOD + 'kind = "fifth_wheel"\nlimits = { articulation = '
     '["-80 m", "80 deg"] }\n', "joints[0].limits.articulation[0]", '"-80 m" is a length'),
    ("one bound", GOOD + 'kind = "revolute"\nlimits = { angle = ["10 deg"] }\n',
     "joints[0].limits.angle", "expected 2 components, got 1"),
    ("a limit out of range (the engine's)", GOOD + 'kind = "fifth_wheel"\nlimits = { '
     'articulation = ["-200 deg", "80 deg"] }\n', "joints[0].limits.articulation",
     "the joint's articulation limit [-200.00, 80.00] deg is invalid: the lower limit must lie "
     "in [-180, 0] deg"),
    ("a limit the kind lacks (the engine's)", GOOD + 'kind = "revolute"\nlimits = { pitch = '
     '"(-10, 10) deg" }\n', "joints[0].limits.pitch", 'a revolute joint has no angle "pitch"'),
    ("a limit on a ball (the engine's)", GOOD + 'limits = { angle = "(-10, 10) deg" }\n',
     "joints[0].limits.angle", 'a spherical joint has no angle "angle" to limit'),
    ("axes of 3", GOOD + "axes = [1, 0, 0]\n", "joints[0].axes", "expected 4 components, got 3"),
    ("zero axes (the engine's)", GOOD + "axes = [0, 0, 0, 0]\n", "joints[0]",
     "joint 'car-towed': axes: orientation must be a finite, non-zero quaternion"),
    ("axes not a rotation", GOOD + "axes = [[1, 0, 0], [0, 2, 0], [0, 0, 1]]\n", "joints[0]",
     "axes: the orientation matrix is not orthonormal"),
    ("a name with a newline", GOOD + 'name = "bar\\n"\n', "joints[0].name", "U+000A"),
    ("a pair joined twice", GOOD + JOINT.replace(VEHICLES, 'vehicles = ["towed", "car"]'),
     "joints[1]", "'towed' and 'car' are already joined by 'car-towed': one joint per pair"),
    ("a name twice", GOOD + 'name = "bar"\n' + JOINT.replace(VEHICLES, 'vehicles = ["towed"]')
     + 'name = "bar"\n', "joints[1]", "the scene already has a joint named 'bar'"),
    ("no ground", GOOD.replace("[ground]\nfriction = 0.8\n", ""), "joints[0]",
     "a joint needs a ground: add a [ground] table"),
    ("contact parameters of a joined pair", GOOD + '\n[[pairs]]\nvehicles = ["towed", "car"]\n'
     "restitution = 0.3\n", "pairs[0].vehicles",
     'towed and car are joined by "car-towed", so their meshes never meet: give the joint '
     "collide = true"),
]  # fmt: skip


@pytest.mark.parametrize("what, text, key, words", ERRORS, ids=[e[0] for e in ERRORS])
def test_bad_joints_are_refused_naming_the_file_table_and_key(
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


def test_a_bad_joint_is_one_line_and_exit_2_from_the_command(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "case.toml"
    path.write_text(GOOD + "stiffness = -5\n", encoding="utf-8")
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert err.startswith(f"crashsim: error: {path}: joints[0].stiffness: the joint's stiffness")
    assert not (tmp_path / "out").exists()


BOXES = """format_version = 1
[contact]
depth_of_penetration = "auto"
[ground]

[[vehicles]]
name = "car"
box = { length = "4.5 m", width = "1.8 m", height = "1.4 m" }
mass = "1450 kg"
position = [0, 0]

[[vehicles]]
name = "towed"
box = { length = "4.5 m", width = "1.8 m", height = "1.4 m" }
mass = "1450 kg"
position = ["-5.1 m", 0]

[[joints]]
vehicles = ["car", "towed"]
at = ["-2.55 m", 0, "0.5 m"]
"""


def test_a_joined_pair_needs_no_stiffness_unless_it_collides() -> None:
    # depth_of_penetration = "auto" needs stiffness for every pair that can meet: boxes have
    # none, and a joined pair cannot meet unless the joint lets it collide
    assert [j.name for j in loads_scene(BOXES).scene.joints] == ["car-towed"]
    with pytest.raises(SceneFileError) as info:
        loads_scene(BOXES + "collide = true\n")
    assert info.value.key == "contact.depth_of_penetration"
    assert "vehicle 'car': it has no stiffness on its front face" in str(info.value)
    # collide = true: the pair exists, and a [[pairs]] entry for it applies
    case = loads_scene(GOOD + 'collide = true\n[[pairs]]\nvehicles = ["car", "towed"]\n'
                       "restitution = 0.3\n")  # fmt: skip
    assert case.scene.contact_parameters("car", "towed")["restitution"] == 0.3
    assert [p[:2] for p in case.scene.pairs()] == [("car", "towed")]


# -- the report ------------------------------------------------------------------------------


def test_a_report_without_joints_has_none_of_their_keys() -> None:
    report = build_report(load_scene(REPO / "examples" / "seed-90deg.toml").simulate())
    d = report.to_dict()
    assert "joints" not in d["scene"] and "joints" not in d and "joint_events" not in d
    assert report.joints == [] and "Joints" not in report.summary_table()


# -- the example -------------------------------------------------------------------------------


def test_the_towed_car_example_runs_and_checks(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    case = load_scene(EXAMPLE)
    (joint,) = case.scene.joints
    assert (joint.name, joint.kind, joint.vehicles) == ("bar", "spherical", ("car", "towed"))
    assert case.run.until == "rest"
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLE), "--out", str(out), "--html"]) == 0
    printed = capsys.readouterr().out
    assert "\nJoints (force and torque of the first vehicle on the second" in printed
    assert "  bar: spherical, car - towed; largest force " in printed
    names = {p.name for p in out.iterdir()}
    assert {"report.json", "time-histories.csv", "trajectories.png", "motion.glb",
            "case.html"} <= names  # fmt: skip
    d = json.loads((out / "report.json").read_text(encoding="utf-8"))
    jsonschema.Draft202012Validator(report_schema()).validate(d)
    assert d["schema_version"] == 1
    assert [j["name"] for j in d["scene"]["joints"]] == ["bar"]
    assert [j["name"] for j in d["joints"]] == ["bar"] and d["joint_events"] == []
    assert all(r["at_rest"] for r in d["run_out"])  # both at rest within max_duration
    # the case page from the report alone
    assert main(["view", str(out / "report.json"), "--out", str(tmp_path / "page.html")]) == 0
    assert main(["check", str(EXAMPLE), "--duration", "1 s"]) == 0
