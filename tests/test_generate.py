"""cs.Vehicle.generate: a vehicle of a built-in class on a generated body.

With no argument every number is the class table's (mass, dimensions, CG, yaw inertia and
stiffness to 1e-12); given dimensions and mass scale the CG and the yaw inertia as stated (the
expected values are computed here by hand from the table); roll and pitch are the uniform solid's,
checked against trimesh's mass properties (an independent integration); overrides, errors, and a
generated pair in the seed's 30 mph side impact.
"""

from __future__ import annotations

import math

import crashsim as cs
import numpy as np
import pytest
import trimesh
from crashsim.vehicles.generator import PRESETS, body_params, generate_body
from crashsim.vehicles.mass_properties import empirical_inertia
from crashsim.vehicles.vehicle_data import vehicle_class

CLASS_FIELDS = ("length", "width", "height", "wheelbase")


def solid_at(mesh: trimesh.Trimesh, mass: float, point: np.ndarray) -> np.ndarray:
    """trimesh's uniform solid of the mesh, scaled to mass (kg) and moved to point (m) by the
    parallel-axis theorem (kg m^2): the independent reference for the engine's integration."""
    d = np.asarray(point, dtype=np.float64) - mesh.center_mass
    about_centroid = mesh.moment_inertia * (mass / mesh.volume)
    return about_centroid + mass * (float(d @ d) * np.eye(3) - np.outer(d, d))


# -- no argument: every number from the class table --------------------------------------------


@pytest.fixture(scope="module", params=PRESETS)
def default_vehicle(request: pytest.FixtureRequest) -> tuple[str, cs.Vehicle]:
    return request.param, cs.Vehicle.generate(request.param)


def test_default_vehicle_takes_every_number_from_the_class(default_vehicle) -> None:
    preset, v = default_vehicle
    vc = vehicle_class(preset)
    p = v.generator_params
    assert p is not None and p.preset == preset
    assert v.name == preset
    assert v.mass == vc.mass.value
    for name in CLASS_FIELDS:
        assert getattr(p, name) == getattr(vc, name).value
    # the mesh spans the dimensions: x, y centred; z from the ground clearance to the roof
    lo, hi = v.mesh.bounds
    assert np.allclose(lo, [-p.length / 2, -p.width / 2, p.ground_clearance], rtol=0, atol=1e-9)
    assert np.allclose(hi, [p.length / 2, p.width / 2, p.height], rtol=0, atol=1e-9)
    # the CG: cg_to_front_axle behind the front axle (front face at +L/2), cg_height high
    front_axle = p.length / 2 - p.front_overhang
    assert v.cg[0] == pytest.approx(front_axle - vc.cg_to_front_axle.value, abs=1e-12)
    assert v.cg[1] == 0.0
    assert v.cg[2] == pytest.approx(vc.cg_height.value, abs=1e-12)
    assert v.inertia[2, 2] == pytest.approx(vc.yaw_inertia.value, rel=1e-12)
    side = vc.side.to_stiffness()
    assert v.stiffness.front == vc.front.to_stiffness()
    assert v.stiffness.rear == vc.rear.to_stiffness()
    assert v.stiffness.left == side and v.stiffness.right == side
    table = f"class table ({preset})"
    assert v.sources == {
        "cg": table,
        "inertia": f"Izz {table}; Ixx, Iyy: uniform solid of the generated body",
        "mass": table,
        "dimensions": table,
        "body": f"generator defaults ({preset})",
        "stiffness": table,
    }
    assert v.mass_source == table
    text = v.summary()
    assert f"[{table}]" in text and f"crashsim.vehicles.generator {preset}" in text
    assert "Ixz = Iyz = 0" in text


def test_default_vehicle_body_is_the_reference_body(default_vehicle) -> None:
    preset, v = default_vehicle
    vc = vehicle_class(preset)
    mesh = generate_body(body_params(preset, **{k: getattr(vc, k).value for k in CLASS_FIELDS}))
    assert np.array_equal(v.mesh.vertices, mesh.vertices)
    assert np.array_equal(v.mesh.faces, mesh.faces)
    assert v.mesh.is_watertight and v.mesh.is_volume and v.mesh.body_count == 1


