"""Scene files (crashsim.io.scenefile): the unit parser against the exact definitions, every
example scene, the seed's examples end to end, the loader against the Python API (same
trajectories bit for bit) and one-line errors that name the file and the key."""

from __future__ import annotations

import math
import os
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
from conftest import MISSING, REPO, SHARED_MESHES
from crashsim.io import scenefile as sf
from crashsim.io.scenefile import SceneFileError, load_scene, loads_scene, parse_quantity
from crashsim.vehicles.generator import SHAPE_PARAMETERS
from crashsim.vehicles.vehicle_data import vehicle_class

EXAMPLES = REPO / "examples"
DOCS = REPO / "docs" / "scene-format.md"
G0 = 9.80665  # m/s^2, standard gravity (exact by definition)
LBF = cs.lb(1.0) * G0  # N
INCH = cs.ft(1.0) / 12.0  # m

# Every unit of the table and its size in SI, from crashsim.units or the definitions.
EXPECTED = {
    "m": 1.0,
    "cm": 0.01,
    "mm": 0.001,
    "km": 1000.0,
    "in": INCH,
    "ft": cs.ft(1.0),
    "kg": 1.0,
    "g": 0.001,
    "t": 1000.0,
    "lb": cs.lb(1.0),
    "lbm": cs.lb(1.0),
    "s": 1.0,
    "ms": 0.001,
    "m/s": 1.0,
    "km/h": cs.kmh(1.0),
    "kph": cs.kmh(1.0),
    "mph": cs.mph(1.0),
    "ft/s": cs.ft_s(1.0),
    "fps": cs.ft_s(1.0),
    "rad": 1.0,
    "deg": cs.deg(1.0),
    "rad/s": 1.0,
    "deg/s": cs.deg(1.0),
    "rpm": 2.0 * math.pi / 60.0,
    "N": 1.0,
    "kN": 1000.0,
    "lbf": LBF,
    "kg m^2": 1.0,
    # lbf ft s^2 = (lbf s^2 / ft) ft^2 = slug ft^2
    "lb ft s^2": LBF * cs.ft(1.0),
    "lbf ft s^2": LBF * cs.ft(1.0),
    "slug ft^2": LBF / cs.ft(1.0) * cs.ft(1.0) ** 2,
    "N/m": 1.0,
    "kN/m": 1000.0,
    "lb/in": LBF / INCH,
    "lbf/in": LBF / INCH,
    "N/m^2": 1.0,
    "kN/m^2": 1000.0,
    "lb/in^2": LBF / INCH**2,
    "lbf/in^2": LBF / INCH**2,
    "psi": LBF / INCH**2,
    "m/s^2": 1.0,
    "ft/s^2": cs.ft(1.0),
    "Hz": 1.0,
    "N s/m": 1.0,
    "kN s/m": 1000.0,
    "N m/rad": 1.0,
    "N m/deg": 1.0 / cs.deg(1.0),
    "kN m/rad": 1000.0,
    "N m s/rad": 1.0,
    "N m s/deg": 1.0 / cs.deg(1.0),
    "kN m s/rad": 1000.0,
    "N m": 1.0,
    "kN m": 1000.0,
    "lbf ft": LBF * cs.ft(1.0),
    "1/rad": 1.0,
    "1/deg": 1.0 / cs.deg(1.0),
    "rad/g": 1.0,
    "deg/g": cs.deg(1.0),
}

# crashsim.units' own helpers: the factor is exactly the helper's value of 1.
HELPERS = {
    "ft": cs.ft,
    "lb": cs.lb,
    "lbm": cs.lb,
    "mph": cs.mph,
    "km/h": cs.kmh,
    "kph": cs.kmh,
    "ft/s": cs.ft_s,
    "fps": cs.ft_s,
    "deg": cs.deg,
    "deg/s": cs.deg,
}


# -- units ---------------------------------------------------------------------------------


def test_every_unit_has_its_exact_factor() -> None:
    assert set(sf.UNITS) == set(EXPECTED)  # a new unit needs its definition here
    for key, unit in sf.UNITS.items():
        assert unit.dimension in sf.DIMENSIONS, key
        assert unit.factor == pytest.approx(EXPECTED[key], rel=2e-16, abs=0.0), key
    for key, helper in HELPERS.items():
        assert sf.UNITS[key].factor == helper(1.0), key
    # the published definitions
    assert sf.UNITS["in"].factor == 0.0254
    assert LBF == pytest.approx(4.4482216152605, rel=1e-15)
    assert sf.UNITS["lb ft s^2"].factor == pytest.approx(1.3558179483314004, rel=1e-15)


