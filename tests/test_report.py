"""The reconstruction report (crashsim.analysis.report): deformation figures against the seed's
worked
example and closed forms, PDOF and clock direction in every quadrant, the published barrier
case, the energy split and EES, the JSON report against its schema, and the text table.

Tolerances: closed forms on box geometry to 1e-9 m or 1e-6 deg (round-off of the engine's
poses and of the bisected first overlap, 1e-9 s); the seed's printed figure (0.4023 m) to 1 mm;
the published barrier case to 0.2 % (the spreadsheet's own rounding, reference-cases.md)."""

from __future__ import annotations

import copy
import json
import math
from typing import Any

import crashsim as cs
import jsonschema
import numpy as np
import pytest
import trimesh
from conftest import SHARED_MESHES
from crashsim.analysis.report import (
    SCHEMA_VERSION,
    Report,
    build_report,
    clock_direction,
    pdof,
    report_schema,
)
from crashsim.errors import SceneError

DTP = 0.030  # s, the seed's default depth of penetration
SAE_880223_INTERCEPT = 3.5 * 0.0254  # m, 3.5 in (exact)


def angle_difference(a: float, b: float) -> float:
    """a - b in degrees, wrapped into [-180, 180)."""
    return (a - b + 180.0) % 360.0 - 180.0


# -- scenes ----------------------------------------------------------------------------------


def seed_side_impact(
    speed: float = cs.mph(30.0), stiffness: dict[str, Any] | None = None, **contact: Any
) -> cs.Result:
    """The seed's 90 deg example with boxes (tests/test_seed_examples.py): red (4.5 x 1.8 x
    1.4 m, 1450 kg) at `speed` m/s along +x into the left side of blue (4.6 x 1.8 x 1.45 m,
    1500 kg, at rest, heading +90 deg: its left side is the plane x = -0.9 m)."""
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red", stiffness=stiffness)
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue", stiffness=stiffness)
    scene = cs.Scene(**{"depth_of_penetration": DTP, **contact})
    scene.add(red, position=(-3.65, 0.3, 0.7), heading=0.0, velocity=(speed, 0.0, 0.0))
    scene.add(blue, position=(0.0, 0.0, 0.725), heading=cs.deg(90.0))
    return scene.run(duration=0.3, dt=1e-3)


FACE_ANGLE = {"front": 0.0, "left": 90.0, "rear": 180.0, "right": -90.0}  # outward, body, deg
EXPECTED = {"front": (0.0, 12), "right": (90.0, 3), "rear": (180.0, 6), "left": (270.0, 9)}


def struck_on(face: str, bullet_first: bool, yaw_deg: float) -> cs.Result:
    """A central, collinear impact: a 4.5 x 1.8 x 1.4 m bullet at 15 m/s along world heading
    `yaw_deg` strikes the `face` of a 4.6 x 1.8 x 1.4 m target at rest. Both CGs at 0.7 m on
    the bullet's line, so the impulse is along the normal and each delta-V is exactly along
    the line of travel."""
    psi = math.radians(yaw_deg)
    u = np.array([math.cos(psi), math.sin(psi), 0.0])
    heading = math.radians(yaw_deg + 180.0 - FACE_ANGLE[face])  # the face looks back at -u
    half = 2.3 if face in ("front", "rear") else 0.9
    bullet = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1400.0, name="bullet")
    target = cs.Vehicle.box(4.6, 1.8, 1.4, mass=1600.0, name="target")
    scene = cs.Scene()
    placements = [
        (bullet, dict(position=(0.0, 0.0, 0.7), heading=psi, velocity=15.0 * u)),
        (target, dict(position=(*((2.25 + half + 0.1) * u[:2]), 0.7), heading=heading)),
    ]
    for vehicle, kw in placements if bullet_first else placements[::-1]:
        scene.add(vehicle, **kw)
    return scene.run(duration=0.1, dt=1e-3)


# the published barrier case (reference-cases.md section 2; tests/test_reference_case.py)
FUSION_MASS = 1621.2  # kg
FUSION_IZZ = 3167.5  # kg m^2
FUSION_SPEED = 17.8613  # m/s
FUSION_POINT = (1.1037, 0.6118, 0.0)  # m from the CG, ISO body frame (+y left)
NORMAL_ANGLE = cs.deg(15.4)


@pytest.fixture(scope="module")
def barrier_report() -> Report:
    car = cs.Vehicle.box(
        4.8, 1.8, 1.45, mass=FUSION_MASS, name="fusion", ground_clearance=0.15,
        inertia=np.diag([600.0, 2900.0, FUSION_IZZ]),
    )  # fmt: skip
    barrier = cs.Vehicle.box(
        1.0, 6.0, 2.0, mass=cs.lb(1e7), name="barrier", inertia=np.eye(3) * 1e12
    )
    scene = cs.Scene()
    scene.add(car, position=(0.0, 0.0, car.cg[2]), velocity=(FUSION_SPEED, 0.0, 0.0))
    scene.add(barrier, position=(2.42 + 0.5, 0.0, barrier.cg[2]))
    scene.contact(
        car,
        barrier,
        restitution=0.0,
        friction=0.82,
        centroid=(car, FUSION_POINT),
        normal=(math.cos(NORMAL_ANGLE), math.sin(NORMAL_ANGLE), 0.0),
    )
    return cs.report(scene.run(duration=0.05, dt=1e-3))


