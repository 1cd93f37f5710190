"""Scenes through the Python API: the seed's examples, closed forms, the published barrier
case, errors, determinism and the demo command."""

import math
import subprocess
import sys

import crashsim as cs
import numpy as np
import pytest


def side_impact(speed, angle_deg, offset, dt, dtp=0.030):
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    a = math.radians(angle_deg)
    scene = cs.Scene(depth_of_penetration=dtp)
    scene.add(
        red,
        position=(-4.0, offset, 0.7),
        heading=a,
        velocity=(speed * math.cos(a), speed * math.sin(a), 0.0),
    )
    scene.add(blue, position=(0.0, 0.0, 0.725), heading=math.radians(90.0))
    return scene.run(duration=0.3, dt=dt)


@pytest.mark.parametrize("dt", [1e-3, 7e-3])
@pytest.mark.parametrize(
    "speed_mph, angle, offset, travel",
    [(30.0, 0.0, 0.0, 0.4023), (60.0, 45.0, -3.0, 0.8047)],  # 1.32 ft and 2.64 ft
)
def test_seed_worked_examples(dt, speed_mph, angle, offset, travel):
    result = side_impact(cs.mph(speed_mph), angle, offset, dt)
    imp = result.impacts[0]
    p0 = result.state_at("red", imp.first_contact_time)["position"]
    p1 = result.state_at("red", imp.time)["position"]
    assert np.linalg.norm(p1 - p0) == pytest.approx(travel, abs=1e-3)
    assert imp.time - imp.first_contact_time == pytest.approx(0.030, abs=1e-12)
    assert imp.vehicles == ("red", "blue")


def test_box_into_box_side_normal_and_centroid():
    result = side_impact(cs.mph(30.0), 0.0, 0.3, 1e-3)
    imp = result.impacts[0]
    assert np.linalg.norm(imp.normal - [1.0, 0.0, 0.0]) < 1e-6
    depth = cs.mph(30.0) * 0.030
    assert np.linalg.norm(imp.centroid - [-0.9 + depth / 2, 0.3, 0.7]) < 1e-6


@pytest.mark.parametrize("eps", [0.0, 0.1, 0.5])
def test_central_collinear_impact_matches_the_closed_form(eps):
    m1, m2, v = 1450.0, 1800.0, 15.0
    a = cs.Vehicle.box(4.0, 1.8, 1.4, mass=m1, name="a")
    b = cs.Vehicle.box(4.6, 1.7, 1.3, mass=m2, name="b", ground_clearance=0.05)
    # b's CG at the same height as a's: a central impact
    scene = cs.Scene(restitution=eps)
    scene.add(a, position=(0.0, 0.0, 0.7), velocity=(v, 0.0, 0.0))
    scene.add(b, position=(4.5, 0.0, 0.7))
    imp = scene.run(duration=0.2, dt=1e-3).impacts[0]
    dv1 = np.linalg.norm(imp.delta_v["a"])
    expected = (1 + eps) * m2 / (m1 + m2) * v
    assert dv1 == pytest.approx(expected, rel=1e-9)
    total = m1 * imp.velocity_after["a"] + m2 * imp.velocity_after["b"]
    assert np.allclose(total, [m1 * v, 0, 0], rtol=1e-12, atol=1e-9)