def test_default_inertia_is_the_solid_with_the_class_yaw_moment(default_vehicle) -> None:
    """Ixx, Iyy, Ixy: trimesh's uniform solid moved to the CG (to 1e-6 of the largest moment);
    Izz the class's; Ixz = Iyz = 0 exactly; the tensor is a physical one (positive principal
    moments that satisfy the triangle inequalities)."""
    preset, v = default_vehicle
    ref = solid_at(v.mesh, v.mass, v.cg)
    tol = 1e-6 * np.abs(ref).max()
    assert abs(v.inertia[0, 0] - ref[0, 0]) < tol
    assert abs(v.inertia[1, 1] - ref[1, 1]) < tol
    assert abs(v.inertia[0, 1] - ref[0, 1]) < tol
    # Ixy would be zero but for the triangulation, which is not mirror symmetric (the vertices
    # are; each quad of the loft is split along the same diagonal on both sides): measured
    # |Ixy| / max |I| from 5e-9 (pickup) to 1.5e-5 (van)
    assert abs(v.inertia[0, 1]) < 3e-5 * np.abs(ref).max()
    assert v.inertia[0, 2] == v.inertia[2, 0] == v.inertia[1, 2] == v.inertia[2, 1] == 0.0
    assert np.array_equal(v.inertia, v.inertia.T)
    moments = np.linalg.eigvalsh(v.inertia)
    assert moments.min() > 0.0
    a, b, c = moments
    assert a + b >= c and b + c >= a and a + c >= b
    # the class's yaw moment and the uniform solid's are of a size (measured ratios: sedan
    # 0.91, suv 0.93, pickup 1.01, van 1.05, bus 0.98)
    assert 0.85 < v.inertia[2, 2] / ref[2, 2] < 1.1, preset


# -- scaled: dimensions and mass given ----------------------------------------------------------


def test_scaled_sedan_keeps_the_class_ratios() -> None:
    """A sedan with wheelbase 2.90 m, height 1.35 m and 1600 kg: the CG keeps the class's
    ratios (cg_to_front_axle / WB, cg_height / H) and Izz follows m k^2 with k / WB the class's;
    the numbers by hand from the table."""
    vc = vehicle_class("sedan")
    v = cs.Vehicle.generate("sedan", wheelbase=2.90, height=1.35, mass=1600.0)
    p = v.generator_params
    assert p is not None
    assert (p.length, p.width, p.wheelbase, p.height) == (
        vc.length.value,
        vc.width.value,
        2.90,
        1.35,
    )
    # front overhang: the sedan's default share 0.46 of the two overhangs
    assert p.front_overhang == pytest.approx(0.46 * (vc.length.value - 2.90), rel=1e-15)
    to_axle = vc.cg_to_front_axle.value * 2.90 / vc.wheelbase.value
    expected_cg = [vc.length.value / 2 - p.front_overhang - to_axle, 0.0, 0.0]
    expected_cg[2] = vc.cg_height.value * 1.35 / vc.height.value
    assert np.allclose(v.cg, expected_cg, rtol=0, atol=1e-12)
    front_axle = p.length / 2 - p.front_overhang
    ratio = vc.cg_to_front_axle.value / vc.wheelbase.value
    assert (front_axle - v.cg[0]) / p.wheelbase == pytest.approx(ratio, rel=1e-12)
    assert v.cg[2] / p.height == pytest.approx(vc.cg_height.value / vc.height.value, rel=1e-12)
    izz = vc.yaw_inertia.value * (1600.0 / vc.mass.value) * (2.90 / vc.wheelbase.value) ** 2
    assert v.inertia[2, 2] == pytest.approx(izz, rel=1e-12)
    # the same as: the yaw radius of gyration is the class's share of the wheelbase
    k_class = math.sqrt(vc.yaw_inertia.value / vc.mass.value) / vc.wheelbase.value
    assert math.sqrt(v.inertia[2, 2] / v.mass) / 2.90 == pytest.approx(k_class, rel=1e-12)
    assert v.sources["cg"] == "class table (sedan), scaled to wheelbase 2.900 m and height 1.350 m"
    assert v.sources["inertia"] == (
        "Izz class table (sedan), scaled to mass 1600.0 kg and wheelbase 2.900 m; "
        "Ixx, Iyy: uniform solid of the generated body"
    )
    assert v.sources["mass"] == "user" and v.mass_source == "user"
    assert v.sources["dimensions"] == "user (height, wheelbase); class table (sedan) for the rest"
    ref = solid_at(v.mesh, 1600.0, v.cg)
    assert v.inertia[0, 0] == pytest.approx(ref[0, 0], rel=1e-6)
    assert v.inertia[1, 1] == pytest.approx(ref[1, 1], rel=1e-6)


def test_mass_alone_scales_izz_and_nothing_else() -> None:
    base = cs.Vehicle.generate("van")
    heavy = cs.Vehicle.generate("van", mass=2.0 * base.mass)
    assert np.array_equal(heavy.cg, base.cg)
    assert np.array_equal(heavy.mesh.vertices, base.mesh.vertices)
    # every moment doubles: the solid's with the mass, Izz by m / m_class
    assert np.allclose(heavy.inertia, 2.0 * base.inertia, rtol=1e-12, atol=1e-9)
    assert heavy.sources["cg"] == "class table (van)"