@pytest.fixture(scope="module")
def seed_report() -> Report:
    return cs.report(seed_side_impact())


STIFF = {"front": (35000.0, 1.0e6), "rear": (35000.0, 0.8e6), "side": (20000.0, 0.5e6)}


@pytest.fixture(scope="module")
def stiff_report() -> Report:
    """The seed's side impact, centred (red's CG on blue's), with face stiffness: red's front
    B = 1e6 N/m^2 against blue's side B = 0.5e6 N/m^2 over the same 1.8 m overlap width."""
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red", stiffness=STIFF)
    blue = cs.Vehicle.box(4.6, 1.8, 1.4, mass=1500.0, name="blue", stiffness=STIFF)
    scene = cs.Scene(depth_of_penetration=DTP)
    scene.add(red, position=(-3.65, 0.0, 0.7), velocity=(cs.mph(30.0), 0.0, 0.0))
    scene.add(blue, position=(0.0, 0.0, 0.7), heading=cs.deg(90.0))
    return cs.report(scene.run(duration=0.3, dt=1e-3))


# -- deformation ------------------------------------------------------------------------------


def test_seed_example_box_deformation_is_half_the_travel(seed_report: Report) -> None:
    imp = seed_report.impacts[0]
    half = cs.mph(30.0) * DTP / 2.0
    assert imp.vehicles == ("red", "blue")
    for p in imp.parties:
        d = p.deformation
        assert d.bounding_box == pytest.approx(0.4023 / 2.0, abs=1e-3)  # the seed's figure
        # first overlap bisected to 1e-9 s: 1.3e-8 m of travel
        assert d.bounding_box == pytest.approx(half, abs=1e-7)
        assert d.mesh == pytest.approx(d.bounding_box, abs=1e-9)  # a box's mesh is its box
        assert d.mesh_crossings == 1  # the centroid is inside the box: one crossing out
        assert d.overlap_depth == pytest.approx(2.0 * half, abs=1e-7)
    red, blue = imp.parties
    assert np.allclose(red.deformation.direction, imp.normal, rtol=0.0, atol=0.0)
    assert np.allclose(blue.deformation.direction, -imp.normal, rtol=0.0, atol=0.0)


def test_seed_example_spring_model_and_residual_crush(seed_report: Report) -> None:
    imp = seed_report.impacts[0]
    total = imp.closing_speed * DTP  # the closing speed is red's 30 mph: blue is at rest
    assert imp.closing_speed == pytest.approx(cs.mph(30.0), rel=1e-12)
    for p in imp.parties:
        d = p.deformation
        assert d.crush_share_basis == "equal (stiffness unknown)" and d.crush_share == 0.5
        assert d.max_crush == pytest.approx(total / 2.0, rel=1e-12)
        # SAE 880223 inverted by hand: C_res = (C_max - 3.5 in) / 1.14
        assert d.residual_crush == pytest.approx(
            (total / 2.0 - SAE_880223_INTERCEPT) / 1.14, rel=1e-12
        )
        assert not d.residual_below_threshold
        assert any("split equally" in n for n in d.notes)


def test_residual_crush_below_three_and_a_half_inches_is_zero() -> None:
    imp = cs.report(seed_side_impact(speed=2.0)).impacts[0]
    for p in imp.parties:
        d = p.deformation
        assert d.max_crush == pytest.approx(0.5 * 2.0 * DTP, rel=1e-12)  # 0.03 m < 0.0889 m
        assert d.residual_crush == 0.0 and d.residual_below_threshold
        assert any("below 3.5 in" in n for n in d.notes)


def chamfered_red() -> cs.Vehicle:
    """A 4.5 x 1.8 x 1.4 m box whose front-left corner is cut at 45 deg: the front face
    x = 2.25 m for y <= 0.4 m, then a chamfer to (1.75, 0.9) m (model frame, CG at the box
    centre (0, 0, 0.7))."""
    points = []
    for z in (0.0, 1.4):
        points += [(-2.25, -0.9, z), (-2.25, 0.9, z), (2.25, -0.9, z), (2.25, 0.4, z)]
        points.append((1.75, 0.9, z))
    mesh = trimesh.convex.convex_hull(np.array(points))
    return cs.Vehicle(mesh, 1450.0, (0.0, 0.0, 0.7), np.diag([600.0, 2700.0, 2800.0]), "red")


