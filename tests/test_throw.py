"""Throw distance (crashsim.analysis.throw, docs/human.md "Throw distance"): the published
corridors' formulas checked against the mechanics they state, and one strike end to end."""

from __future__ import annotations

import math
import warnings

import crashsim as cs
import numpy as np
import pytest
from crashsim.analysis.pedestrian import whole_body
from crashsim.analysis.throw import (
    VKU_FRICTION,
    VKU_THROW_FACTORS,
    G,
    first_contact_time,
    plan_path_type,
    searle_distance,
    searle_speed,
    throw_distance,
    trajectory_type,
    vku_throw_distance,
)
from crashsim.errors import ParameterError


def projected(v: float, theta: float, mu: float) -> float:
    """Searle's model stepped through by hand: a point launched from the road at v (m/s),
    theta rad up, flies v^2 sin(2 theta) / g, lands (the road's normal impulse m v sin theta
    takes up to mu times it off the horizontal speed), then slides to rest at mu g."""
    flight = v * v * math.sin(2.0 * theta) / G
    after = v * math.cos(theta) - mu * v * math.sin(theta)
    return flight + after * after / (2.0 * mu * G)


@pytest.mark.parametrize("mu", [0.45, 0.66, 1.0])
def test_searle_bounds_are_the_extremes_of_the_launch_angle(mu: float) -> None:
    # Searle's bounds: the horizontal launch throws least, tan(theta) = mu throws furthest,
    # over the launch angles up to 2 atan(mu) (beyond, cos + mu sin < 1) while the point
    # still slides after landing (theta below atan(1 / mu))
    v = 15.0
    thetas = np.linspace(0.0, min(2.0 * math.atan(mu), math.atan(1.0 / mu)), 20001)
    s = np.array([projected(v, th, mu) for th in thetas])
    s_min, s_max = searle_distance(v, mu)
    assert s.min() == pytest.approx(s_min, rel=1e-12)
    assert s.max() == pytest.approx(s_max, rel=1e-8)
    assert thetas[s.argmax()] == pytest.approx(math.atan(mu), abs=1e-4)
    # v^2 / (2 mu g): 15 m/s on mu 0.45 slides 25.49 m
    assert searle_distance(15.0, 0.45)[0] == pytest.approx(225.0 / (0.9 * G), rel=1e-15)


def test_searle_speed_inverts_the_distance() -> None:
    for s in (5.0, 20.0, 40.0):
        v_lo, v_hi = searle_speed(s, 0.7)
        assert searle_distance(v_hi, 0.7)[0] == pytest.approx(s, rel=1e-14)
        assert searle_distance(v_lo, 0.7)[1] == pytest.approx(s, rel=1e-14)
        assert v_hi / v_lo == pytest.approx(math.sqrt(1.49), rel=1e-14)


def test_vku_throw_factor_is_searles_minimum_speed_over_the_impact_speed() -> None:
    # the 1997 article's definition: f_w = v_min / v_k, v_min Searle's minimum projection
    # speed for the throw distance, with its adults' factors 64 % and 74.4 % at mu 0.66
    assert VKU_THROW_FACTORS == {"low front": 0.64, "high front": 0.744}
    assert VKU_FRICTION == 0.66
    v = cs.kmh(50.0)
    for front, f in VKU_THROW_FACTORS.items():
        s = vku_throw_distance(v, front)
        assert searle_speed(s, 0.66)[0] / v == pytest.approx(f, rel=1e-14)
    # 50 km/h, high front: (0.744 * 13.889)^2 (1 + 0.66^2) / (2 0.66 g) = 11.842 m
    assert vku_throw_distance(v, "high front") == pytest.approx(11.842, abs=5e-4)


def test_bad_input() -> None:
    with pytest.raises(ParameterError, match="mu must be"):
        searle_distance(10.0, 0.0)
    with pytest.raises(ParameterError, match="speed must be"):
        searle_distance(-1.0, 0.5)
    with pytest.raises(ParameterError, match="speed must be"):
        searle_speed(float("nan"), 0.5)
    with pytest.raises(ParameterError, match="front = 'bus' is unknown"):
        vku_throw_distance(10.0, "bus")