def test_weight_in_pounds() -> None:
    v = cs.Vehicle.generate("pickup", weight_lb=3600.0)
    assert v.mass == pytest.approx(3600.0 * 0.45359237, rel=1e-15)
    assert v.mass_source == v.sources["mass"] == "weight in lb (3600 lb)"


# -- overrides ----------------------------------------------------------------------------------


def test_user_cg_moves_the_solid_and_keeps_the_class_izz() -> None:
    cg = (0.2, 0.0, 0.6)
    v = cs.Vehicle.generate("sedan", cg=cg)
    assert np.array_equal(v.cg, cg)
    assert v.sources["cg"] == "user"
    ref = solid_at(v.mesh, v.mass, np.array(cg))
    assert v.inertia[0, 0] == pytest.approx(ref[0, 0], rel=1e-6)
    assert v.inertia[1, 1] == pytest.approx(ref[1, 1], rel=1e-6)
    assert v.inertia[2, 2] == pytest.approx(vehicle_class("sedan").yaw_inertia.value, rel=1e-12)


def test_inertia_choices() -> None:
    given = np.diag([600.0, 2900.0, 3100.0])
    v = cs.Vehicle.generate("suv", inertia=given)
    assert np.array_equal(v.inertia, given) and v.sources["inertia"] == "user"
    solid = cs.Vehicle.generate("suv", inertia="mesh")
    ref = solid_at(solid.mesh, solid.mass, solid.cg)
    assert np.allclose(solid.inertia, ref, rtol=0, atol=1e-6 * np.abs(ref).max())
    assert solid.inertia[0, 2] != 0.0  # the whole solid, products included
    assert solid.sources["inertia"] == "uniform solid of the generated body"
    emp = cs.Vehicle.generate("suv", inertia="empirical")
    p = emp.generator_params
    assert p is not None
    expected = empirical_inertia(emp.mass, p.wheelbase, *(float(e) for e in emp.mesh.extents))
    assert np.array_equal(emp.inertia, expected)
    assert emp.sources["inertia"] == "empirical"
    centroid = cs.Vehicle.generate("suv", cg="mesh")
    assert np.allclose(centroid.cg, centroid.mesh.center_mass, rtol=0, atol=1e-9)
    assert centroid.sources["cg"] == "uniform solid of the generated body"
    explicit = cs.Vehicle.generate("suv", cg="class", inertia="class")
    default = cs.Vehicle.generate("suv")
    assert np.array_equal(explicit.cg, default.cg)
    assert np.array_equal(explicit.inertia, default.inertia)


def test_stiffness_override_and_shape_parameters_pass_through() -> None:
    v = cs.Vehicle.generate(
        "sedan",
        name="red",
        stiffness={"front": (50_000.0, 1.2e6)},
        bumper_radius=0.3,
        front_overhang=0.9,
        resolution=0.5,
    )
    assert v.name == "red"
    assert v.stiffness == cs.Stiffness(front=cs.FaceStiffness(50_000.0, 1.2e6))
    assert v.sources["stiffness"] == "user"
    p = v.generator_params
    assert p is not None and (p.bumper_radius, p.front_overhang) == (0.3, 0.9)
    assert v.sources["body"] == "user (bumper_radius, front_overhang); generator defaults (sedan)"
    assert len(v.mesh.faces) < 0.6 * len(cs.Vehicle.generate("sedan").mesh.faces)
    # the CG follows the front axle that front_overhang moved
    vc = vehicle_class("sedan")
    assert v.cg[0] == pytest.approx(p.length / 2 - 0.9 - vc.cg_to_front_axle.value, abs=1e-12)


def test_alias_renamed_and_other_vehicles() -> None:
    v = cs.Vehicle.generate("mid_car")
    assert v.generator_params is not None and v.generator_params.preset == "sedan"
    assert v.name == "sedan"
    w = v.renamed("other")
    assert w.generator_params is v.generator_params and w.sources == v.sources
    assert cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0).generator_params is None


# -- errors -------------------------------------------------------------------------------------