def test_mesh_deformation_follows_the_surface_not_the_box() -> None:
    # a centroid fixed in red at body (1.9, 0.65, 0): along +n = +x the box's front is at
    # x = 2.25 (0.35 m away) but the chamfer crosses y = 0.65 at x = 2.25 - 0.25 = 2.0 m
    red = chamfered_red()
    blue = cs.Vehicle.box(4.6, 1.8, 1.4, mass=1500.0, name="blue")
    scene = cs.Scene(centroid=(red, (1.9, 0.65, 0.0)))
    scene.add(red, position=(-3.25, 0.0, 0.7), velocity=(cs.mph(30.0), 0.0, 0.0))
    scene.add(blue, position=(0.0, 0.0, 0.7), heading=cs.deg(90.0))
    imp = cs.report(scene.run(duration=0.2, dt=1e-3)).impacts[0]
    r, b = imp.parties
    assert np.allclose(imp.normal, [1.0, 0.0, 0.0], rtol=0.0, atol=1e-12)
    assert np.allclose(r.centroid_body, [1.9, 0.65, 0.0], rtol=0.0, atol=1e-12)
    assert r.deformation.bounding_box == pytest.approx(0.35, abs=1e-9)
    assert r.deformation.mesh == pytest.approx(0.10, abs=1e-9)
    # blue: from the centroid back to its side plane x = -0.9 m, box and mesh alike
    assert b.deformation.bounding_box == pytest.approx(imp.centroid[0] + 0.9, abs=1e-9)
    assert b.deformation.mesh == pytest.approx(b.deformation.bounding_box, abs=1e-9)


def test_mesh_deformation_is_none_when_the_ray_misses() -> None:
    # a centroid fixed beside red (body y = 1.5 m, outside its 0.9 m half width): the ray
    # along +x crosses nothing
    red = chamfered_red()
    blue = cs.Vehicle.box(4.6, 1.8, 1.4, mass=1500.0, name="blue")
    scene = cs.Scene(centroid=(red, (1.9, 1.5, 0.0)))
    scene.add(red, position=(-3.25, 0.0, 0.7), velocity=(cs.mph(30.0), 0.0, 0.0))
    scene.add(blue, position=(0.0, 0.0, 0.7), heading=cs.deg(90.0))
    report = cs.report(scene.run(duration=0.2, dt=1e-3))
    r = report.impacts[0].vehicle("red")
    assert r.deformation.mesh is None and r.deformation.mesh_crossings == 0
    assert any("no mesh deformation" in n for n in r.deformation.notes)
    assert r.deformation.bounding_box == pytest.approx(0.35, abs=1e-9)
    assert "n/a" in report.summary_table()
    jsonschema.validate(report.to_dict(), report_schema())


@pytest.mark.skipif(not SHARED_MESHES.is_dir(), reason="the shared meshes are absent")
def test_mesh_deformation_of_a_real_mesh_lies_within_its_box() -> None:
    # the farthest crossing of the mesh lies inside the mesh's own bounding box
    sedan = cs.Vehicle.from_mesh(SHARED_MESHES / "sedan_quaternius_normalcar1.ply", mass=1400.0)
    box = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="box")
    scene = cs.Scene()
    front = float(sedan.shape.aabb()[1][0])
    scene.add(sedan, position=(-0.9 - front - 0.05, 0.0, sedan.cg[2]), velocity=(13.0, 0, 0))
    scene.add(box, position=(0.0, 0.0, 0.725), heading=cs.deg(90.0))
    report = cs.report(scene.run(duration=0.2, dt=1e-3))
    assert report.impacts
    for imp in report.impacts:
        for p in imp.parties:
            d = p.deformation
            assert d.mesh is not None  # the centroid is inside both; the rays leave them
            assert d.mesh <= d.bounding_box + 1e-12
    jsonschema.validate(report.to_dict(), report_schema())


# -- delta-V, PDOF, clock ---------------------------------------------------------------------


@pytest.mark.parametrize("yaw_deg", [0.0, 37.0])
@pytest.mark.parametrize("bullet_first", [True, False], ids=["bullet-first", "target-first"])
@pytest.mark.parametrize("face", ["front", "right", "rear", "left"])
def test_pdof_and_clock_in_every_quadrant(face: str, bullet_first: bool, yaw_deg: float) -> None:
    report = cs.report(struck_on(face, bullet_first, yaw_deg))
    assert len(report.impacts) == 1
    imp = report.impacts[0]
    assert imp.vehicles == (("bullet", "target") if bullet_first else ("target", "bullet"))
    bullet, target = imp.vehicle("bullet"), imp.vehicle("target")
    assert target.struck_face == face and bullet.struck_face == "front"
    for p, (angle, hour) in ((bullet, EXPECTED["front"]), (target, EXPECTED[face])):
        assert p.pdof_deg is not None and 0.0 <= p.pdof_deg < 360.0
        assert abs(angle_difference(p.pdof_deg, angle)) < 1e-6, (p.name, p.pdof_deg)
        assert p.clock == hour
        assert abs(p.yaw_rate_change) < 1e-9  # central: no turning
    # EDR signs: a force from the right pushes left (lateral, +right, negative), ...
    sign = {"front": (-1, 0), "rear": (1, 0), "right": (0, -1), "left": (0, 1)}[face]
    for component, s in zip((target.longitudinal, target.lateral), sign, strict=True):
        if s == 0:
            assert abs(component) < 1e-9 * target.delta_v_magnitude
        else:
            assert component * s == pytest.approx(target.delta_v_magnitude, rel=1e-12)
    assert bullet.longitudinal == pytest.approx(-bullet.delta_v_magnitude, rel=1e-12)