@pytest.mark.parametrize("key", sorted(EXPECTED))
def test_each_unit_parses_to_its_si_value(key: str) -> None:
    dimension = sf.UNITS[key].dimension
    for number in (1.0, 30.0, 0.25, -7.5e2):
        got = parse_quantity(f"{number:g} {key}", dimension)
        assert got == pytest.approx(number * EXPECTED[key], rel=4e-16, abs=0.0)
    if key in HELPERS:  # the same value as crashsim.units' helper, to the last bit or one
        assert parse_quantity(f"48 {key}", dimension) == pytest.approx(
            HELPERS[key](48.0), rel=2.3e-16, abs=0.0
        )


def test_the_briefs_unit_strings() -> None:
    cases = {
        ("30 mph", "speed"): cs.mph(30.0),
        ("1450 kg", "mass"): 1450.0,
        ("3200 lb", "mass"): cs.lb(3200.0),
        ("90 deg", "angle"): math.pi / 2.0,
        ("12 ft", "length"): cs.ft(12.0),
        ("48 km/h", "speed"): cs.kmh(48.0),
        ("30 ms", "time"): 0.030,
        ("0.2 rad/s", "angular velocity"): 0.2,
        ("15 deg/s", "angular velocity"): cs.deg(15.0),
    }
    for (text, dim), want in cases.items():
        assert parse_quantity(text, dim) == pytest.approx(want, rel=2.3e-16, abs=0.0), text


def test_spellings_and_plain_numbers() -> None:
    assert parse_quantity(1450, "mass") == 1450.0  # a plain number is SI
    assert parse_quantity(0.5, "time") == 0.5
    assert parse_quantity("30mph", "speed") == cs.mph(30.0)
    assert parse_quantity("  30   MPH ", "speed") == cs.mph(30.0)  # case-insensitive
    assert parse_quantity("1.5e3 kg", "mass") == 1500.0
    assert parse_quantity("-2 ft", "length") == cs.ft(-2.0)
    assert parse_quantity("+.5 m", "length") == 0.5
    assert parse_quantity("15 °/s", "angular velocity") == cs.deg(15.0)
    assert parse_quantity("90°", "angle") == cs.deg(90.0)
    assert parse_quantity("2500 kg*m^2", "moment of inertia") == 2500.0
    assert parse_quantity("2500 kg·m²", "moment of inertia") == 2500.0
    assert parse_quantity("50 km / h", "speed") == pytest.approx(cs.kmh(50.0), rel=2.3e-16)


@pytest.mark.parametrize(
    "value, dimension, match",
    [
        ("30 mph", "length", r'"30 mph" is a speed, not a length'),
        ("30 mph", "mass", r"is a speed, not a mass.*kg, g, t, lb"),
        ("3 parsec", "length", r'unknown unit "parsec"'),
        ("1450", "mass", r'"1450" has no unit'),
        ("heavy", "mass", "does not start with a number"),
        ("inf kg", "mass", "does not start with a number"),
        (float("nan"), "mass", "not a finite number"),
        (float("inf"), "length", "not a finite number"),
        (True, "mass", "got true/false"),
        ([1, 2], "length", "got a list"),
        ("1 m", "volume", "unknown dimension"),
    ],
)
def test_bad_quantities_are_refused(value: object, dimension: str, match: str) -> None:
    with pytest.raises(cs.ParameterError, match=match):
        parse_quantity(value, dimension)


@pytest.mark.parametrize("dimension", sorted(sf.DIMENSIONS))
def test_every_quantity_says_what_it_expected(dimension: str) -> None:
    # an anti-roll bar's "3 mph", a cornering coefficient or roll gradient in a wrong unit
    # raised KeyError (no example written for their quantity): a traceback, not exit 2
    wrong = "3 mph" if dimension != "speed" else "3 kg"
    for value in (wrong, True):
        with pytest.raises(cs.ParameterError, match=f" {dimension} such as "):
            parse_quantity(value, dimension)
    with pytest.raises(cs.ParameterError, match='"3" has no unit: write e.g. "'):
        parse_quantity("3", dimension)