def test_published_barrier_case():
    """reference-cases.md section 2 (Carpenter et al., SAE 2019-01-0422 method)."""
    m, izz = 1621.2, 3167.5
    car = cs.Vehicle.box(4.8, 1.8, 1.45, mass=m, name="fusion")
    car.inertia = np.diag([600.0, 2900.0, izz])
    barrier = cs.Vehicle.box(1.0, 6.0, 2.0, mass=cs.lb(1e7), name="barrier")
    barrier.inertia = np.eye(3) * 1e12
    scene = cs.Scene()
    scene.add(car, position=(0.0, 0.0, 0.6), velocity=(17.8613, 0.0, 0.0))
    scene.add(barrier, position=(3.0, 0.0, 1.0))
    a = math.radians(15.4)
    scene.contact(
        car,
        barrier,
        restitution=0.0,
        friction=0.82,
        centroid=(car, (1.1037, 0.6118, 0.0)),
        normal=(math.cos(a), math.sin(a), 0.0),
    )
    imp = scene.run(duration=0.1, dt=1e-3).impacts[0]
    assert not imp.sliding
    dv = imp.delta_v["fusion"]
    dyaw = math.degrees(imp.delta_omega["fusion"][2])
    # The planar closed form of the same inputs (immovable barrier): J = K^-1 u.
    r = np.array([1.1037, 0.6118])
    k = np.array(
        [
            [1 / m + r[1] ** 2 / izz, -r[0] * r[1] / izz],
            [-r[0] * r[1] / izz, 1 / m + r[0] ** 2 / izz],
        ]
    )
    j = np.linalg.solve(k, [17.8613, 0.0])
    assert dv[:2] == pytest.approx(-j / m, rel=1e-3)
    # Published: -15.972 m/s, 3.397 m/s to the right (ISO y -), +176.43 deg/s, 231.06 kJ.
    assert dv[0] == pytest.approx(-15.972, rel=2e-3)
    assert dv[1] == pytest.approx(-3.397, rel=2e-3)
    assert dyaw == pytest.approx(176.43, rel=2e-3)
    assert imp.energy_dissipated == pytest.approx(231.06e3, rel=2e-3)


def test_the_same_scene_twice_gives_the_same_bits():
    r1 = side_impact(cs.mph(60.0), 40.0, -2.5, 1e-3)
    r2 = side_impact(cs.mph(60.0), 40.0, -2.5, 1e-3)
    for name in ("red", "blue"):
        for a, b in zip(r1.trajectory(name), r2.trajectory(name), strict=True):
            assert np.array_equal(a, b)
    assert r1.to_dict() == r2.to_dict()


@pytest.mark.parametrize(
    "params, match",
    [
        ({"depth_of_penetration": 0.07}, "depth_of_penetration"),
        ({"depth_of_penetration": -0.01}, "depth_of_penetration"),
        ({"restitution": 1.5}, "restitution"),
        ({"friction": -0.1}, "friction"),
        ({"friction": float("nan")}, "friction"),
        ({"restitution_mode": "bouncy"}, "restitution_mode"),
    ],
)
def test_bad_contact_parameters_are_parameter_errors(params, match):
    a = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="a")
    b = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="b")
    scene = cs.Scene()
    scene.add(a, position=(0, 0, 0.7)).add(b, position=(10, 0, 0.7))
    scene.contact(a, b, **params)
    with pytest.raises(cs.ParameterError, match=match):
        scene.run(0.1)


def test_bad_states_and_scenes_are_typed_errors():
    a = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="a")
    scene = cs.Scene()
    with pytest.raises(cs.ParameterError, match="velocity"):
        scene.add(a, position=(0, 0, 0.7), velocity=(float("nan"), 0, 0))
    with pytest.raises(cs.ParameterError, match="position"):
        scene.add(a, position=(0, 0))
    scene.add(a, position=(0, 0, 0.7))
    with pytest.raises(cs.SceneError, match="already"):
        scene.add(a, position=(5, 0, 0.7))
    with pytest.raises(cs.SceneError, match="not in the scene"):
        scene.contact(a, "ghost")
    with pytest.raises(cs.ParameterError, match="dt"):
        scene.run(0.1, dt=0.0)


def test_vehicles_overlapping_at_the_start_raise():
    a = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="a")
    b = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="b")
    scene = cs.Scene()
    scene.add(a, position=(0, 0, 0.7)).add(b, position=(3.0, 0.5, 0.7), heading=0.3)
    with pytest.raises(cs.InitialOverlapError, match="overlap"):
        scene.run(0.1)


def test_demo_command_prints_the_seed_figure():
    out = subprocess.run(
        [sys.executable, "-m", "crashsim", "demo"],
        capture_output=True,
        text=True,
        check=True,
        timeout=120,
    )
    assert "0.4023 m = 1.320 ft" in out.stdout
    assert "delta-V red" in out.stdout