def test_delta_v_is_impulse_over_mass_in_every_frame(seed_report: Report) -> None:
    result = seed_report.result
    for p in seed_report.impacts[0].parties:
        m = result.vehicle(p.name).mass
        assert np.allclose(p.delta_v, p.impulse / m, rtol=1e-12, atol=1e-12)
        assert np.linalg.norm(p.delta_v_body) == pytest.approx(p.delta_v_magnitude, rel=1e-12)
        assert p.lateral == -p.delta_v_body[1] and p.longitudinal == p.delta_v_body[0]
        assert not p.delta_v.flags.writeable  # read-only, as Result's arrays
        # Result.delta_v_body is an independent route to the same numbers
        imp = result.impacts[0]
        assert np.allclose(result.delta_v_body(imp, p.name), p.delta_v_body, atol=1e-12)
        assert p.speed_before == pytest.approx(np.linalg.norm(imp.velocity_before[p.name]))
        assert p.speed_after == pytest.approx(np.linalg.norm(imp.velocity_after[p.name]))


def test_centroid_in_each_body_frame(seed_report: Report) -> None:
    imp = seed_report.impacts[0]
    half = cs.mph(30.0) * DTP / 2.0
    # red (heading 0, CG at z = 0.7): its front at body x = 2.25, the centroid half behind
    assert np.allclose(imp.vehicle("red").centroid_body, [2.25 - half, 0.0, 0.0], atol=1e-7)
    # blue (heading 90 deg: body x = world y, body y = world -x; CG at z = 0.725)
    blue = imp.vehicle("blue").centroid_body
    assert np.allclose(blue, [0.3, 0.9 - half, -0.025], atol=1e-7)


def test_published_barrier_case(barrier_report: Report) -> None:
    imp = barrier_report.impacts[0]
    car, barrier = imp.parties
    assert car.longitudinal == pytest.approx(-15.972, rel=2e-3)
    assert car.lateral == pytest.approx(3.397, rel=2e-3)  # to the RIGHT
    assert car.yaw_rate_change == pytest.approx(176.43, rel=2e-3)  # counter-clockwise
    assert imp.energy_dissipated == pytest.approx(231.06e3, rel=2e-3)
    # the PDOF that follows from the published components: the force comes from -dV,
    # i.e. from ahead and to the left: 360 - atan(3.397 / 15.972) = 347.99 deg, 12 o'clock
    published = math.degrees(math.atan2(-3.397, 15.972)) % 360.0
    assert published == pytest.approx(347.993, abs=1e-3)
    assert abs(angle_difference(car.pdof_deg, published)) < 0.05  # 0.2 % of the components
    assert car.clock == 12
    # the barrier (same heading) takes the opposite impulse: its PDOF is 180 deg away
    assert abs(angle_difference(barrier.pdof_deg, car.pdof_deg + 180.0)) < 1e-9
    assert barrier.clock == 6
    assert imp.impact_type == "full"


def test_pdof_and_clock_helpers() -> None:
    assert pdof([-1.0, 0.0, 0.0]) == 0.0
    assert pdof([0.0, 1.0, 0.0]) == pytest.approx(90.0, abs=1e-12)  # pushed left: from right
    assert pdof([1.0, 0.0, 0.0]) == pytest.approx(180.0, abs=1e-12)
    assert pdof([0.0, -1.0, 0.0]) == pytest.approx(270.0, abs=1e-12)
    assert pdof([-1.0, 1.0, 5.0]) == pytest.approx(45.0, abs=1e-12)  # the vertical part aside
    tiny = pdof([-1.0, -1e-18, 0.0])  # atan2 gives -1e-18 rad: wraps to 0, never to 360
    assert tiny is not None and 0.0 <= tiny < 360.0 and min(tiny, 360.0 - tiny) < 1e-12
    assert pdof([0.0, 0.0, 2.0]) is None and clock_direction(None) is None
    table = {0.0: 12, 14.99: 12, 15.0: 1, 90.0: 3, 180.0: 6, 270.0: 9, 344.99: 11, 345.0: 12}
    for angle, hour in table.items():
        assert clock_direction(angle) == hour, angle
    with pytest.raises(cs.ParameterError):
        pdof([1.0, math.nan, 0.0])


# -- energy -----------------------------------------------------------------------------------


def test_energy_split_and_ees_by_stiffness(stiff_report: Report) -> None:
    imp = stiff_report.impacts[0]
    red, blue = imp.parties
    assert imp.energy_split_basis == "stiffness"
    k1, k2 = red.spring_rate, blue.spring_rate
    assert k1 == pytest.approx(1.0e6 * 1.8, rel=1e-12)  # k = B W, W = 1.8 m
    assert k2 == pytest.approx(0.5e6 * 1.8, rel=1e-12)
    e = imp.energy_dissipated
    assert red.energy == pytest.approx(e * k2 / (k1 + k2), rel=1e-14)  # = E / 3
    assert blue.energy == pytest.approx(e * k1 / (k1 + k2), rel=1e-14)  # = 2 E / 3
    assert red.energy + blue.energy == pytest.approx(e, rel=1e-12)
    for p in imp.parties:
        assert p.ees == pytest.approx(math.sqrt(2.0 * p.energy / p.mass), rel=1e-14)
    # the spring model with the same shares: k1 C1 = k2 C2 and C1 + C2 = v_n dt_p
    c1, c2 = red.deformation.max_crush, blue.deformation.max_crush
    assert k1 * c1 == pytest.approx(k2 * c2, rel=1e-12)
    assert c1 + c2 == pytest.approx(imp.closing_speed * DTP, rel=1e-12)
    assert imp.series_stiffness == pytest.approx(k1 * k2 / (k1 + k2), rel=1e-12)
    assert imp.implied_depth_of_penetration == pytest.approx(
        math.sqrt(imp.reduced_mass / imp.series_stiffness), rel=1e-14
    )