def strike(
    speed_kmh: float, duration: float, gap: float = 0.05, vehicle: cs.Vehicle | None = None
):
    """benches/pedestrian_throw.py's scene: a braking sedan (or ``vehicle``, named "car")
    into a walking man's left side."""
    car = cs.Vehicle.generate("sedan", name="car") if vehicle is None else vehicle
    ped = cs.Pedestrian(height=1.75, mass=75.0, pose="walking")
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    ahead = float(car.mesh.bounds[1, 0] - car.cg[0])
    scene.add(car, (0.0, 0.0), heading=0.0, velocity=(cs.kmh(speed_kmh), 0.0, 0.0),
              inputs=cs.DriverInputs(brake=[(0.0, 1.0), (duration, 1.0)]))
    scene.add(ped, (ahead + gap + float(ped.vertices()[:, 1].max()), 0.0), heading=np.pi / 2)
    for seg in ped.segments:
        scene.contact(car, seg, depth_of_penetration=0.0, restitution=0.1, friction=0.3,
                      normal="volume")
    scene.soft_contact(car, ped, stiffness=1e5, damping_ratio=0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cs.DepthOfPenetrationWarning)
        return ped, scene.run(duration, dt=2e-4, record_interval=2e-3)


def test_a_30_kmh_strike_lands_inside_the_corridors() -> None:
    # about 5 s of wall time: 3.3 s simulated at 0.2 ms steps
    ped, result = strike(30.0, 3.3)
    s = throw_distance(result, "car", ped)
    pelvis = result.trajectory("pedestrian/pelvis")
    assert np.linalg.norm(pelvis.velocity[-1]) < 0.1  # at rest (m/s)
    v = cs.kmh(30.0)
    # the widest corridor drawn: from the 1997 low-front relation (mu 0.66: 3.2 m) to
    # Searle's maximum at the engine's body-ground friction 0.45 (9.4 m)
    assert vku_throw_distance(v, "low front") < s < searle_distance(v, 0.45)[1]
    # the whole-body CG: the segments' CGs weighted by mass, here at the end
    t, cg, _ = whole_body(result, ped)
    weighted = sum(seg.mass * result.trajectory(seg.name).position[-1] for seg in ped.segments)
    np.testing.assert_allclose(cg[-1], weighted / 75.0, rtol=0, atol=1e-12)
    assert 0.0 < first_contact_time(result, "car", ped) < 0.02
    # over the bonnet and off the front of the stopped car: Ravani et al.'s wrap
    assert trajectory_type(result, cs.Vehicle.generate("sedan", name="car"), ped) == "wrap"


def test_a_flat_truck_front_projects_the_person_forward() -> None:
    # the laden rigid truck's cab front at 30 km/h: the whole-body CG never gets over its plan
    truck = cs.rigid_truck("rigid_truck", name="car")
    ped, result = strike(30.0, 1.0, vehicle=truck)
    assert trajectory_type(result, truck, ped) == "forward projection"
    assert throw_distance(result, "car", ped) > 1.0  # pushed ahead, not run over


# (rear, front), (right, left) of a 4 m x 1.8 m plan
PLAN = ((-2.0, 2.0), (-0.9, 0.9))


@pytest.mark.parametrize(
    ("path", "kind"),
    [
        ([(2.5, 0.0), (2.2, 0.1), (2.1, 0.0)], "forward projection"),  # pushed ahead
        ([(2.5, 0.0), (1.0, 0.0), (-1.0, 0.0), (1.5, 0.0), (2.5, 0.0)], "wrap"),
        ([(2.5, 0.0), (1.0, 0.0), (-1.9, 0.0), (-2.5, 0.0)], "roof vault"),
        ([(2.5, 0.0), (1.0, 0.5), (0.5, 1.2), (0.0, 2.0)], "fender vault"),
        ([(2.5, 0.0), (1.0, -0.5), (0.5, -1.2)], "fender vault"),  # over the right side
        ([(2.5, 0.0), (1.0, 0.0), (0.0, 0.0)], "carried"),
        # the last way off counts: over a side in the air, back on, then off the front
        ([(2.5, 0.0), (1.0, 0.5), (0.5, 1.2), (0.5, 0.5), (2.5, 0.0)], "wrap"),
        ([(2.5, 0.0), (1.0, 0.0), (2.5, 0.0), (1.0, 0.0), (-2.5, 0.0)], "roof vault"),
        ([(2.5, 0.0), (1.0, 0.0), (2.5, 0.0), (1.0, 0.0)], "carried"),
    ],
)
def test_the_path_over_the_plan_names_the_type(path: list, kind: str) -> None:
    assert plan_path_type(np.array(path, dtype=float), *PLAN) == kind


def test_no_contact_no_throw_distance() -> None:
    ped, result = strike(30.0, 0.01, gap=1.0)
    with pytest.raises(ParameterError, match="never touched"):
        throw_distance(result, "car", ped)