@pytest.mark.parametrize("preset", ["coupe", "small_car", "", 3])
def test_unknown_preset_lists_the_presets(preset) -> None:
    with pytest.raises(cs.ParameterError, match=r"unknown preset .*: use one of sedan, suv, pick"):
        cs.Vehicle.generate(preset)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"wheelbase": 6.0}, r"wheelbase = 6.0 m is not shorter than length"),
        ({"length": 2.0}, r"wheelbase = 2.728214 m is not shorter than length = 2.0 m"),
        ({"height": -1.0}, r"height = -1.0 m is invalid"),
        ({"wheelbase": 0.4}, r"wheelbase = 0.4 m is too short for two wheel arches"),
        ({"roof_height": 1.4}, r"unknown shape parameter\(s\) roof_height"),
        ({"mass": 1500.0, "weight_lb": 3300.0}, r"they conflict; give exactly one"),
        ({"mass": -5.0}, r"mass"),
        ({"inertia": "box"}, r"inertia = 'box' is unknown: give numbers or one of 'class'"),
        ({"cg": "centre"}, r"cg = 'centre' is unknown"),
        ({"cg": (0.0, 0.0)}, r"cg must be 3 numbers"),
        ({"resolution": 0.0}, r"resolution = 0.0 is invalid"),
        ({"stiffness": {"roof": (1.0, 2.0)}}, r"unknown face 'roof'"),
    ],
)
def test_bad_input_is_a_parameter_error(kwargs: dict, message: str) -> None:
    with pytest.raises(cs.ParameterError, match=message):
        cs.Vehicle.generate("sedan", **kwargs)


# -- in a scene ---------------------------------------------------------------------------------


def seed_side_impact(depth_of_penetration: float | str) -> tuple[cs.Result, float, float]:
    """The seed's 30 mph side impact (reference-cases.md section 1) with two generated sedans:
    red (heading 0, at 30 mph) into the left side of blue (at rest, heading 90 deg: its left
    side faces -x), 0.5 m apart, red 0.3 m off blue's CG. Returns the result, the speed (m/s)
    and the gap (m)."""
    red = cs.Vehicle.generate("sedan", name="red")
    blue = red.renamed("blue")
    p = red.generator_params
    assert p is not None
    speed, gap = cs.mph(30.0), 0.5
    # red's front face (x = L/2 in its model frame) 0.5 m from blue's left side (y = W/2)
    x0 = -p.width / 2 - (p.length / 2 - red.cg[0]) - gap
    scene = cs.Scene(depth_of_penetration=depth_of_penetration)  # type: ignore[arg-type]
    scene.add(red, position=(x0, 0.3, red.cg[2]), heading=0.0, velocity=(speed, 0.0, 0.0))
    scene.add(blue, position=(0.0, 0.0, blue.cg[2]), heading=cs.deg(90.0))
    return scene.run(duration=0.3, dt=1e-3), speed, gap


def test_generated_sedans_in_the_seed_side_impact() -> None:
    result, speed, gap = seed_side_impact(0.030)
    assert len(result.impacts) >= 1
    imp = result.impacts[0]
    assert imp.vehicles == ("red", "blue") and not imp.secondary
    # red's flat front face meets blue's flat side wall after the gap at 30 mph (the first
    # overlap is bisected to 1e-9 s)
    assert imp.first_contact_time == pytest.approx(gap / speed, abs=1e-8)
    assert imp.time - imp.first_contact_time == pytest.approx(0.030, abs=1e-9)
    assert imp.normal[0] > 0.999  # into blue's left side, along +x
    # linear momentum is conserved through the exchange (equal masses)
    before = result.state_at("red", 0.0)["velocity"] + result.state_at("blue", 0.0)["velocity"]
    after = result.state_at("red", 0.3)["velocity"] + result.state_at("blue", 0.3)["velocity"]
    assert np.allclose(after, before, rtol=0, atol=1e-9 * speed)
    red_after = result.state_at("red", 0.3)["velocity"]
    blue_after = result.state_at("blue", 0.3)["velocity"]
    assert 0.0 < red_after[0] < speed and blue_after[0] > 0.0  # a real exchange


def test_generated_sedans_carry_the_class_stiffness_into_the_engine() -> None:
    """With depth_of_penetration="auto" the engine uses the class stiffness of red's front
    and blue's left side: k = B W over the overlap width, and dt_p = sqrt(m'/k') with the
    series effective mass and stiffness (the seed's relation)."""
    result, _, _ = seed_side_impact("auto")
    imp = result.impacts[0]
    vc = vehicle_class("sedan")
    assert imp.struck_faces == {"red": "front", "blue": "left"}
    width = imp.overlap_width
    assert imp.spring_rates["red"] == pytest.approx(vc.front.B.value * width, rel=1e-12)
    assert imp.spring_rates["blue"] == pytest.approx(vc.side.B.value * width, rel=1e-12)
    k1, k2 = imp.spring_rates["red"], imp.spring_rates["blue"]
    m1, m2 = imp.effective_mass["red"], imp.effective_mass["blue"]
    expected = math.sqrt((m1 * m2 / (m1 + m2)) / (k1 * k2 / (k1 + k2)))
    assert imp.depth_of_penetration == pytest.approx(expected, abs=2e-9)  # bisected to 1e-9 s
    assert 0.010 < imp.depth_of_penetration < 0.060