def test_stiffness_placed_centroid_makes_box_deformation_the_spring_model_crush() -> None:
    # centroid="stiffness" moves P along n so that the crush splits C1 : C2 = k2 : k1; for
    # boxes the bounding-box deformations are then the spring model's maximum crush
    # (eqs. 34-35) as the report computes it from v_n dt_p
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red", stiffness=STIFF)
    blue = cs.Vehicle.box(4.6, 1.8, 1.4, mass=1500.0, name="blue", stiffness=STIFF)
    scene = cs.Scene(depth_of_penetration=DTP, centroid="stiffness")
    scene.add(red, position=(-3.65, 0.0, 0.7), velocity=(cs.mph(30.0), 0.0, 0.0))
    scene.add(blue, position=(0.0, 0.0, 0.7), heading=cs.deg(90.0))
    imp = cs.report(scene.run(duration=0.3, dt=1e-3)).impacts[0]
    red_part, blue_part = imp.parties
    assert red_part.deformation.max_crush == pytest.approx(cs.mph(30.0) * DTP / 3.0, rel=1e-12)
    for p in imp.parties:
        assert p.deformation.bounding_box == pytest.approx(p.deformation.max_crush, abs=1e-7)


def test_equal_stiffness_splits_equally() -> None:
    same = {"front": (35000.0, 0.7e6), "rear": (35000.0, 0.7e6), "side": (35000.0, 0.7e6)}
    imp = cs.report(seed_side_impact(stiffness=same)).impacts[0]
    red, blue = imp.parties
    assert red.spring_rate == blue.spring_rate
    assert red.energy == blue.energy == pytest.approx(imp.energy_dissipated / 2.0, rel=1e-15)
    assert red.energy + blue.energy == pytest.approx(imp.energy_dissipated, rel=1e-12)
    assert red.deformation.max_crush == blue.deformation.max_crush
    assert red.deformation.crush_share_basis == "stiffness"


def test_unknown_stiffness_is_never_split(seed_report: Report) -> None:
    imp = seed_report.impacts[0]
    assert imp.energy_split_basis == "unknown" and imp.series_stiffness is None
    for p in imp.parties:
        assert p.energy is None and p.ees is None and p.spring_rate is None
    assert any("not split" in n for n in imp.notes)


def test_dissipated_energy_is_the_kinetic_energy_lost(seed_report: Report) -> None:
    # independent bookkeeping: translational and rotational kinetic energy of both vehicles
    imp = seed_report.impacts[0]
    change = sum(p.translational_energy_change + p.rotational_energy_change for p in imp.parties)
    assert -change == pytest.approx(imp.energy_dissipated, rel=1e-9)
    assert imp.vehicle("blue").rotational_energy_change > 0.0  # struck off its CG: it turns


def test_automatic_depth_of_penetration_is_reported() -> None:
    imp = cs.report(seed_side_impact(stiffness=STIFF, depth_of_penetration="auto")).impacts[0]
    assert imp.depth_of_penetration_mode == "auto"
    assert "sqrt(m'/k')" in imp.how_depth_of_penetration
    # the engine lands the exchange to 1e-9 s; its dt_p is sqrt(m'/k') at that instant
    assert imp.depth_of_penetration == pytest.approx(imp.implied_depth_of_penetration, abs=2e-9)


# -- JSON -------------------------------------------------------------------------------------


def walk(value: Any) -> list[Any]:
    """Every leaf of a JSON-like value."""
    if isinstance(value, dict):
        return [leaf for v in value.values() for leaf in walk(v)]
    if isinstance(value, list):
        return [leaf for v in value for leaf in walk(v)]
    return [value]


@pytest.mark.parametrize("which", ["seed", "stiff", "barrier"])
def test_json_validates_and_round_trips(which: str, request: pytest.FixtureRequest) -> None:
    report: Report = request.getfixturevalue(f"{which}_report")
    schema = report_schema()
    jsonschema.Draft202012Validator.check_schema(schema)
    d = report.to_dict()
    jsonschema.Draft202012Validator(schema).validate(d)
    assert d["schema"] == "crashsim-report" and d["schema_version"] == SCHEMA_VERSION == 1
    assert d["crashsim_version"] == cs.__version__
    assert json.loads(json.dumps(d, allow_nan=False)) == d
    for leaf in walk(d):  # plain Python only, no numpy scalars
        assert leaf is None or type(leaf) in (str, bool, int, float), type(leaf)
    # a corrupted report fails: the schema is not vacuous
    for corrupt in ("version", "pdof", "face"):
        bad = copy.deepcopy(d)
        if corrupt == "version":
            bad["schema_version"] = 2
        elif corrupt == "pdof":
            bad["impacts"][0]["parties"][0]["pdof_deg"] = 360.0
        else:
            bad["impacts"][0]["struck_faces"][bad["impacts"][0]["vehicles"][0]] = "roof"
        with pytest.raises(jsonschema.ValidationError):
            jsonschema.validate(bad, schema, cls=jsonschema.Draft202012Validator)