# -- examples ------------------------------------------------------------------------------

WANTED_EXAMPLES = {
    "seed-90deg.toml",
    "seed-45deg.toml",
    "mesh-sedan-into-pickup.toml",
    "generated-offset-frontal.toml",
    "three-vehicles.toml",
    "runout-sedan-into-suv.toml",
    "runout-small-overlap-barrier.toml",
    "runout-sedan-into-pole.toml",
    "runout-rollover-kerb.toml",
    "fit-skid.toml",
    "manoeuvre-step-steer.toml",
    "manoeuvre-lane-change.toml",
    "manoeuvre-fishhook.toml",
    "reference-sedan-steer-15mph.toml",
}


def _needs(text: str) -> str | None:
    """Why an example cannot load here (None when it can)."""
    if "shared/meshes" in text and not SHARED_MESHES.is_dir():
        return MISSING
    return None


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.stem)
def test_every_example_loads(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    reason = _needs(text)
    if reason is not None:
        pytest.skip(reason)
    case = load_scene(path)
    assert case.path == path and case.title
    # two vehicles, or one and a wall, or one vehicle's run-out to fit (a [fit] table), or a
    # manoeuvre on a ground
    assert (
        len(case.scene) + len(case.scene.obstacles) >= 2
        or case.fit is not None
        or case.scene.ground is not None
    )
    assert case.run.longest > 0.0 and case.run.dt > 0.0
    scene, run, output = case  # unpacks
    assert scene is case.scene and run is case.run and output is case.output


def test_the_examples_are_all_there() -> None:
    assert WANTED_EXAMPLES <= {p.name for p in EXAMPLES.glob("*.toml")}
    mesh_case = (EXAMPLES / "mesh-sedan-into-pickup.toml").read_text(encoding="utf-8")
    assert "../../shared/meshes/" in mesh_case and "NOT in this repository" in mesh_case
    three = load_scene(EXAMPLES / "three-vehicles.toml")
    assert len(three.scene) == 3


@pytest.mark.parametrize(
    "name, speed, published",
    [("seed-90deg.toml", cs.mph(30.0), 0.4023), ("seed-45deg.toml", cs.mph(60.0), 0.8047)],
)
def test_seed_examples_end_to_end(name: str, speed: float, published: float) -> None:
    case = load_scene(EXAMPLES / name)
    result = case.simulate()
    imp = result.impacts[0]
    assert imp.vehicles == ("red", "blue") and not imp.secondary
    assert imp.depth_of_penetration == 0.030
    p0 = result.state_at("red", imp.first_contact_time)["position"]
    p1 = result.state_at("red", imp.time)["position"]
    travel = float(np.linalg.norm(p1 - p0))
    assert travel == pytest.approx(published, abs=1e-3)  # the seed's figure, to 1 mm
    assert travel == pytest.approx(speed * 0.030, rel=1e-9)  # v dt_p
    assert np.allclose(imp.normal, [1.0, 0.0, 0.0], rtol=0.0, atol=1e-9)  # blue's left side


def test_the_seed_file_is_the_api_scene_bit_for_bit() -> None:
    """The 90 deg example against the same scene built with the Python API (as in
    test_seed_examples.py): identical trajectories and impacts."""
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene(depth_of_penetration=0.030, restitution=0.1, friction=0.6)
    scene.add(red, position=(-3.65, 0.3, 0.7), heading=0.0, velocity=(cs.mph(30.0), 0.0, 0.0))
    scene.add(blue, position=(0.0, 0.0, 0.725), heading=cs.deg(90.0))
    want = scene.run(duration=0.3, dt=1e-3)
    got = load_scene(EXAMPLES / "seed-90deg.toml").simulate()
    assert np.array_equal(got.t, want.t)
    for name in ("red", "blue"):
        a, b = got.trajectory(name), want.trajectory(name)
        for field in a._fields:
            assert np.array_equal(getattr(a, field), getattr(b, field)), (name, field)
    assert [i.to_dict() for i in got.impacts] == [i.to_dict() for i in want.impacts]


# -- what the keys mean --------------------------------------------------------------------

BOX = 'box = { length = "4.5 m", width = "1.8 m", height = "1.4 m" }'


def scene_text(first: str = "", second: str = "", top: str = "") -> str:
    """Two box vehicles 10 m apart; extra lines for the first and second vehicle."""
    return f"""format_version = 1
{top}
[[vehicles]]
name = "red"
{BOX}
mass = "1450 kg"
position = [-5, 0]
{first}

[[vehicles]]
name = "blue"
{BOX}
mass = "1500 kg"
position = [5, 0]
{second}
"""


def placement(case: sf.SceneFile, k: int) -> object:
    return case.scene._placements[k]


def test_speed_direction_heading_and_position() -> None:
    case = loads_scene(
        scene_text(
            first='heading = "30 deg"\nspeed = "50 km/h"',
            second='heading = "90 deg"\nspeed = "10 mph"\ndirection = "-90 deg"\n'
            'yaw_rate = "15 deg/s"',
        )
    )
    red, blue = placement(case, 0), placement(case, 1)
    h = cs.deg(30.0)
    assert np.allclose(
        red.velocity, cs.kmh(50.0) * np.array([math.cos(h), math.sin(h), 0]), rtol=0, atol=1e-15
    )  # the direction of travel defaults to the heading
    assert np.allclose(red.orientation, [math.cos(h / 2), 0, 0, math.sin(h / 2)], atol=1e-16)
    assert np.allclose(blue.velocity, [0.0, -cs.mph(10.0), 0.0], rtol=0, atol=1e-15)
    assert np.array_equal(blue.angular_velocity, [0.0, 0.0, cs.deg(15.0)])
    # a 2-D position puts the CG at its model-frame height: the box stands on the ground
    assert np.array_equal(red.position, [-5.0, 0.0, 0.7])


def test_vector_forms_and_3d_position() -> None:
    case = loads_scene(
        scene_text(
            first='velocity = ["30 mph", "-2 ft/s", 0]\nangular_velocity = [0, 0, "0.2 rad/s"]',
            second='position = "(16.4, 0, 2.3) ft"\norientation = [1, 0, 0, 0]',
        ).replace("position = [5, 0]\n", "", 1)
    )
    red, blue = placement(case, 0), placement(case, 1)
    assert np.array_equal(red.velocity, [cs.mph(30.0), cs.ft_s(-2.0), 0.0])
    assert np.array_equal(red.angular_velocity, [0.0, 0.0, 0.2])
    assert np.array_equal(blue.position, [cs.ft(16.4), 0.0, cs.ft(2.3)])


def test_mass_weight_and_their_units() -> None:
    def mass(line: str) -> cs.Vehicle:
        text = scene_text().replace('mass = "1450 kg"', line, 1)
        return loads_scene(text).scene.vehicles[0]

    assert mass('mass = "1450 kg"').mass == 1450.0
    assert mass("mass = 1450").mass == 1450.0
    v = mass('weight = "3200 lb"')
    assert v.mass == cs.lb(3200.0) and "3200 lb" in v.mass_source
    assert mass('mass = "3200 lb"').mass == cs.lb(3200.0)
    assert mass('weight = "3200 lbf"').mass == cs.lb(3200.0)  # 1 lbf weighs 1 lb
    assert mass('weight = "14.2 kN"').mass == pytest.approx(14200.0 / G0, rel=1e-15)
    assert mass('mass = "1.45 t"').mass == pytest.approx(1450.0, rel=1e-15)


def test_cg_inertia_and_stiffness() -> None:
    case = loads_scene(
        scene_text(
            first='cg_height = "0.55 m"\ninertia = "empirical"\nwheelbase = "2.7 m"\n'
            'stiffness = "sedan"',
            second='inertia = { Ixx = "600 kg m^2", Iyy = 2900, Izz = "2336.3 lb ft s^2" }\n'
            'stiffness = { front = { A = "356 lb/in", B = "34 lb/in^2" }, '
            'side = { A = "143 lb/in", B = "50 psi" } }',
        )
    )
    red, blue = case.scene.vehicles
    assert np.array_equal(red.cg, [0.0, 0.0, 0.55])
    assert red.inertia[2, 2] == pytest.approx(1450.0 * (0.5 * 2.7) ** 2, rel=1e-15)
    assert red.stiffness == vehicle_class("sedan").stiffness
    # reference case 2's yaw inertia: 2336.3 lb ft s^2, given there as 3167.5 kg m^2
    assert blue.inertia[2, 2] == pytest.approx(2336.3 * LBF * cs.ft(1.0), rel=1e-15)
    assert blue.inertia[2, 2] == pytest.approx(3167.5, abs=0.1)
    assert np.array_equal(np.diag(blue.inertia)[:2], [600.0, 2900.0])
    assert np.count_nonzero(blue.inertia - np.diag(np.diag(blue.inertia))) == 0
    s = blue.stiffness
    assert s.front.A == pytest.approx(356.0 * LBF / INCH, rel=1e-15)
    assert s.front.B == pytest.approx(34.0 * LBF / INCH**2, rel=1e-15)
    assert s.left == s.right and s.left.B == pytest.approx(50.0 * LBF / INCH**2, rel=1e-15)
    assert s.rear is None
    # the 2-D position takes the given CG height
    assert placement(case, 0).position[2] == 0.55


def test_full_inertia_tensor() -> None:
    rows = '[["450 kg m^2", 0, -20], [0, 2100, 0], [-20, 0, "2300 kg m^2"]]'
    v = loads_scene(scene_text(first=f"inertia = {rows}")).scene.vehicles[0]
    assert np.array_equal(v.inertia, [[450.0, 0, -20], [0, 2100, 0], [-20, 0, 2300]])


def test_contact_defaults_pairs_run_and_output(tmp_path: Path) -> None:
    top = """
[run]
duration = "250 ms"
dt = "0.5 ms"

[contact]
depth_of_penetration = "25 ms"
restitution = 0.2
friction = 0.5
restitution_mode = "normal"
pitch = "2 deg"

[[pairs]]
vehicles = ["blue", "red"]
normal = [-1, 0, 0]
centroid = { vehicle = "blue", point = ["-2.25 m", 0, 0] }
friction = 0.3

[output]
dir = "results/case"
pictures = false
"""
    path = tmp_path / "case.toml"
    path.write_text(scene_text(top=top), encoding="utf-8")
    case = load_scene(path)
    assert case.run == sf.RunSettings(duration=0.25, dt=0.0005)
    assert case.output.dir == tmp_path / "results/case"  # relative to the scene file
    assert not case.output.pictures and case.output.csv and case.output.report
    d = case.scene.defaults
    assert d["depth_of_penetration"] == 0.025 and d["restitution"] == 0.2
    assert d["restitution_mode"] == "normal" and d["pitch"] == cs.deg(2.0)
    p = case.scene.contact_parameters("blue", "red")
    assert p["friction"] == 0.3 and p["restitution"] == 0.2
    assert np.array_equal(p["normal"], [-1.0, 0.0, 0.0])
    assert p["centroid"][0] == "blue" and np.array_equal(p["centroid"][1], [-2.25, 0.0, 0.0])


def test_auto_depth_of_penetration_with_class_stiffness() -> None:
    text = scene_text(
        top='[contact]\ndepth_of_penetration = "auto"',
        first='stiffness = "sedan"',
        second='stiffness = "suv"',
    )
    assert loads_scene(text).scene.defaults["depth_of_penetration"] == "auto"


def test_mesh_options_and_relative_path(tmp_path: Path) -> None:
    # a box written in millimetres with y up and -z forward, referred to relatively
    import trimesh

    box = trimesh.creation.box(extents=[1800.0, 1400.0, 4500.0])  # file axes: x, y up, z back
    (tmp_path / "meshes").mkdir()
    box.export(tmp_path / "meshes" / "car.ply")
    mesh = (
        'mesh = { file = "meshes/car.ply", units = "mm", up = "y", forward = "-z", ground = true }'
    )
    text = scene_text(first=mesh).replace(BOX, "", 1)
    (tmp_path / "scenes").mkdir()
    path = tmp_path / "scenes" / "c.toml"
    path.write_text(text.replace("meshes/car.ply", "../meshes/car.ply"), encoding="utf-8")
    v = load_scene(path).scene.vehicles[0]
    assert np.allclose(v.extents, [4.5, 1.8, 1.4], rtol=0, atol=1e-12)  # model frame, m
    assert v.mesh.bounds[0][2] == pytest.approx(0.0, abs=1e-12)


@pytest.mark.skipif(not SHARED_MESHES.is_dir(), reason=MISSING)
def test_the_mesh_example_has_the_files_meshes() -> None:
    case = load_scene(EXAMPLES / "mesh-sedan-into-pickup.toml")
    sedan, pickup = case.scene.vehicles
    assert sedan.mesh.faces.shape == (2954, 3) and pickup.mesh.faces.shape == (1084, 3)
    assert pickup.mass == cs.lb(4500.0) and np.array_equal(sedan.cg, [0.0, 0.0, 0.55])


def test_generate_gets_the_preset_and_the_dimensions_in_si(monkeypatch: pytest.MonkeyPatch) -> None:
    """The loader's side of Vehicle.generate, with a stand-in that records its arguments (a
    box of the given length and width)."""
    calls = []

    def generate(preset, *, name=None, mass=None, weight_lb=None, stiffness=None, **dims):
        calls.append((preset, name, mass, weight_lb, stiffness, dims))
        return cs.Vehicle.box(dims["length"], dims["width"], 1.5, mass=mass, name=name)

    monkeypatch.setattr(cs.Vehicle, "generate", staticmethod(generate), raising=False)
    text = GOOD.replace(
        BOX,
        'generate = { preset = "pickup", length = "18 ft", width = "2.0 m", '
        'bumper_radius = "30 cm", tumblehome = 0 }\nstiffness = "pickup"',
        1,
    )
    case = loads_scene(text)
    preset, name, mass, weight_lb, stiffness, dims = calls[0]
    assert (preset, name, mass, weight_lb) == ("pickup", "red", 1450.0, None)
    assert stiffness == vehicle_class("pickup").stiffness
    assert dims == {"length": cs.ft(18.0), "width": 2.0, "bumper_radius": 0.3, "tumblehome": 0.0}
    assert set(sf.GENERATE_KEYS) == {
        "preset",
        "length",
        "width",
        "height",
        "wheelbase",
        *SHAPE_PARAMETERS,
    }
    assert case.scene.vehicles[0].extents[0] == cs.ft(18.0)


def test_the_generated_example_has_its_dimensions() -> None:
    suv, sedan = load_scene(EXAMPLES / "generated-offset-frontal.toml").scene.vehicles
    assert np.allclose(suv.extents[:2], [4.75, 1.90], rtol=0, atol=1e-9)
    assert np.allclose(sedan.extents[:2], [4.85, 1.83], rtol=0, atol=1e-9)
    assert suv.mesh.bounds[1][2] == pytest.approx(1.72, abs=1e-9)  # the roof height


# -- errors --------------------------------------------------------------------------------

GOOD = scene_text()

ERRORS = [
    # (what, text, key path, words of the message)
    ("missing mass", GOOD.replace('mass = "1450 kg"\n', "", 1), "vehicles[0].mass", "required"),
    (
        "a speed as a mass",
        GOOD.replace('"1450 kg"', '"30 mph"', 1),
        "vehicles[0].mass",
        '"30 mph" is a speed, not a mass',
    ),
    (
        "a typo",
        GOOD.replace("position = [5, 0]", "positon = [5, 0]"),
        "vehicles[1].positon",
        'did you mean "position"',
    ),
    ("an unknown section", GOOD + "\n[runn]\ndt = 1\n", "runn", 'did you mean "run"'),
    (
        "an unknown preset",
        GOOD.replace(BOX, 'generate = { preset = "tank", length = "4 m" }', 1),
        "vehicles[0].generate.preset",
        '"tank" is not one of "sedan", "suv", "pickup", "van", "bus", "tractor", '
        '"tractor_6x4" or "rigid_truck"',
    ),
    (
        "a missing mesh file",
        GOOD.replace(BOX, 'mesh = "no/such/car.ply"', 1),
        "vehicles[0].mesh",
        'mesh file "no/such/car.ply" does not exist',
    ),
    (
        "a missing mesh file in a mesh table",
        GOOD.replace(BOX, 'mesh = { file = "car.obj", units = "in" }', 1),
        "vehicles[0].mesh.file",
        'mesh file "car.obj" does not exist',
    ),
    ("no format version", GOOD.replace("format_version = 1\n", ""), "format_version", "missing"),
    (
        "a later format",
        GOOD.replace("format_version = 1", "format_version = 2"),
        "format_version",
        "2 is not a version",
    ),
    (
        "mass and weight",
        GOOD.replace('mass = "1450 kg"', 'mass = "1450 kg"\nweight = "3200 lb"', 1),
        "vehicles[0].weight",
        "not both",
    ),
    ("no shape", GOOD.replace(BOX + "\n", "", 1), "vehicles[0]", "exactly one of box, mesh"),
    (
        "a negative box length",
        GOOD.replace('length = "4.5 m"', 'length = "-4.5 m"', 1),
        "vehicles[0].box.length",
        "must be positive",
    ),
    (
        "a time as a depth of penetration given in mph",
        GOOD.replace(
            "format_version = 1", 'format_version = 1\n[contact]\ndepth_of_penetration = "30 mph"'
        ),
        "contact.depth_of_penetration",
        "is a speed, not a time",
    ),
    (
        "an out-of-range restitution (the engine's check)",
        GOOD.replace("format_version = 1", "format_version = 1\n[contact]\nrestitution = 1.5"),
        "contact.restitution",
        "restitution = 1.5",
    ),
    (
        "a pair with an unknown vehicle",
        GOOD + '\n[[pairs]]\nvehicles = ["red", "grey"]\nfriction = 0.3\n',
        "pairs[0].vehicles[1]",
        'no vehicle named "grey"',
    ),
    (
        "a duplicate name",
        GOOD.replace('name = "blue"', 'name = "red"'),
        "vehicles[1].name",
        "already in the scene",
    ),
    (
        "a 4-component position",
        GOOD.replace("position = [5, 0]", "position = [5, 0, 1, 2]"),
        "vehicles[1].position",
        "expected 2 or 3 components, got 4",
    ),
    (
        "a bad vector component",
        GOOD.replace("position = [5, 0]", 'position = [5, "2 s"]'),
        "vehicles[1].position[1]",
        '"2 s" is a time, not a length',
    ),
    (
        "heading and orientation",
        GOOD.replace(
            "position = [5, 0]", "position = [5, 0, 1]\nheading = 0\norientation = [1, 0, 0, 0]"
        ),
        "vehicles[1].orientation",
        "not both",
    ),
    (
        "a NaN",
        GOOD.replace('"1450 kg"', "nan", 1),
        "vehicles[0].mass",
        "not a finite number",
    ),
    (
        "auto without stiffness",
        GOOD.replace(
            "format_version = 1", 'format_version = 1\n[contact]\ndepth_of_penetration = "auto"'
        ),
        "contact.depth_of_penetration",
        "vehicle 'red': it has no stiffness on its front face",
    ),
    (
        "cg_height on a mesh",
        GOOD.replace(BOX, 'mesh = "x.ply"\ncg_height = 0.5', 1),
        "vehicles[0].cg_height",
        "for box vehicles",
    ),
    (
        "an unknown vehicle class",
        GOOD.replace('mass = "1450 kg"', 'mass = "1450 kg"\nstiffness = "tank"', 1),
        "vehicles[0].stiffness",
        "unknown vehicle class 'tank'",
    ),
    (
        "a string where a boolean goes",
        GOOD + '\n[output]\ncsv = "yes"\n',
        "output.csv",
        "expected true or false",
    ),
]


@pytest.mark.parametrize("what, text, key, words", ERRORS, ids=[e[0] for e in ERRORS])
def test_errors_name_the_file_and_key_in_one_line(
    what: str, text: str, key: str, words: str, tmp_path: Path
) -> None:
    path = tmp_path / "case.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(SceneFileError) as info:
        load_scene(path)
    e = info.value
    message = str(e)
    assert "\n" not in message
    assert e.file == str(path) and e.key == key
    assert message.startswith(f"{path}: {key}: "), message
    assert words in message, message
    assert isinstance(e, cs.SceneError) and isinstance(e, ValueError)


def test_syntax_errors_give_the_line() -> None:
    text = GOOD.replace('mass = "1500 kg"', 'mass = "1500 kg', 1)  # unclosed string
    line = text.splitlines().index('mass = "1500 kg') + 1
    with pytest.raises(SceneFileError) as info:
        loads_scene(text, source="c.toml")
    e = info.value
    assert e.line == line and e.key is None
    assert str(e).startswith(f"c.toml: line {line}, column ") and "not valid TOML" in str(e)
    assert "\n" not in str(e)


def test_unreadable_files(tmp_path: Path) -> None:
    with pytest.raises(SceneFileError, match=r"nothere\.toml: no such file"):
        load_scene(tmp_path / "nothere.toml")
    bad = tmp_path / "latin1.toml"
    bad.write_bytes(b'format_version = 1\ntitle = "caf\xe9"\n')
    with pytest.raises(SceneFileError, match=r"cannot read it"):
        load_scene(bad)


def test_a_path_that_is_no_file_is_never_opened_and_says_what_it_is(tmp_path: Path) -> None:
    # issue 24: a mesh path that is a folder, a named pipe or a link to /dev/zero said "does
    # not exist"; a scene file that is a named pipe waited for ever, /dev/zero read for ever
    os.mkfifo(tmp_path / "pipe")
    (tmp_path / "zero").symlink_to("/dev/zero")
    (tmp_path / "folder").mkdir()
    kinds = {
        "folder": "a folder",
        "pipe": r"a named pipe \(FIFO\)",
        "zero": r"a character device \(a link to /dev/zero\)",
    }
    for name, kind in kinds.items():
        with pytest.raises(SceneFileError, match=rf"{name}: is {kind}, not a scene file"):
            load_scene(tmp_path / name)
        text = GOOD.replace(BOX, f'mesh = "{name}"', 1)
        with pytest.raises(SceneFileError, match=rf'vehicles\[0\].mesh: mesh file "{name}" is '
                           f"{kind}, not a file"):  # fmt: skip
            loads_scene(text, base_dir=tmp_path)
        text = GOOD.replace("format_version = 1\n", f'format_version = 1\n[ground]\nterrain = '
                            f'"{name}"\n', 1)  # fmt: skip
        with pytest.raises(SceneFileError, match=rf'ground.terrain: terrain file "{name}" is '
                           f"{kind}, not a file"):  # fmt: skip
            loads_scene(text, base_dir=tmp_path)


def test_names_with_control_or_bidirectional_characters_are_refused_at_their_key() -> None:
    # issue 24: a name with a newline or U+202E was accepted (the newline split the CSV header)
    cases = [
        (scene_text().replace('name = "red"', 'name = "red\\u202E"', 1), "vehicles[0].name",
         r"U\+202E \(RIGHT-TO-LEFT OVERRIDE\) at position 3"),
        (scene_text(top='[[obstacles]]\nname = "po\\nle"\npole = { diameter = "0.3 m", height = '
                        '"6 m" }\nposition = ["0 m", "8 m"]\n'),
         "obstacles[0].name", r"U\+000A"),
        (scene_text(top='[ground]\n[[ground.zones]]\nname = "wet\\u2067"\npolygon = [[0, 0], '
                        '[1, 0], [1, 1]]\nfriction = 0.5\n'),
         "ground.zones[0].name", r"U\+2067 \(RIGHT-TO-LEFT ISOLATE\)"),
        (scene_text().replace('name = "red"', 'name = " "', 1), "vehicles[0].name", "non-blank"),
    ]  # fmt: skip
    for text, key, why in cases:
        with pytest.raises(SceneFileError, match=why) as e:
            loads_scene(text)
        assert e.value.key == key


# -- the documentation ---------------------------------------------------------------------


def test_the_format_document_names_every_key_and_unit() -> None:
    doc = DOCS.read_text(encoding="utf-8")
    keys = {
        *sf.TOP_KEYS,
        *sf.RUN_KEYS,
        *sf.OUTPUT_KEYS,
        *sf.CONTACT_KEYS,
        *sf.VEHICLE_KEYS,
        *sf.MESH_KEYS,
        *sf.GENERATE_KEYS,
        *sf.JOINT_KEYS,
        *sf.TRACTOR_KEYS,
        *sf.TRAILER_KEYS,
        *sf.HITCH_KEYS,
        *sf.COUPLING_KEYS,
    }
    missing = sorted(k for k in keys if f"`{k}`" not in doc)
    assert not missing, f"docs/scene-format.md does not describe {missing}"
    units = sorted(u for u in sf.UNITS if f"`{u}`" not in doc)
    assert not units, f"docs/scene-format.md does not list the units {units}"