def test_json_holds_the_impact_figures(stiff_report: Report) -> None:
    d = stiff_report.to_dict()
    imp = stiff_report.impacts[0]
    j = d["impacts"][0]
    assert j["exchange_time"] == imp.exchange_time
    assert j["energy"]["dissipated"] == imp.energy_dissipated
    for jp, p in zip(j["parties"], imp.parties, strict=True):
        assert jp["name"] == p.name and jp["pdof_deg"] == p.pdof_deg and jp["clock"] == p.clock
        assert jp["delta_v"]["lateral"] == p.lateral
        assert jp["energy"]["share"] == p.energy and jp["energy"]["ees"] == p.ees
        assert jp["deformation"]["bounding_box"] == p.deformation.bounding_box
    assert d["units"]["velocity"] == "m/s" and d["units"]["yaw_rate_change"] == "deg/s"


def test_write_json(tmp_path, seed_report: Report) -> None:
    path = tmp_path / "report.json"
    seed_report.write_json(path)
    assert json.loads(path.read_text(encoding="utf-8")) == seed_report.to_dict()


def test_the_json_inputs_reproduce_the_run(barrier_report: Report) -> None:
    """Rebuild the scene from the JSON alone (meshes included) and run it again."""
    d = json.loads(barrier_report.to_json(include_meshes=True))
    jsonschema.validate(d, report_schema(), cls=jsonschema.Draft202012Validator)
    vehicles = {}
    for v in d["scene"]["vehicles"]:
        mesh = trimesh.Trimesh(
            v["mesh"]["vertex_positions"], v["mesh"]["face_indices"], process=False
        )
        stiffness = {f: s for f, s in v["stiffness"].items() if s is not None}
        vehicles[v["name"]] = cs.Vehicle(
            mesh, v["mass"], v["cg_model"], v["inertia"], v["name"], stiffness=stiffness
        )
    scene = cs.Scene(**d["scene"]["contact"]["defaults"])
    for v in d["scene"]["vehicles"]:
        s = v["initial_state"]
        scene.add(
            vehicles[v["name"]],
            position=s["position"],
            orientation=s["orientation"],
            velocity=s["velocity"],
            angular_velocity=s["angular_velocity"],
        )
    for pair in d["scene"]["contact"]["pairs"]:
        scene.contact(*pair["vehicles"], **pair["parameters"])
    again = cs.report(scene.run(duration=d["run"]["end_time"], dt=1e-3))
    assert len(again.impacts) == len(barrier_report.impacts) == 1
    a, b = again.impacts[0], barrier_report.impacts[0]
    assert a.exchange_time == pytest.approx(b.exchange_time, abs=1e-12)
    for pa, pb in zip(a.parties, b.parties, strict=True):
        assert np.allclose(pa.delta_v, pb.delta_v, rtol=0.0, atol=1e-12)


# -- the text table ---------------------------------------------------------------------------


def table_rows(text: str, header_cell: str) -> list[dict[str, str]]:
    """The rows of every table in `text` whose header holds `header_cell`, as dicts."""
    lines = text.splitlines()
    rows = []
    for i, line in enumerate(lines):
        if header_cell not in line or "|" not in line:
            continue
        headers = [c.strip() for c in line.split("|")]
        for row in lines[i + 2 :]:  # after the rule line
            if "|" not in row:
                break
            rows.append(dict(zip(headers, (c.strip() for c in row.split("|")), strict=True)))
    return rows


def test_text_table_holds_the_numbers(stiff_report: Report, seed_report: Report) -> None:
    text = str(stiff_report)
    assert text == stiff_report.summary_table()
    imp = stiff_report.impacts[0]
    kinematics = {r["Vehicle"]: r for r in table_rows(text, "PDOF (deg)")}
    energy = {r["Vehicle"]: r for r in table_rows(text, "EES (m/s)")}
    speeds = {r["Vehicle"]: r for r in table_rows(text, "v before (mph)")}
    assert set(kinematics) == set(energy) == set(speeds) == {"red", "blue"}
    for p in imp.parties:
        row = kinematics[p.name]
        assert float(row["dV (m/s)"]) == pytest.approx(p.delta_v_magnitude, abs=5e-4)
        assert float(row["dV (km/h)"]) == pytest.approx(p.delta_v_magnitude * 3.6, abs=5e-3)
        assert float(row["dV (mph)"]) == pytest.approx(p.delta_v_magnitude / 0.44704, abs=5e-3)
        assert float(row["dV long (m/s)"]) == pytest.approx(p.longitudinal, abs=5e-4)
        assert float(row["dV lat (m/s)"]) == pytest.approx(p.lateral, abs=5e-4)
        assert float(row["PDOF (deg)"]) == pytest.approx(p.pdof_deg, abs=5e-3)
        assert int(row["Clock"]) == p.clock
        row = energy[p.name]
        assert float(row["Energy (J)"]) == pytest.approx(p.energy, abs=0.05)
        assert float(row["EES (m/s)"]) == pytest.approx(p.ees, abs=5e-4)
        assert float(row["Box def. (m)"]) == pytest.approx(p.deformation.bounding_box, abs=5e-5)
        assert float(row["C max (m)"]) == pytest.approx(p.deformation.max_crush, abs=5e-5)
        assert float(speeds[p.name]["v before (mph)"]) == pytest.approx(
            p.speed_before / 0.44704, abs=5e-3
        )
    assert f"{imp.energy_dissipated:.1f} J" in text
    assert "30.000 ms (fixed" in text
    # 30 mph before: the field's units in the speeds table
    assert speeds["red"]["v before (mph)"] == "30.00"
    assert speeds["red"]["v before (km/h)"] == "48.28"
    # round-off is not a direction: the centred impact's zero components print unsigned
    assert kinematics["red"]["dV lat (m/s)"] == "0.000"
    assert kinematics["red"]["PDOF (deg)"] == "0.00" and "-0.000" not in text
    unknown = {r["Vehicle"]: r for r in table_rows(str(seed_report), "EES (m/s)")}
    assert unknown["red"]["Energy (J)"] == "unknown" and unknown["blue"]["EES (m/s)"] == "unknown"


def test_report_needs_the_scene(seed_report: Report) -> None:
    bare = copy.copy(seed_report.result)
    bare.scene = None
    with pytest.raises(SceneError, match="no scene"):
        build_report(bare)


def test_a_run_without_impacts_reports_none() -> None:
    a = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1400.0, name="a")
    b = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1400.0, name="b")
    scene = cs.Scene()
    scene.add(a, position=(0.0, 0.0, 0.7), velocity=(1.0, 0.0, 0.0))
    scene.add(b, position=(0.0, 10.0, 0.7))
    report = cs.report(scene.run(duration=0.1, dt=1e-2))
    assert report.impacts == [] and "No impulse exchange" in str(report)
    jsonschema.validate(report.to_dict(), report_schema(), cls=jsonschema.Draft202012Validator)


# -- engagements: secondary exchanges grouped, overlaps without an exchange stated -------------


@pytest.fixture(scope="module")
def three_vehicles() -> Report:
    from conftest import REPO
    from crashsim.io.scenefile import load_scene

    return cs.report(load_scene(REPO / "examples" / "three-vehicles.toml").simulate())


def test_three_vehicles_secondary_exchanges_grouped_with_summed_delta_v(
    three_vehicles: Report,
) -> None:
    # Was: six exchanges listed one after another, four of them small re-contacts, unexplained.
    report = three_vehicles
    impacts = report.result.impacts
    assert len(impacts) == 6 and sum(i.secondary for i in impacts) == 4
    groups = {e.vehicles: e for e in report.engagements}
    assert set(groups) == {("red", "blue"), ("blue", "green")}
    red_blue = groups[("red", "blue")]
    assert (red_blue.primary, red_blue.secondary) == (0, (2, 4))
    assert groups[("blue", "green")].exchanges == (1, 3, 5)
    for e in report.engagements:
        for name in e.vehicles:
            total = sum(impacts[i].delta_v[name] for i in e.exchanges)
            assert np.allclose(e.delta_v[name], total, rtol=0, atol=1e-12)
        assert e.energy_dissipated == pytest.approx(
            sum(impacts[i].energy_dissipated for i in e.exchanges), rel=1e-12
        )
    # impact 3 (red-blue) closed again at the instant impact 2 (blue-green) changed blue
    assert abs(impacts[2].first_contact_time - impacts[1].time) < 1e-6
    assert red_blue.causes[2].startswith("impact 2 (blue-green) at 0.148892 s changed blue's")
    # impact 4 (blue-green) closed again at no other exchange: the rotation
    assert all(abs(impacts[3].first_contact_time - o.time) > 1e-6 for o in impacts)
    assert "rotated" in groups[("blue", "green")].causes[3]
    text = str(report)
    assert "Contacts by pair" in text and "Why secondary exchanges:" in text
    assert "impact 1 (primary) and secondary 3 and 5" in text
    assert "Impact 3: red (1) -> blue (2) [secondary to impact 1], full impact" in text
    dv = float(np.linalg.norm(red_blue.delta_v["red"]))
    assert f"summed delta-V (vector sum over its 3 exchange(s)): red {dv:.3f} m/s" in text
    data = report.to_dict()
    jsonschema.validate(data, report_schema(), cls=jsonschema.Draft202012Validator)
    first = data["engagements"][0]
    assert (first["vehicles"], first["primary"], first["secondary"]) == (["red", "blue"], 1, [3, 5])
    assert first["secondary_causes"][0]["impact"] == 3 and first["exchanged"] is True
    assert first["delta_v"]["magnitude"]["red"] == pytest.approx(dv, rel=1e-12)
    assert "secondary exchange" in data["conventions"]["engagements"]


def graze(speed: float = 40.0) -> cs.Result:
    """Red slides sideways past blue's rear 1 cm deep at ``speed`` m/s: the faces that meet
    are parallel to the motion, so at the timer's end the vehicles are not approaching along
    the normal and no impulse is exchanged; they separate 90 ms after the first overlap."""
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene(depth_of_penetration=0.060)
    scene.add(red, position=(-2.3 - 2.25 + 0.01, -3.0, 0.7), velocity=(0.0, speed, 0.0))
    scene.add(blue, position=(0.0, 0.0, 0.725))
    return scene.run(duration=0.3, dt=1e-3)


def test_first_overlap_without_an_exchange_is_stated_in_text_and_json() -> None:
    result = graze()
    assert [c.kind for c in result.contacts] == ["first_overlap", "no_exchange", "separation"]
    report = cs.report(result)
    (e,) = report.engagements
    assert not e.exchanged and e.primary is None
    assert e.separation_time == pytest.approx(0.12)
    text = str(report)
    assert "No impulse exchange in this run." in text
    assert "red-blue: first overlap at 0.030000 s, separated at 0.120000 s" in text
    assert (
        "NO EXCHANGE: the overlap that began at 0.030000 s ended without an impulse (timer end "
        "0.090000 s: the vehicles are not approaching at the centroid along the normal"
    ) in text
    data = report.to_dict()
    jsonschema.validate(data, report_schema(), cls=jsonschema.Draft202012Validator)
    (record,) = data["engagements"]
    assert record["exchanged"] is False and record["primary"] is None
    (no_exchange,) = record["no_exchange"]
    assert no_exchange["time"] == pytest.approx(0.09)
    assert no_exchange["reason"].startswith(
        "the vehicles are not approaching at the centroid along the normal"
    )
    assert record["delta_v"]["magnitude"] == {"red": 0.0, "blue": 0.0}


def test_a_single_exchange_keeps_the_short_text_and_gets_one_engagement(
    seed_report: Report,
) -> None:
    assert "Contacts by pair" not in str(seed_report)
    (record,) = seed_report.to_dict()["engagements"]
    assert (record["primary"], record["secondary"], record["exchanged"]) == (1, [], True)


def test_a_report_without_engagements_still_validates(seed_report: Report) -> None:
    # the field is optional: reports written before it existed stay valid
    data = seed_report.to_dict()
    del data["engagements"]
    jsonschema.validate(data, report_schema(), cls=jsonschema.Draft202012Validator)


# -- the impact's figures (ImpactReport.figures) ----------------------------------------------


def oblique(friction: float, restitution: float = 0.1) -> cs.Result:
    """Red at 20 m/s into blue's side while blue moves at 10 m/s along its own axis: sliding
    at low friction, sticking (a full impact) at high."""
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene(depth_of_penetration=0.030, friction=friction, restitution=restitution)
    scene.add(red, position=(-3.65, 0.3, 0.7), velocity=(20.0, 0.0, 0.0))
    scene.add(blue, position=(0.0, 0.0, 0.725), heading=math.pi / 2, velocity=(0.0, 10.0, 0.0))
    return scene.run(0.3, 1e-3)


@pytest.mark.parametrize("friction", [0.05, 0.1, 0.2])
def test_a_sliding_impacts_impulse_ratio_is_the_friction(friction: float) -> None:
    (imp,) = cs.report(oblique(friction)).impacts
    assert imp.impact_type == "sliding"
    assert imp.impulse_ratio == pytest.approx(friction, abs=1e-12)
    assert imp.restitution_along_normal == pytest.approx(0.1, abs=1e-12)


@pytest.mark.parametrize("restitution", [0.0, 0.1, 0.4])
def test_a_full_impact_ends_at_minus_e_times_its_normal_closing_speed(restitution: float) -> None:
    (imp,) = cs.report(oblique(0.6, restitution)).impacts
    assert imp.impact_type == "full"
    assert imp.restitution_along_normal == pytest.approx(restitution, abs=1e-12)
    assert 0.0 < imp.impulse_ratio < 0.6


def test_the_figures_are_in_the_text_and_the_json_with_their_labels() -> None:
    report = cs.report(oblique(0.2))
    (imp,) = report.impacts
    data = report.to_dict()
    jsonschema.validate(data, report_schema(), cls=jsonschema.Draft202012Validator)
    figures = data["impacts"][0]["figures"]
    assert [f["name"] for f in figures] == ["restitution_along_normal", "impulse_ratio"]
    assert figures[1]["value"] == imp.impulse_ratio
    text = str(report)
    for f in figures:
        assert f"  {f['label']}: {f['value']:.{f['digits']}f}" in text


def test_a_figure_declared_on_the_model_alone_reaches_the_text_and_the_json() -> None:
    """The contract of ``figure``: one declared field shows in every view without their code
    knowing it (report_text.py and report.js render ImpactReport.figures)."""
    from dataclasses import dataclass, fields

    from crashsim.analysis.impact_report import ImpactReport, figure

    @dataclass(frozen=True)
    class WithOneMore(ImpactReport):
        common_speed: float | None = figure("a new figure", "m/s", 2)

    report = cs.report(oblique(0.2))
    (imp,) = report.impacts
    more = WithOneMore(**{f.name: getattr(imp, f.name) for f in fields(imp)}, common_speed=None)
    assert more.figures()[-1] == {
        "name": "common_speed", "label": "a new figure", "unit": "m/s", "digits": 2,
        "value": None,
    }  # fmt: skip
    assert more.to_dict()["figures"][-1]["name"] == "common_speed"
    object.__setattr__(report, "impacts", (more,))
    assert "  a new figure: n/a m/s" in str(report)
